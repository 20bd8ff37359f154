# Tests of geometry/src/surface

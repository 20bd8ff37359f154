# Tests of geometry/src/terrain

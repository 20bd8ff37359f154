# Tests of geometry/src/fog

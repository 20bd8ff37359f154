# Tests of geometry/src/terrain
kiri_test(terrain_test SOURCES terrain_test.cpp LIBS kiri_geometry LABELS unit)

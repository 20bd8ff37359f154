# Tests of geometry/src/surface
kiri_test(gregory_patch_test SOURCES gregory_patch_test.cpp LIBS kiri_geometry LABELS unit)

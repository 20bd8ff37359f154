# Tests of geometry/src/surface
kiri_test(gregory_patch_test SOURCES gregory_patch_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(surface_network_test SOURCES surface_network_test.cpp LIBS kiri_geometry LABELS unit)

# Tests of geometry/src/fog
kiri_test(footprint_test SOURCES footprint_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(base_surface_test SOURCES base_surface_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(tessellate_test SOURCES tessellate_test.cpp LIBS kiri_geometry LABELS unit)

# Tests of geometry/src/placement (issue 10)
kiri_test(fog_fill_test SOURCES fog_fill_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(mask_outline_test SOURCES mask_outline_test.cpp LIBS kiri_geometry LABELS unit)

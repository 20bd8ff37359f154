kiri_test(error_test SOURCES error_test.cpp LIBS kiri_geometry LABELS unit)

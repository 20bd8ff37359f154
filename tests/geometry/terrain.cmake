# Tests of geometry/src/terrain
find_package(GDAL REQUIRED)
kiri_test(terrain_test SOURCES terrain_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(ground_test SOURCES ground_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(dem_test SOURCES dem_test.cpp LIBS kiri_geometry GDAL::GDAL LABELS unit)
kiri_test(dem_refusal_test SOURCES dem_refusal_test.cpp LIBS kiri_geometry GDAL::GDAL LABELS unit)
kiri_test(scattered_points_test SOURCES scattered_points_test.cpp LIBS kiri_geometry LABELS unit)

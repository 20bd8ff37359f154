kiri_test(error_test SOURCES error_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(scene_test SOURCES scene_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(quality_test SOURCES quality_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(pipeline_test SOURCES pipeline_test.cpp LIBS kiri_geometry LABELS unit)

kiri_test(error_test SOURCES error_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(scene_test SOURCES scene_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(quality_test SOURCES quality_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(docs_fields_test SOURCES docs_fields_test.cpp LIBS kiri_geometry LABELS unit)

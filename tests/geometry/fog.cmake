# Tests of geometry/src/fog
kiri_test(footprint_test SOURCES footprint_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(base_surface_test SOURCES base_surface_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(tessellate_test SOURCES tessellate_test.cpp LIBS kiri_geometry LABELS unit)
find_package(nlohmann_json REQUIRED)
kiri_test(fog_spec_test SOURCES fog_spec_test.cpp LIBS kiri_geometry nlohmann_json::nlohmann_json LABELS unit)
kiri_test(author_test SOURCES author_test.cpp LIBS kiri_geometry nlohmann_json::nlohmann_json LABELS unit)
kiri_test(layer_stack_test SOURCES layer_stack_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(medium_test SOURCES medium_test.cpp LIBS kiri_geometry LABELS unit)

# Tests of geometry/src/surface
kiri_test(gregory_patch_test SOURCES gregory_patch_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(surface_network_test SOURCES surface_network_test.cpp LIBS kiri_geometry LABELS unit)
# The same tests on the SSE2 lanes of the batch path (the run-time choice takes AVX2 where it can).
kiri_test(gregory_patch_sse2_test SOURCES gregory_patch_test.cpp ${PROJECT_SOURCE_DIR}/geometry/src/surface/gregory_patch.cpp
  LIBS kiri_geometry LABELS unit)
target_compile_definitions(gregory_patch_sse2_test PRIVATE KIRI_GREGORY_NO_AVX2)

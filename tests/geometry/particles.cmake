# Tests of geometry/src/particles
kiri_test(particle_footprint_test SOURCES particle_footprint_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(particle_sampling_test SOURCES particle_sampling_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(harris_reference_test SOURCES harris_reference_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(attenuation_cpu_test SOURCES attenuation_cpu_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(particle_distribution_test SOURCES particle_distribution_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(relax_points_test SOURCES relax_points_test.cpp LIBS kiri_geometry LABELS unit)
kiri_test(density_ratio_test SOURCES density_ratio_test.cpp LIBS kiri_geometry LABELS unit)

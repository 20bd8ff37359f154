# Sources of geometry/src/particles (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/particles/particle_footprint.cpp
  src/particles/relax_particles.cpp
  src/particles/sample_elimination.cpp
  src/particles/shell_envelope.cpp
  src/particles/sample_particles.cpp
  src/particles/particle_ply.cpp
  src/particles/light_grid.cpp
  src/particles/harris_reference.cpp
  src/particles/attenuation_cpu.cpp
  src/particles/density_ratio.cpp
)

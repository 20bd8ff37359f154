# Sources of geometry/src/fog (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/fog/footprint.cpp
  src/fog/fog_target.cpp
  src/fog/base_surface.cpp
  src/fog/fit_assemble.cpp
  src/fog/fit_clearance.cpp
  src/fog/fit_solver.cpp
  src/fog/fit_samples.cpp
  src/fog/tessellate.cpp
)

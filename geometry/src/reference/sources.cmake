# Sources of geometry/src/reference: the CPU reference ray marcher (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/reference/heightfield_ray.cpp
  src/reference/shell_intervals.cpp
  src/reference/fog_marcher.cpp
  src/reference/reference_fog.cpp
  src/reference/path_tracer.cpp
  src/reference/path_traced_image.cpp
  src/reference/light_volume_bake.cpp
  src/reference/light_volume_grids.cpp
)

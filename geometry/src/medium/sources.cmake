# Sources of geometry/src/medium (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/medium/optics.cpp
  src/medium/fog_noise.cpp
  src/medium/medium.cpp
  src/medium/fog_partition.cpp
  src/medium/air_light.cpp
  src/medium/fog_lighting.cpp
  src/medium/light_volume.cpp
)

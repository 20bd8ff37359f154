# Sources of geometry/src/terrain (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/terrain/terrain.cpp
  src/terrain/ground.cpp
  src/terrain/terrain_index.cpp
  src/terrain/dem.cpp
  src/terrain/nodata_fill.cpp
  src/terrain/scattered_points.cpp
  src/terrain/point_files.cpp
)

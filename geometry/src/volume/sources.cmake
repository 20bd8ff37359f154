# Sources of geometry/src/volume: what the volume renderers share besides the Medium
# (height fog, froxel options and slice distributions, the OpenVDB export)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/volume/height_fog.cpp
  src/volume/height_fog_free_path.cpp
  src/volume/froxel_slices.cpp
  src/volume/medium_vdb.cpp
)

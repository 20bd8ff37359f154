# Sources of geometry/src/scene (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/scene/error.cpp
  src/scene/scene.cpp
  src/scene/quality.cpp
  src/scene/fog_partition_json.cpp
  src/scene/scene_fog.cpp
  src/scene/scene_fog_report.cpp
)

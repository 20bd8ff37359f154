# Sources of geometry/src/scene (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/scene/scene.cpp
  src/scene/quality.cpp
  src/scene/quality_json.cpp
  src/scene/field_docs.cpp
  src/scene/scene_fields.cpp
  src/scene/field_json.cpp
  src/scene/fog_partition_json.cpp
  src/scene/author_report.cpp
  src/scene/author.cpp
  src/scene/author_estimate.cpp
  src/scene/fog_spec_json.cpp
  src/scene/froxel_options_json.cpp
  src/scene/layer_options_json.cpp
  src/scene/medium_options_json.cpp
  src/scene/particle_options_json.cpp
  src/scene/placement_json.cpp
  src/scene/stage_inputs.cpp
  src/scene/pipeline.cpp
  src/scene/scene_defaults.cpp
  src/scene/dem_scene.cpp
)

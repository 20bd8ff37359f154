# Sources of geometry/src/layers (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/layers/layer_formulas.cpp
  src/layers/layer_lod.cpp
  src/layers/layer_stack.cpp
  src/layers/layer_medium.cpp
  src/layers/layer_texture.cpp
  src/layers/layer_export.cpp
)

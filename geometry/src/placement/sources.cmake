# Sources of geometry/src/placement (paths relative to geometry/): fog placed by the terrain
# (docs/placement.md): fill, outlines, valley analysis, maps, burn-off, flow, the scene's keys.
list(APPEND KIRI_GEOMETRY_SOURCES
  src/placement/fog_fill.cpp
  src/placement/mask_outline.cpp
  src/placement/valley_analysis.cpp
  src/placement/fog_maps.cpp
  src/placement/fog_columns.cpp
  src/placement/burn_off.cpp
  src/placement/fog_flow.cpp
  src/placement/placement.cpp
  src/placement/fill_medium.cpp
)

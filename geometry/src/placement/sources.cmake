# Sources of geometry/src/placement (paths relative to geometry/): fog placed by the terrain
# (issue 10): fill, outlines, valley analysis, maps, burn-off, flow.
list(APPEND KIRI_GEOMETRY_SOURCES
  src/placement/fog_fill.cpp
  src/placement/mask_outline.cpp
)

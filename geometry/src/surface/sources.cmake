# Sources of geometry/src/surface (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/surface/catmull_clark_stencil.cpp
  src/surface/gregory_stencil.cpp
  src/surface/tessellate.cpp
  src/surface/gregory_patch.cpp
  src/surface/gregory_opensubdiv.cpp
)

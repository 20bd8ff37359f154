# Sources of geometry/src/surface (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/surface/catmull_clark_stencil.cpp
  src/surface/gregory_stencil.cpp
  src/surface/gregory_patch.cpp
  src/surface/gregory_opensubdiv.cpp
  src/surface/gregory_network.cpp
  src/surface/gregory_surface.cpp
  src/surface/limit_surface.cpp
  src/surface/osd_refiner.cpp
  src/surface/surface.cpp
)

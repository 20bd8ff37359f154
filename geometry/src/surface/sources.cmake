# Sources of geometry/src/surface (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
)

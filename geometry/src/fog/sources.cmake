# Sources of geometry/src/fog (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
)

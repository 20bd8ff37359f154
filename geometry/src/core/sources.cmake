# Sources of geometry/src/core (paths relative to geometry/)
list(APPEND KIRI_GEOMETRY_SOURCES
  src/core/error.cpp
  src/core/fields.cpp
)

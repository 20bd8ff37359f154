# The house rules that a reader of the tree can check without building (cmake -P, run by ctest):
#  1. geometry's areas are layered: a file in geometry/{include/kiri/geometry,src}/<area>/ includes
#     headers of its own area or of areas below it, never above;
#  2. no public header includes nlohmann (JSON stays inside the scene area's .cpp files);
#  3. render/ neither parses scenes nor samples particles (it holds passes);
#  4. code comments cite sources by key (docs/references.md), not by documents outside the
#     repository ("REFERENCE n", "STYLE n") or by project history ("issue n").
# Every violation is printed as FILE: rule: what; the script fails if there is any.
# usage: cmake -DROOT=<repository root> -P check_architecture.cmake
cmake_minimum_required(VERSION 3.22)
set(areas core terrain surface fog medium placement layers particles volume reference scene)
set(violations "")

function(area_rank area out)
  list(FIND areas "${area}" rank)
  set(${out} ${rank} PARENT_SCOPE)
endfunction()

# 1. layering
file(GLOB_RECURSE geometry_files RELATIVE "${ROOT}"
  "${ROOT}/geometry/include/kiri/geometry/*.hpp" "${ROOT}/geometry/src/*.hpp" "${ROOT}/geometry/src/*.cpp")
foreach(file IN LISTS geometry_files)
  if(file MATCHES "^geometry/include/kiri/geometry/([a-z_]+)/")
    set(area ${CMAKE_MATCH_1})
  elseif(file MATCHES "^geometry/src/([a-z_]+)/")
    set(area ${CMAKE_MATCH_1})
  else()
    list(APPEND violations "${file}: layering: not inside an area folder")
    continue()
  endif()
  area_rank(${area} rank)
  if(rank LESS 0)
    list(APPEND violations "${file}: layering: '${area}' is not one of the areas (${areas})")
    continue()
  endif()
  file(STRINGS "${ROOT}/${file}" includes REGEX "^#include \"")
  foreach(line IN LISTS includes)
    if(line MATCHES "^#include \"(kiri/geometry/)?([a-z_]+)/[a-z_]+\\.hpp\"")
      set(other ${CMAKE_MATCH_2})
      area_rank(${other} other_rank)
      if(other_rank GREATER rank)
        list(APPEND violations "${file}: layering: ${area} includes ${other} (above it): ${line}")
      endif()
    endif()
  endforeach()
endforeach()

# 2. nlohmann in public headers
file(GLOB_RECURSE public_headers RELATIVE "${ROOT}" "${ROOT}/geometry/include/*.hpp" "${ROOT}/render/include/*.hpp")
foreach(file IN LISTS public_headers)
  file(STRINGS "${ROOT}/${file}" hits REGEX "#include <nlohmann/")
  if(hits)
    list(APPEND violations "${file}: public header: includes nlohmann")
  endif()
endforeach()

# 3. render/ holds passes
file(GLOB_RECURSE render_files RELATIVE "${ROOT}" "${ROOT}/render/*.hpp" "${ROOT}/render/*.cpp")
foreach(file IN LISTS render_files)
  file(STRINGS "${ROOT}/${file}" hits REGEX "(sample_particles|load_scene|parse_scene)\\(")
  foreach(hit IN LISTS hits)
    string(STRIP "${hit}" hit)
    list(APPEND violations "${file}: render: scene parsing or particle sampling: ${hit}")
  endforeach()
endforeach()

# 4. citations. Lines are read whole (semicolons and brackets would split a CMake list). A name
#    that merely ends in REFERENCE (the KIRI_UPDATE_REFERENCE variable) is not a citation.
file(GLOB_RECURSE code_files RELATIVE "${ROOT}"
  "${ROOT}/geometry/*.hpp" "${ROOT}/geometry/*.cpp" "${ROOT}/render/*.hpp" "${ROOT}/render/*.cpp"
  "${ROOT}/render/shaders/*" "${ROOT}/apps/*.hpp" "${ROOT}/apps/*.cpp" "${ROOT}/tests/*.hpp" "${ROOT}/tests/*.cpp"
  "${ROOT}/fuzz/*.cpp" "${ROOT}/CMakeLists.txt" "${ROOT}/*/CMakeLists.txt" "${ROOT}/cmake/*.cmake")
# The sources only: a build folder inside the tree holds CMakeLists.txt of its own, which the
# install test writes and removes while the suite runs (a file listed here, gone when read).
list(FILTER code_files INCLUDE REGEX "^((geometry|render|apps|tests|fuzz|cmake)/|CMakeLists.txt$)")
foreach(file IN LISTS code_files)
  file(READ "${ROOT}/${file}" text)
  if(NOT text MATCHES "(^|[^A-Z_])REFERENCE|STYLE [0-9]|[Ii]ssues? [0-9]")
    continue()
  endif()
  string(REGEX REPLACE "[][;]" "_" text "${text}")
  string(REPLACE "\n" ";" lines "${text}")
  set(number 0)
  foreach(line IN LISTS lines)
    math(EXPR number "${number} + 1")
    if(line MATCHES "(^|[^A-Z_])REFERENCE|STYLE [0-9]|[Ii]ssues? [0-9]")
      string(STRIP "${line}" line)
      list(APPEND violations "${file}:${number}: citation: cite by key (docs/references.md), not a document outside the repository or project history: ${line}")
    endif()
  endforeach()
endforeach()

list(LENGTH violations count)
if(count GREATER 0)
  foreach(v IN LISTS violations)
    message("${v}")
  endforeach()
  message(FATAL_ERROR "${count} violation(s) of the house rules")
endif()
message(STATUS "house rules hold: layering over ${areas}, no JSON in public headers, render holds passes, citations by key")

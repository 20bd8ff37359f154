# kiri_find_openvdb(): defines OpenVDB::openvdb in the calling directory. OpenVDB's own
# package config when the installation has one; else the find module that Debian and Ubuntu
# ship with libopenvdb-dev (<prefix>/lib/<arch>/cmake/OpenVDB/FindOpenVDB.cmake), looked up
# under the usual prefixes (CMAKE_PREFIX_PATH, then the system's) rather than at a fixed path.
# Imported targets belong to the directory that finds them: call it wherever one is needed.
function(kiri_find_openvdb)
  if(TARGET OpenVDB::openvdb)
    return()
  endif()
  find_package(OpenVDB CONFIG QUIET)
  if(OpenVDB_FOUND)
    return()
  endif()
  find_path(KIRI_OPENVDB_MODULE_DIR FindOpenVDB.cmake
    PATHS ${CMAKE_PREFIX_PATH} ${CMAKE_SYSTEM_PREFIX_PATH}
    PATH_SUFFIXES lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB lib/cmake/OpenVDB lib64/cmake/OpenVDB
    DOC "Folder holding OpenVDB's FindOpenVDB.cmake")
  if(NOT KIRI_OPENVDB_MODULE_DIR)
    message(FATAL_ERROR "OpenVDB not found: neither an OpenVDB package config nor FindOpenVDB.cmake under "
                        "lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB or lib/cmake/OpenVDB of a prefix "
                        "(install libopenvdb-dev, or set CMAKE_PREFIX_PATH or KIRI_OPENVDB_MODULE_DIR)")
  endif()
  if(NOT KIRI_OPENVDB_MODULE_DIR IN_LIST CMAKE_MODULE_PATH)
    list(APPEND CMAKE_MODULE_PATH "${KIRI_OPENVDB_MODULE_DIR}")
  endif()
  find_package(OpenVDB MODULE REQUIRED)
endfunction()

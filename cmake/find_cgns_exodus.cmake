# SPDX-License-Identifier: MIT
# CGNS (Debian libcgns-dev: CGNS 3.4 on HDF5) as CGNS::CGNS and Exodus II (Debian
# libexodusii-dev: 6.02 on netCDF) as Exodus::Exodus, found by their header and library
# (neither ships a pkg-config or CMake file); scripts/install-deps installs both.
foreach(lib IN ITEMS CGNS Exodus)
  if(lib STREQUAL "CGNS")
    set(header cgnslib.h)
    set(names cgns)
  else()
    set(header exodusII.h)
    set(names exoIIv2c exodus)
  endif()
  find_path(${lib}_INCLUDE_DIR ${header} PATH_SUFFIXES cgns exodusii)
  find_library(${lib}_LIBRARY NAMES ${names})
  if(NOT ${lib}_INCLUDE_DIR OR NOT ${lib}_LIBRARY)
    message(FATAL_ERROR "${lib} not found (${header}, lib${names}): run scripts/install-deps "
                        "(Debian libcgns-dev and libexodusii-dev)")
  endif()
  if(NOT TARGET ${lib}::${lib})
    add_library(${lib}::${lib} UNKNOWN IMPORTED)
    set_target_properties(${lib}::${lib} PROPERTIES IMPORTED_LOCATION ${${lib}_LIBRARY}
                          INTERFACE_INCLUDE_DIRECTORIES ${${lib}_INCLUDE_DIR})
  endif()
endforeach()

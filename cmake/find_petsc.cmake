# SPDX-License-Identifier: MIT
# PETSc (Debian petsc-dev: PETSc 3.18 with hypre, on Open MPI) as PETSc::PETSc: its library
# and include directory from pkg-config's PETSc module (PETSC_DIR/lib/pkgconfig is searched
# too when PETSC_DIR is set), and MPI's C interface (pkg-config mpi-c), whose mpi.h PETSc's
# headers include. Only the include directories are taken from the PETSc module: its Cflags
# carry -D_FORTIFY_SOURCE=2, which breaks unoptimized builds under -Werror.
find_package(PkgConfig REQUIRED)
pkg_check_modules(MPI_C REQUIRED IMPORTED_TARGET mpi-c)
if(DEFINED ENV{PETSC_DIR})
  list(APPEND CMAKE_PREFIX_PATH $ENV{PETSC_DIR})
endif()
list(APPEND CMAKE_PREFIX_PATH /usr/lib/petsc)
pkg_check_modules(PETSC REQUIRED PETSc)
find_library(PETSC_LIBRARY NAMES ${PETSC_LIBRARIES} HINTS ${PETSC_LIBRARY_DIRS} REQUIRED NO_DEFAULT_PATH)
if(NOT TARGET PETSc::PETSc)
  add_library(PETSc::PETSc UNKNOWN IMPORTED)
  set_target_properties(PETSc::PETSc PROPERTIES
    IMPORTED_LOCATION ${PETSC_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES "${PETSC_INCLUDE_DIRS}"
    INTERFACE_LINK_LIBRARIES PkgConfig::MPI_C)
endif()
# PT-Scotch, PETSc's partitioner (libptscotch-dev, which petsc-dev depends on): meshmorph seeds
# its random generator (src/parallel/partition.cpp).
find_library(PTSCOTCH_LIBRARY NAMES ptscotch REQUIRED)
if(NOT TARGET PETSc::PTScotch)
  add_library(PETSc::PTScotch UNKNOWN IMPORTED)
  set_target_properties(PETSc::PTScotch PROPERTIES IMPORTED_LOCATION ${PTSCOTCH_LIBRARY} INTERFACE_LINK_LIBRARIES PkgConfig::MPI_C)
endif()

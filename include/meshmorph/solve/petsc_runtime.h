// SPDX-License-Identifier: MIT
#pragma once

namespace meshmorph {

/// Whether an MPI launcher (mpirun, mpiexec, srun) started this process: its rank variables
/// (Open MPI's OMPI_COMM_WORLD_SIZE, PMIx's PMIX_RANK, MPICH's PMI_SIZE) are set.
bool launched_by_mpi();

/// Initializes PETSc once per process (thread-safe; later calls return at once) and
/// registers its finalization at exit. PETSc reads neither the command line nor .petscrc
/// files, installs no signal handler, and reports errors through return codes only (its
/// error handler prints nothing). A process that no launcher started becomes an MPI
/// singleton with Open MPI's self transport and no daemon (see the .cpp); under a launcher
/// MPI starts as the launcher set it up, on PETSC_COMM_WORLD = MPI_COMM_WORLD.
/// Throws std::runtime_error when initialization fails.
void ensure_petsc();

/// Throws std::runtime_error ("meshmorph: PETSc <what> failed (error <code>)") when a PETSc
/// call returned the nonzero error code `error`.
void check_petsc(int error, const char* what);

/// The options prefix of meshmorph's GAMG preconditioners, the serial backend's and the
/// distributed one's, once its defaults (solve/petsc_solver.cpp) are in PETSc's options
/// database wherever PETSC_OPTIONS has not set them.
const char* gamg_options_prefix();

}  // namespace meshmorph

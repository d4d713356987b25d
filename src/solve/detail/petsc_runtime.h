// SPDX-License-Identifier: MIT
#pragma once

namespace meshmorph::detail {

/// Initializes PETSc once per process (thread-safe; later calls return at once) and
/// registers its finalization at exit. PETSc reads neither the command line nor .petscrc
/// files, installs no signal handler, and reports errors through return codes only (its
/// error handler prints nothing). When MPI is not initialized yet, PETSc initializes it as a
/// singleton process with Open MPI's shared-memory and self transports (see the .cpp).
/// Throws std::runtime_error when initialization fails.
void ensure_petsc();

}  // namespace meshmorph::detail

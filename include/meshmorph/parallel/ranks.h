// SPDX-License-Identifier: MIT
#pragma once
#include <exception>
#include <functional>
#include <stdexcept>

namespace meshmorph {

/// Starts MPI through PETSc when an MPI launcher started the process (launched_by_mpi());
/// otherwise does nothing, and the process stays serial (PETSc, where a solver needs it,
/// starts later as an MPI singleton). Returns whether the process runs on ranks.
bool start_ranks();
/// Whether start_ranks() started MPI: commands then take their distributed paths, even on
/// one rank (docs/parallel.md).
bool on_ranks();
/// This process's rank in PETSC_COMM_WORLD (0 when not on ranks).
int mpi_rank();
/// The number of ranks (1 when not on ranks).
int mpi_size();

/// Collective: rank 0's `value` on every rank.
int broadcast_from_root(int value);
/// Ends every rank at once with exit status `code` (MPI_Abort): for a failure that one rank
/// meets while the others may wait for it in a collective call. Serial: std::exit(code).
[[noreturn]] void abort_ranks(int code);

/// Thrown by on_root() on every rank once rank 0's part failed; rank 0 has printed why.
class RootFailed : public std::runtime_error {
 public:
  explicit RootFailed(int exit_code) : std::runtime_error("rank 0 failed"), exit_code_(exit_code) {}
  int exit_code() const { return exit_code_; }

 private:
  int exit_code_;
};

/// Collective: runs `part` on rank 0 alone (reading input, writing output). When it throws,
/// rank 0 passes the exception to `report` (which prints it and returns the exit code) and
/// every rank throws RootFailed with that code, so that all end alike and none waits for
/// rank 0 in vain.
void on_root(const std::function<void()>& part, const std::function<int(std::exception_ptr)>& report);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/parallel/ranks.h"

#include <cstdlib>

#include <petscsys.h>

#include "meshmorph/solve/petsc_runtime.h"

namespace meshmorph {
namespace {

bool started = false;

}  // namespace

bool start_ranks() {
  if (started || !launched_by_mpi()) return started;
  ensure_petsc();
  started = true;
  return true;
}

bool on_ranks() { return started; }

int mpi_rank() {
  int rank = 0;
  if (started) MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  return rank;
}

int mpi_size() {
  int size = 1;
  if (started) MPI_Comm_size(PETSC_COMM_WORLD, &size);
  return size;
}

int broadcast_from_root(int value) {
  if (started) MPI_Bcast(&value, 1, MPI_INT, 0, PETSC_COMM_WORLD);
  return value;
}

void abort_ranks(int code) {
  if (started && mpi_size() > 1) MPI_Abort(PETSC_COMM_WORLD, code);
  std::exit(code);
}

void on_root(const std::function<void()>& part, const std::function<int(std::exception_ptr)>& report) {
  int code = 0;
  if (mpi_rank() == 0) {
    try {
      part();
    } catch (...) {
      code = report(std::current_exception());
      if (code == 0) code = 3;  // a failure never ends as a success
    }
  }
  code = broadcast_from_root(code);
  if (code != 0) throw RootFailed(code);
}

}  // namespace meshmorph

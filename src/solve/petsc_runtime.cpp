// SPDX-License-Identifier: MIT
#include "meshmorph/solve/petsc_runtime.h"

#include <cstdlib>
#include <mutex>
#include <stdexcept>
#include <string>

#include <petscsys.h>

namespace meshmorph {
namespace {

void finalize_petsc() {
  PetscBool finalized = PETSC_FALSE;
  if (PetscFinalized(&finalized) == 0 && !finalized) PetscFinalize();
}

}  // namespace

void check_petsc(int error, const char* what) {
  if (error != 0) throw std::runtime_error(std::string("meshmorph: PETSc ") + what + " failed (error " + std::to_string(error) + ")");
}

bool launched_by_mpi() {
  for (const char* name : {"OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_SIZE"})
    if (std::getenv(name) != nullptr) return true;
  return false;
}

void ensure_petsc() {
  static std::once_flag once;
  static PetscErrorCode status = 0;
  std::call_once(once, [] {
    int mpi_ready = 0;
    MPI_Initialized(&mpi_ready);
    if (!mpi_ready && !launched_by_mpi()) {
      // A serial process is an MPI singleton. Open MPI's defaults would fork an orted daemon
      // and probe the UCX transport: 0.25–0.4 s of MPI_Init on a 2-core machine, against
      // 0.03 s with the self transport alone and no daemon. The environment still overrides.
      setenv("OMPI_MCA_ess_singleton_isolated", "1", 0);
      setenv("OMPI_MCA_pml", "ob1", 0);
      setenv("OMPI_MCA_btl", "self", 0);
    }
    // Set before PetscInitialize, which reads them: no signal handler (the program's own
    // stay), no .petscrc files from the working directory, no report of unused options.
    PetscOptionsSetValue(nullptr, "-no_signal_handler", nullptr);
    PetscOptionsSetValue(nullptr, "-skip_petscrc", nullptr);
    PetscOptionsSetValue(nullptr, "-options_left", "no");
    status = PetscInitializeNoArguments();
    if (status != 0) return;
    // Errors come back as return codes, which the solvers turn into failed set-ups and solves.
    status = PetscPushErrorHandler(PetscReturnErrorHandler, nullptr);
    std::atexit(finalize_petsc);
  });
  if (status != 0) throw std::runtime_error("meshmorph: PETSc failed to initialize (error " + std::to_string(static_cast<int>(status)) + ")");
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/app/optimize_ranks.h"

#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "meshmorph/error.h"
#include "meshmorph/parallel/partition.h"
#include "meshmorph/parallel/rank_optimize.h"
#include "meshmorph/parallel/ranks.h"

namespace meshmorph {

void check_runs_on_ranks(const OptimizeRunner& runner) {
  if (!runner.constraints().slides.empty())
    throw InputError(runner.where() + ": sliding and projected boundary nodes do not run on MPI ranks yet; run without mpirun, or fix them");
}

RunOutput run_on_ranks(const OptimizeRunner* runner) {
  std::string partitioner;
  const std::vector<int> cell_rank = partition_cells(runner ? &runner->topology() : nullptr, partitioner);
  std::vector<LocalMesh> parts;
  if (runner) {
    Mesh start = runner->input();
    start.x = runner->start();
    parts = split_mesh(start, cell_rank, mpi_size(), runner->constraints().fixed);
  }
  const LocalMesh local = scatter_local_meshes(std::move(parts));
  // A failure of one rank while the others work on, for the tests (docs/parallel.md, Failures).
  if (const char* rank = std::getenv("MESHMORPH_FAIL_ON_RANK"); rank != nullptr && std::atoi(rank) == mpi_rank())
    throw IoError("rank " + std::to_string(mpi_rank()) + ": a failure injected by MESHMORPH_FAIL_ON_RANK");
  const OptimizeOptions options = broadcast_optimize_options(runner ? &runner->settings().options : nullptr);
  Eigen::MatrixXd x = local.mesh.x;
  const OptimizeResult r = optimize_on_ranks(local, options, x);
  Eigen::MatrixXd global;
  if (runner) global = runner->start();
  gather_owned_nodes(local, x, &global);
  if (!runner) return {};
  RunOutput out = runner->output(r, global);
  out.extra["ranks"] = mpi_size();
  out.extra["partitioner"] = partitioner;
  return out;
}

}  // namespace meshmorph

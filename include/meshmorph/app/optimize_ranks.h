// SPDX-License-Identifier: MIT
#pragma once
#include "meshmorph/app/optimize_case.h"
#include "meshmorph/app/run_output.h"

namespace meshmorph {

/// Throws InputError naming the case where `runner`'s run cannot go on MPI ranks yet:
/// where boundary nodes slide or are projected (docs/parallel.md).
void check_runs_on_ranks(const OptimizeRunner& runner);

/// Collective: `runner`'s optimization on the MPI ranks (docs/parallel.md). Rank 0 passes
/// its runner, the other ranks nullptr. Rank 0 partitions the cells (partition_cells) and
/// sends each rank its part; every rank optimizes it (optimize_on_ranks); rank 0 gathers the
/// nodes in their input order. Returns runner->output() on rank 0, with the number of ranks
/// and the partitioner in its extras; an empty output on the other ranks.
RunOutput run_on_ranks(const OptimizeRunner* runner);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>

namespace meshmorph {

/// The OpenMP threads a method runs on for a problem of `n_dofs` unknowns when `requested`
/// are asked for: those, or for 0, one thread below 30 000 unknowns and the OpenMP default
/// (all cores) from there on. On small problems the barriers of the coloured element loops
/// cost about what a second thread saves, and many times more on a machine that other jobs
/// share: a thread waiting at a barrier for one the system has paused spins or sleeps for a
/// time slice (bench/README.md, "Threads on a shared machine").
int default_threads(int requested, std::size_t n_dofs);

}  // namespace meshmorph

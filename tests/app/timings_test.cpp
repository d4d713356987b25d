// SPDX-License-Identifier: MIT
#include "meshmorph/timings.h"

#include <cmath>

#include <gtest/gtest.h>

namespace meshmorph {
namespace {

// Work the clock can see: a few hundred microseconds of arithmetic the compiler cannot drop.
double busy() {
  volatile double sum = 0.0;
  for (int i = 0; i < 200000; ++i) sum = sum + std::sqrt(double(i));
  return sum;
}

// Each phase gets the time inside its timers only, less that of the timers opened inside it;
// the rest of the run is Other; phases no timer opened stay exactly 0.
TEST(Timings, EachPhaseGetsOnlyItsOwnTime) {
  const RunTimings run;
  busy();
  {
    const PhaseTimer search(Phase::LineSearch);
    busy();
    const PhaseTimer validity(Phase::Validity);
    busy();
  }
  const Timings t = run.totals();
  EXPECT_GT(t[Phase::Other], 0.0);
  EXPECT_GT(t[Phase::LineSearch], 0.0);
  EXPECT_GT(t[Phase::Validity], 0.0);
  EXPECT_EQ(t[Phase::Assembly], 0.0);
  EXPECT_EQ(t[Phase::Solve], 0.0);
  EXPECT_EQ(t[Phase::Io], 0.0);
}

// Timers outside a run and timers opened inside parallel regions count nowhere; a run inside
// another adds to it instead of starting over.
TEST(Timings, OnlyTheRunsOwnThreadOutsideParallelRegionsCounts) {
  {
    const PhaseTimer outside(Phase::Io);
    busy();
  }
  const RunTimings run;
  {
    const PhaseTimer assembly(Phase::Assembly);
    busy();
  }
#pragma omp parallel num_threads(2)
  {
    const PhaseTimer inside(Phase::Solve);
    busy();
  }
  {
    const RunTimings inner;
    const PhaseTimer setup(Phase::SolverSetup);
    busy();
  }
  const Timings t = run.totals();
  EXPECT_EQ(t[Phase::Io], 0.0);
  EXPECT_EQ(t[Phase::Solve], 0.0);
  EXPECT_GT(t[Phase::Assembly], 0.0);
  EXPECT_GT(t[Phase::SolverSetup], 0.0);
}

}  // namespace
}  // namespace meshmorph

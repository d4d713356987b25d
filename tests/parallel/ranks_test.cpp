// SPDX-License-Identifier: MIT
#include "meshmorph/parallel/ranks.h"

#include <stdexcept>

#include <gtest/gtest.h>

namespace meshmorph {
namespace {

// A process that no MPI launcher started is one rank, and on_root() runs its part there:
// a failure reaches `report` once and comes back as RootFailed with report's exit code.
TEST(Ranks, SerialProcessIsRankZeroOfOne) {
  EXPECT_FALSE(on_ranks());
  EXPECT_EQ(mpi_rank(), 0);
  EXPECT_EQ(mpi_size(), 1);
  EXPECT_EQ(broadcast_from_root(7), 7);

  int runs = 0, reports = 0;
  on_root([&] { ++runs; }, [&](std::exception_ptr) { return ++reports; });
  EXPECT_EQ(runs, 1);
  EXPECT_EQ(reports, 0);

  try {
    on_root([] { throw std::invalid_argument("bad"); },
            [&](std::exception_ptr e) {
              ++reports;
              EXPECT_THROW(std::rethrow_exception(e), std::invalid_argument);
              return 2;
            });
    FAIL() << "no RootFailed";
  } catch (const RootFailed& f) {
    EXPECT_EQ(f.exit_code(), 2);
  }
  EXPECT_EQ(reports, 1);
  // A report that returns 0 for a failure still ends the ranks with a failure's code.
  EXPECT_THROW(on_root([] { throw std::runtime_error("x"); }, [](std::exception_ptr) { return 0; }), RootFailed);
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/methods/threads.h"

#include <gtest/gtest.h>

namespace meshmorph {
namespace {

TEST(DefaultThreads, OneThreadBelowThirtyThousandUnknownsAllCoresFromThere) {
  EXPECT_EQ(default_threads(0, 2530), 1);
  EXPECT_EQ(default_threads(0, 29999), 1);
  EXPECT_EQ(default_threads(0, 30000), 0);  // 0: the OpenMP default, all cores
  EXPECT_EQ(default_threads(0, 645000), 0);
}

TEST(DefaultThreads, ThreadsAskedForAreKept) {
  EXPECT_EQ(default_threads(2, 10), 2);
  EXPECT_EQ(default_threads(1, 1000000), 1);
  EXPECT_EQ(default_threads(8, 30000), 8);
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
// coordinate_range_problem: where double precision no longer holds a mesh's cell volumes.
#include <gtest/gtest.h>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {
namespace {

TEST(CoordinateRange, NamesTheFirstNodeBeyondTheLimitAndATooSmallExtent) {
  Eigen::MatrixXd x(3, 3);
  x << 0, 1, 0, 0, 0, 1, 0, 0, 0;
  EXPECT_FALSE(coordinate_range_problem(x));
  EXPECT_FALSE(coordinate_range_problem(1e100 * x));  // the limit itself holds: 1e300 volumes
  x(1, 2) = -2e100;
  const auto far = coordinate_range_problem(x);
  ASSERT_TRUE(far);
  EXPECT_EQ(far->node, 2);
  EXPECT_EQ(far->what, "coordinate 2e+100 is beyond +-1e+100, where cell volumes overflow");
  x(1, 2) = 1;
  const auto tiny = coordinate_range_problem(1e-95 * x);
  ASSERT_TRUE(tiny);
  EXPECT_EQ(tiny->node, -1);
  EXPECT_NE(tiny->what.find("is below 1e-90, where cell volumes underflow"), std::string::npos) << tiny->what;
  EXPECT_FALSE(coordinate_range_problem(1e-85 * x));
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/fem/validity.h"
#include "meshmorph/methods/morph.h"
#include "methods/morph_fixtures.h"

namespace meshmorph {
namespace {

// Paper 000 §5.2's shell (bench/geo/shell.geo at lc 0.8: 444 nodes), its inner sphere
// translated by 8, the outer one fixed. In the second AL iteration Newton absorbs each weight
// update in one step: growing the bound per update from β towards β⁴ there takes 18 Newton
// steps where β at every update takes 23, and ends at a higher min quality (0.513 against
// 0.508).
TEST(MorphWeights, AdaptiveGrowthTakesFewerStepsToABetterShell) {
  const test::CoarseShell shell;
  const Mesh& mesh = shell.mesh;
  const Topology& topo = shell.topology;
  const BoundaryTargets& bc = shell.bc;
  long long steps[2];
  double quality[2];
  for (const bool adaptive : {false, true}) {
    MorphOptions o;
    o.adaptive_growth = adaptive;
    o.threads = 1;
    Eigen::MatrixXd x = mesh.x;
    const MorphResult r = Morpher(mesh, topo, bc, o).solve(bc.target, x);
    ASSERT_TRUE(r.converged) << adaptive << ": " << r.message;
    Mesh moved = mesh;
    moved.x = x;
    EXPECT_EQ(count_invalid_cells(moved), 0u);
    steps[adaptive] = r.newton;
    quality[adaptive] = test::min_quality(mesh, x);
  }
  EXPECT_LE(steps[1], steps[0] - 3);
  EXPECT_GT(quality[1], quality[0] + 0.002);
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/methods/morph.h"
#include "meshmorph/quality/element_quality.h"

namespace meshmorph {
namespace {

double min_quality(const Mesh& input, const Eigen::MatrixXd& x) {
  Mesh moved = input;
  moved.x = x;
  double q = 1.0;
  for (const CellBlock& block : input.cells)
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const Eigen::MatrixXd X0 = cell_coordinates(input, block, c);
      q = std::min(q, element_quality(block.type, block.order, cell_coordinates(moved, block, c), &X0));
    }
  return q;
}

// Paper 000 §5.2's shell (bench/geo/shell.geo at lc 0.8: 444 nodes), its inner sphere
// translated by 8, the outer one fixed. In the second AL iteration Newton absorbs each weight
// update in one step: growing the bound per update from β towards β⁴ there takes 18 Newton
// steps where β at every update takes 23, and ends at a higher min quality (0.513 against
// 0.508).
TEST(MorphWeights, AdaptiveGrowthTakesFewerStepsToABetterShell) {
  const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/shell_coarse.msh");
  const Topology topo = build_topology(mesh);
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(3, static_cast<Eigen::Index>(mesh.n_nodes()));
  for (std::int32_t node : mesh.group_nodes(*mesh.find_group("outer"))) bc.role[node] = NodeRole::Fixed;
  for (std::int32_t node : mesh.group_nodes(*mesh.find_group("inner"))) {
    bc.role[node] = NodeRole::Prescribed;
    bc.target(0, node) += 8.0;
  }
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
    quality[adaptive] = min_quality(mesh, x);
  }
  EXPECT_LE(steps[1], steps[0] - 3);
  EXPECT_GT(quality[1], quality[0] + 0.002);
}

}  // namespace
}  // namespace meshmorph

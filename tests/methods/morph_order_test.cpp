// SPDX-License-Identifier: MIT
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/fem/validity.h"
#include "meshmorph/methods/morph.h"
#include "methods/morph_fixtures.h"

namespace meshmorph {
namespace {

// The Morpher solves on its own numbering of the nodes (mesh/node_order.h) and hands x back
// in the caller's: on paper 000's shell (444 nodes, 42 across, inner sphere translated by 8)
// the result is the run on the input's numbering up to the rounding of sums taken in another
// order, which the weights' history carries on (7e-5).
TEST(MorphOrder, ReturnsTheRunOnTheInputNumberingInTheInputNumbering) {
  const test::CoarseShell shell;
  const Mesh& mesh = shell.mesh;
  const Topology& topo = shell.topology;
  const BoundaryTargets& bc = shell.bc;
  const auto run = [](const Mesh& m, const Topology& t, const BoundaryTargets& b, bool renumber) {
    MorphOptions o;
    o.renumber = renumber;
    o.threads = 1;
    Eigen::MatrixXd x = m.x;
    const MorphResult r = Morpher(m, t, b, o).solve(b.target, x);
    EXPECT_TRUE(r.converged) << r.message;
    return x;
  };
  const Eigen::MatrixXd plain = run(mesh, topo, bc, false), renumbered = run(mesh, topo, bc, true);
  Mesh moved = mesh;
  moved.x = renumbered;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
  EXPECT_LT((renumbered - plain).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_GT((renumbered - mesh.x).cwiseAbs().maxCoeff(), 7.9);  // it did move
}

}  // namespace
}  // namespace meshmorph

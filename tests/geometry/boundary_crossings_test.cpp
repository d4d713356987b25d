// SPDX-License-Identifier: MIT
#include "meshmorph/geometry/boundary_crossings.h"

#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/structured.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

class BoundaryCrossingSweep : public ::testing::TestWithParam<test::ElementCase> {};

TEST_P(BoundaryCrossingSweep, AStructuredMeshHasNone) {
  const Mesh mesh = structured_mesh(GetParam().type, GetParam().order, 3);
  EXPECT_EQ(boundary_crossings(mesh, build_topology(mesh)).count, 0u);
}

// Turned by an angle that no coordinate survives exactly, and elevated there: the high-order
// nodes of a flat facet sit off its plane by rounding, and its pieces lie in one plane up to
// that, as do the pieces of flat neighbours. None of them cross.
TEST_P(BoundaryCrossingSweep, FlatFacetsElevatedOffTheAxesHaveNone) {
  Mesh linear = structured_mesh(GetParam().type, 1, 3);
  Eigen::MatrixXd R = Eigen::MatrixXd::Identity(linear.dim, linear.dim);
  const double c = std::cos(0.7), s = std::sin(0.7);
  R.topLeftCorner(2, 2) << c, -s, s, c;
  if (linear.dim == 3) R = R * Eigen::AngleAxisd(0.4, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  linear.x = 3.7 * R * linear.x;
  const Mesh mesh = GetParam().order > 1 ? elevate_order(linear, GetParam().order) : linear;
  EXPECT_EQ(boundary_crossings(mesh, build_topology(mesh)).count, 0u);
}

// The mesh and a copy of it, shifted by `shift` along every axis, in one mesh of two parts
// with nodes of their own: their boundaries cross where the copies overlap.
TEST_P(BoundaryCrossingSweep, TwoOverlappingPartsCrossAndTwoTouchingPartsDoNot) {
  const Mesh one = structured_mesh(GetParam().type, GetParam().order, 2);
  const auto two = [&](double shift) {
    Mesh mesh = one;
    const auto n = static_cast<std::int32_t>(one.n_nodes());
    mesh.x.conservativeResize(Eigen::NoChange, 2 * one.x.cols());
    mesh.x.rightCols(one.x.cols()) = one.x.array() + shift;
    mesh.x.rightCols(one.x.cols()).row(0) = one.x.row(0).array() + 1.0 + shift;  // side by side along x
    for (auto v : one.cells[0].nodes) mesh.cells[0].nodes.push_back(v + n);
    mesh.cells[0].physical.resize(mesh.cells[0].nodes.size() / static_cast<std::size_t>(mesh.cells[0].n_nodes_per_cell()), 1);
    mesh.cells[0].entity.resize(mesh.cells[0].physical.size(), 0);
    mesh.node_tags.resize(mesh.n_nodes());
    return mesh;
  };
  // Touching along the face x = 1 with nodes of their own (a slit): no crossing.
  const Mesh touching = two(0.0);
  EXPECT_EQ(boundary_crossings(touching, build_topology(touching)).count, 0u);
  // Pushed 0.3 into each other (and 0.3 aside): the boundaries cross.
  const Mesh overlapping = two(-0.3);
  const BoundaryCrossings c = boundary_crossings(overlapping, build_topology(overlapping));
  EXPECT_GT(c.count, 0u);
  EXPECT_LT(c.first[0], c.first[1]);
}

INSTANTIATE_TEST_SUITE_P(AllCells, BoundaryCrossingSweep, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());
INSTANTIATE_TEST_SUITE_P(PrismPyramid, BoundaryCrossingSweep, ::testing::ValuesIn(test::prism_pyramid_cases()), test::CaseName());

}  // namespace
}  // namespace meshmorph

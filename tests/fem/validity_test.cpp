// SPDX-License-Identifier: MIT
#include "meshmorph/fem/validity.h"

#include <algorithm>
#include <cstdlib>
#include <limits>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/structured.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

using test::ElementCase;

class ValiditySweep : public ::testing::TestWithParam<ElementCase> {};

TEST_P(ValiditySweep, StructuredMeshIsValidAndAffineJacobiansAreExact) {
  const auto mesh = structured_mesh(GetParam().type, GetParam().order, 2);
  EXPECT_EQ(count_invalid_cells(mesh), 0u);
  // Map the mesh by x → Mx + b: every element Jacobian is M times the original one.
  Eigen::MatrixXd M = Eigen::MatrixXd::Identity(mesh.dim, mesh.dim);
  M(0, 1) = 0.3;
  M(mesh.dim - 1, 0) = -0.2;
  auto moved = mesh;
  moved.x = (M * mesh.x).colwise() + Eigen::VectorXd::Constant(mesh.dim, 0.7);
  const auto& b = mesh.cells[0];
  const auto& t = shape_table(b.type, b.order, metric_quadrature_degree(b.type, b.order));
  for (std::size_t c = 0; c < b.n_cells(); ++c)
    for (int q = 0; q < t.n_points(); ++q) {
      const auto A0 = jacobian(cell_coordinates(mesh, b, c), t, q);
      const auto A1 = jacobian(cell_coordinates(moved, b, c), t, q);
      EXPECT_LT((A1 - M * A0).norm(), 1e-12 * A0.norm());
    }
}

TEST_P(ValiditySweep, SwappingTwoCornersInverts) {
  auto mesh = structured_mesh(GetParam().type, GetParam().order, 1);
  auto& b = mesh.cells[0];
  std::swap(b.cell(0)[0], b.cell(0)[1]);
  EXPECT_GE(count_invalid_cells(mesh), 1u);
}

// Quadrilaterals and hexahedra take sum-factorized Jacobians over tensor grids of the samples;
// with a skip mask (all kept) the samples are evaluated one by one from validity_samples: both
// must give the same minimum, on curved valid cells, on inverted ones and on NaN coordinates.
TEST_P(ValiditySweep, MinimumMatchesTheDenseSamples) {
  const auto mesh = structured_mesh(GetParam().type, GetParam().order, 1);
  const auto& b = mesh.cells[0];
  const std::vector<std::uint8_t> keep(static_cast<std::size_t>(validity_samples(b.type, b.order).n_points()), 0);
  std::srand(7);
  for (double amplitude : {0.02, 0.2, 0.6}) {
    for (bool mirrored : {false, true}) {  // mirrored: det A < 0 throughout
      Eigen::MatrixXd X = cell_coordinates(mesh, b, 0) + amplitude * Eigen::MatrixXd::Random(mesh.dim, b.n_nodes_per_cell());
      if (mirrored) X.row(0) *= -1.0;
      const double dense = min_jacobian_det(b.type, b.order, X, keep);
      EXPECT_NEAR(min_jacobian_det(b.type, b.order, X), dense, 1e-13 * std::max(1.0, std::abs(dense)))
          << "amplitude " << amplitude << (mirrored ? ", mirrored" : "");
      if (mirrored && amplitude < 0.5) {
        EXPECT_LT(dense, 0.0);
      }
    }
  }
  Eigen::MatrixXd X = cell_coordinates(mesh, b, 0);
  X(0, b.n_nodes_per_cell() - 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(min_jacobian_det(b.type, b.order, X) > 0.0);
}

// Random curved cells against det A on a much finer lattice (order 24 in 2D, 12 in 3D): a
// cell that is negative anywhere there must be found invalid by the Bernstein bounds, whatever
// the validity samples say. Counts the folds that lie between the samples, so that the sweep
// shows it met some.
TEST_P(ValiditySweep, NoFoldEscapesTheBernsteinBounds) {
  const auto mesh = structured_mesh(GetParam().type, GetParam().order, 1);
  const auto& b = mesh.cells[0];
  const std::vector<std::uint8_t> keep(static_cast<std::size_t>(validity_samples(b.type, b.order).n_points()), 0);
  const int m = mesh.dim == 2 ? 24 : 12;
  Eigen::MatrixXd fine = structured_mesh(b.type, 1, m).x;  // the lattice of order m on the unit cell
  if (!is_simplex(b.type)) fine = (2.0 * fine.array() - 1.0).matrix();
  else fine = Eigen::MatrixXd(fine(Eigen::all, [&] {
    std::vector<Eigen::Index> inside;  // the unit simplex's part of the unit square (cube)
    for (Eigen::Index i = 0; i < fine.cols(); ++i)
      if (fine.col(i).sum() <= 1.0 + 1e-12) inside.push_back(i);
    return inside;
  }()));
  const ShapeTable t = tabulate(b.type, b.order, fine);
  std::srand(11);
  int between = 0;
  const int trials = b.type == ElementType::Hexahedron ? 200 : 1000;  // (folds between samples are rarer on simplices)
  for (int trial = 0; trial < trials; ++trial) {
    const double amplitude = 0.05 + 0.25 * (trial % 10) / 10.0;
    const Eigen::MatrixXd X = cell_coordinates(mesh, b, 0) + amplitude * Eigen::MatrixXd::Random(mesh.dim, b.n_nodes_per_cell());
    double lowest = std::numeric_limits<double>::infinity();
    for (int q = 0; q < t.n_points(); ++q) lowest = std::min(lowest, jacobian(X, t, q).determinant());
    const double bounded = min_jacobian_det(b.type, b.order, X);
    if (lowest < 0.0) {
      EXPECT_LE(bounded, 0.0) << "trial " << trial << ": det A = " << lowest << " on the fine lattice";
      if (min_jacobian_det(b.type, b.order, X, keep) > 0.0) ++between;
    }
  }
  RecordProperty("folds_between_samples", between);
  // (P4 tetrahedra: the order-8 sample lattice left none of 1000 random folds between its points.)
  const bool p4_tet = b.type == ElementType::Tetrahedron && b.order == 4;
  if (!p4_tet && (b.order >= 3 || (b.order == 2 && !is_simplex(b.type)))) {
    EXPECT_GT(between, 0) << "no fold between the samples: the sweep does not test the bounds";
  }
}

INSTANTIATE_TEST_SUITE_P(AllCells, ValiditySweep, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());

// A P2 triangle whose edge node is pushed across the opposite corner folds inside, while
// det A stays positive at the corners: the dense samples must catch it.
TEST(Validity, CatchesAFoldBetweenTheCornersOfACurvedTriangle) {
  Eigen::MatrixXd X(2, 6);
  X << 0, 1, 0, 0.5, 0.5, 0.0,  //
      0, 0, 1, 0.0, 0.5, 0.5;
  EXPECT_GT(min_jacobian_det(ElementType::Triangle, 2, X), 0.0);
  X.col(3) << 0.5, 0.9;  // edge 0–1 midpoint pulled far inside
  EXPECT_LE(min_jacobian_det(ElementType::Triangle, 2, X), 0.0);
}

// A quadrilateral whose corner 3 lies on the diagonal through corners 0 and 2: det A = 0
// there and > 0 at every other sample; skipping that corner's samples leaves it positive.
TEST(Validity, SkippedSamplesAreLeftOut) {
  Eigen::MatrixXd X(2, 4);
  X << 0, 1, 1, 0.5,  //
      0, 0, 1, 0.5;
  EXPECT_NEAR(min_jacobian_det(ElementType::Quadrilateral, 1, X), 0.0, 1e-15);
  const ShapeTable& t = validity_samples(ElementType::Quadrilateral, 1);
  std::vector<std::uint8_t> skip(static_cast<std::size_t>(t.n_points()), 0);
  for (int q = 0; q < t.n_points(); ++q) skip[static_cast<std::size_t>(q)] = (t.points.col(q) - Eigen::Vector2d(-1, 1)).norm() < 1e-12;
  EXPECT_GT(min_jacobian_det(ElementType::Quadrilateral, 1, X, skip), 0.01);
  skip.pop_back();
  EXPECT_THROW(min_jacobian_det(ElementType::Quadrilateral, 1, X, skip), std::logic_error);
}

// invalid_cells flags exactly the cells that min_jacobian_det finds invalid, in block order.
TEST(Validity, InvalidCellsFlagsTheInvertedCellsInOrder) {
  auto mesh = structured_mesh(ElementType::Tetrahedron, 2, 2);
  auto& b = mesh.cells[0];
  const std::size_t swapped = b.n_cells() / 3;
  std::swap(b.cell(swapped)[0], b.cell(swapped)[1]);
  const std::vector<std::uint8_t> flags = invalid_cells(mesh);
  ASSERT_EQ(flags.size(), mesh.n_cells());
  for (std::size_t c = 0; c < b.n_cells(); ++c)
    EXPECT_EQ(flags[c] != 0, !(min_jacobian_det(b.type, b.order, cell_coordinates(mesh, b, c)) > 0.0)) << "cell " << c;
  EXPECT_EQ(flags[swapped], 1);
  EXPECT_EQ(count_invalid_cells(mesh), static_cast<std::size_t>(std::count(flags.begin(), flags.end(), std::uint8_t{1})));
}

TEST(Validity, NanCoordinatesAreInvalid) {
  auto mesh = structured_mesh(ElementType::Tetrahedron, 1, 1);
  mesh.x(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_GE(count_invalid_cells(mesh), 1u);
}

// A P3 tetrahedron folded between its validity samples (a random one of a seeded sweep):
// fold_samples gives points of the reference cell, det A ≤ 0 at one of them at least, which the
// samples miss; on a valid cell it gives none.
TEST(Validity, FoldSamplesSeeTheFoldBetweenTheSamples) {
  const auto mesh = structured_mesh(ElementType::Tetrahedron, 3, 1);
  const auto& b = mesh.cells[0];
  const std::vector<std::uint8_t> keep(static_cast<std::size_t>(validity_samples(b.type, b.order).n_points()), 0);
  EXPECT_EQ(fold_samples(b.type, b.order, cell_coordinates(mesh, b, 0)).cols(), 0);
  std::srand(11);
  int folds = 0;
  for (int trial = 0; trial < 1000 && folds < 3; ++trial) {
    const double amplitude = 0.05 + 0.25 * (trial % 10) / 10.0;
    const Eigen::MatrixXd X = cell_coordinates(mesh, b, 0) + amplitude * Eigen::MatrixXd::Random(3, b.n_nodes_per_cell());
    if (!(min_jacobian_det(b.type, b.order, X, keep) > 0.0) || min_jacobian_det(b.type, b.order, X) > 0.0) continue;
    ++folds;
    const Eigen::MatrixXd points = fold_samples(b.type, b.order, X);
    ASSERT_GT(points.cols(), 0) << "trial " << trial;
    const ShapeTable t = tabulate(b.type, b.order, points);
    double lowest = std::numeric_limits<double>::infinity();
    for (int q = 0; q < t.n_points(); ++q) lowest = std::min(lowest, jacobian(X, t, q).determinant());
    EXPECT_LE(lowest, 0.0) << "trial " << trial;
    EXPECT_LE(points.colwise().sum().maxCoeff(), 1.0 + 1e-12);  // inside the reference cell
    EXPECT_GE(points.minCoeff(), -1e-12);
  }
  EXPECT_GT(folds, 0) << "no fold between the samples: the sweep does not test fold_samples";
}

}  // namespace
}  // namespace meshmorph

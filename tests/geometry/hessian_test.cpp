// SPDX-License-Identifier: MIT
// LevelSetFunction::hessian: every kind against five-point differences of gradient(), the
// closed forms against known curvatures, and symmetry.
#include <cmath>
#include <string>
#include <vector>

#include <random>

#include <gtest/gtest.h>

#include "geometry/level_set_fixtures.h"
#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/structured.h"

namespace meshmorph {
namespace {

using test::vec;

/// H(x) is symmetric and matches differences of ∇σ (step 1e-4: the points stay ≥ 0.05 from
/// kinks, so the truncation error is ≈ (1e-4/0.05)⁴ relative; rounding of an exact
/// gradient ≈ 1e-16/1e-4).
void expect_hessian_matches_gradient(const LevelSetFunction& f, const Eigen::VectorXd& x, double tol = 1e-8) {
  SCOPED_TRACE(testing::Message() << "x = " << x.transpose());
  const Eigen::MatrixXd H = f.hessian(x);
  ASSERT_EQ(H.rows(), f.dim());
  ASSERT_EQ(H.cols(), f.dim());
  EXPECT_TRUE(H == H.transpose()) << H;
  const auto gradient = [&](const Eigen::VectorXd& y) { return f.gradient(y); };
  test::expect_hessian_matches_fd(gradient, x, H, 1e-4, tol);
}

// By const reference and emplace: GCC 12 warns (maybe-uninitialized) about variants built
// from aggregate temporaries.
template <class Shape>
LevelSetFunction compile(const Shape& shape, int dim) {
  LevelSet ls;
  ls.shape.emplace<Shape>(shape);
  return {ls, dim};
}

TEST(LevelSetHessian, SphereAndCircleAreProjectorsOverTheDistance) {
  const LevelSetFunction sphere = compile(SphereLevelSet{vec({0.1, -0.2, 0.3}), 0.5}, 3);
  for (const auto& x : {vec({1, 0.4, -0.2}), vec({0.2, 0.1, 0.35}), vec({-2, 3, 1})}) expect_hessian_matches_gradient(sphere, x);
  // At distance 2 along x: curvature 1/2 in the two tangent directions, 0 along the normal.
  EXPECT_LE((sphere.hessian(vec({2.1, -0.2, 0.3})) - Eigen::Vector3d(0, 0.5, 0.5).asDiagonal().toDenseMatrix()).norm(),
            1e-15);
  const LevelSetFunction circle = compile(SphereLevelSet{vec({0.5, 0.5}), 0.3}, 2);
  for (const auto& x : {vec({0.9, 0.1}), vec({0.55, 0.6})}) expect_hessian_matches_gradient(circle, x);
  EXPECT_LE((circle.hessian(vec({0.5, 1.5})) - Eigen::Vector2d(1, 0).asDiagonal().toDenseMatrix()).norm(), 1e-15);
  // At the centre the direction, and so the curvature, is undefined.
  EXPECT_TRUE(circle.hessian(vec({0.5, 0.5})).array().isNaN().all());
}

TEST(LevelSetHessian, CylinderIsFlatAlongItsAxis) {
  const LevelSetFunction cylinder = compile(CylinderLevelSet{vec({0.1, 0.2, 0.3}), vec({1, 2, 2}), 0.4}, 3);
  for (const auto& x : {vec({1, 0.4, -0.2}), vec({0.3, 0.1, 0.5}), vec({-2, 3, 1})}) expect_hessian_matches_gradient(cylinder, x);
  const LevelSetFunction z_axis = compile(CylinderLevelSet{vec({0, 0, 0}), vec({0, 0, 3}), 1}, 3);
  EXPECT_LE((z_axis.hessian(vec({0, 4, 7})) - Eigen::Vector3d(0.25, 0, 0).asDiagonal().toDenseMatrix()).norm(), 1e-15);
  EXPECT_TRUE(z_axis.hessian(vec({0, 0, 2})).array().isNaN().all());
}

TEST(LevelSetHessian, PlaneIsZero) {
  const LevelSetFunction plane = compile(PlaneLevelSet{vec({0.1, 0.2, 0.3}), vec({1, -1, 2})}, 3);
  EXPECT_EQ(plane.hessian(vec({3, 2, 1})), Eigen::Matrix3d::Zero());
}

TEST(LevelSetHessian, BoxIsZeroInsideAndBesideFacesCurvedBeyondEdgesAndCorners) {
  const LevelSetFunction box = compile(BoxLevelSet{vec({0.5, 0.5, 0.5}), vec({1, 2, 0.5})}, 3);
  EXPECT_EQ(box.hessian(vec({0.4, 0.3, 0.6})), Eigen::Matrix3d::Zero());  // inside
  EXPECT_EQ(box.hessian(vec({1.5, 0.3, 0.6})), Eigen::Matrix3d::Zero());  // beside the face x = 1
  for (const auto& x : {vec({1.5, 1.9, 0.6}), vec({1.3, 0.3, 1.2}), vec({-0.4, -0.8, -0.3}), vec({1.2, 1.7, 1.1})})
    expect_hessian_matches_gradient(box, x);
  // Beyond the edge x = 1, y = 1.5: a cylinder of radius ρ around it.
  const Eigen::MatrixXd H = box.hessian(vec({1.3, 1.9, 0.6}));
  EXPECT_NEAR(H.trace(), 1 / 0.5, 1e-14);
  EXPECT_NEAR(H(2, 2), 0, 1e-15);
  const LevelSetFunction square = compile(BoxLevelSet{vec({0, 0}), vec({2, 2})}, 2);
  expect_hessian_matches_gradient(square, vec({1.5, -1.2}));
  EXPECT_EQ(square.hessian(vec({0.2, 0.3})), Eigen::Matrix2d::Zero());
}

TEST(LevelSetHessian, TorusHasTheTubeAndRingCurvatures) {
  const LevelSetFunction torus = compile(TorusLevelSet{vec({0.1, 0.2, 0.3}), vec({1, 1, 0}), 1.0, 0.3}, 3);
  for (const auto& x : {vec({1, 0.4, -0.2}), vec({0.6, -0.2, 0.9}), vec({-2, 3, 1}), vec({0.2, 0.1, 0.5})})
    expect_hessian_matches_gradient(torus, x);
  // At the outer equator (distance ρ = R + r from the axis): 1/r across the tube, 1/(R + r)
  // around the axis, 0 along the normal.
  const LevelSetFunction flat = compile(TorusLevelSet{vec({0, 0, 0}), vec({0, 0, 1}), 1.0, 0.25}, 3);
  const Eigen::MatrixXd H = flat.hessian(vec({1.25, 0, 0}));
  EXPECT_LE((H - Eigen::Vector3d(0, 1 / 1.25, 4).asDiagonal().toDenseMatrix()).norm(), 1e-14) << H;
  EXPECT_TRUE(flat.hessian(vec({0, 0, 0.5})).array().isNaN().all());  // on the axis
  EXPECT_TRUE(flat.hessian(vec({0, 1, 0})).array().isNaN().all());    // on the core circle
}

TEST(LevelSetHessian, ExpressionsByDifferencesOfTheirGradient) {
  const LevelSetFunction poly = compile(ExprLevelSet{"x^2 + 3*x*y - y^3 + z"}, 3);
  for (const auto& x : {vec({0.3, -0.7, 0.1}), vec({2, 1, 5})}) {
    Eigen::Matrix3d exact;
    exact << 2, 3, 0, 3, -6 * x(1), 0, 0, 0, 0;
    const Eigen::MatrixXd H = poly.hessian(x);
    EXPECT_LE((H - exact).norm(), 1e-7 * std::max(1.0, x.squaredNorm())) << H;
    EXPECT_EQ(H, H.transpose());
  }
  // The same circle as an expression and in closed form.
  const LevelSetFunction expr = compile(ExprLevelSet{"sqrt((x-0.5)^2 + (y-0.5)^2) - 0.3"}, 2);
  const LevelSetFunction exact = compile(SphereLevelSet{vec({0.5, 0.5}), 0.3}, 2);
  for (const auto& x : {vec({0.9, 0.1}), vec({0.55, 0.8})})
    EXPECT_LE((expr.hessian(x) - exact.hessian(x)).norm(), 1e-7) << expr.hessian(x);
}

TEST(LevelSetHessian, CsgTakesTheActiveOperand) {
  const LevelSet a = test::sphere(vec({0, 0}), 1);
  const LevelSet b = test::sphere(vec({1.5, 0}), 1);
  const LevelSetFunction fa(a, 2), fb(b, 2);
  const LevelSetFunction uni(test::level_set(UnionLevelSet{{a, b}}), 2);
  const LevelSetFunction diff(test::level_set(DifferenceLevelSet{{a, b}}), 2);
  const LevelSetFunction inter(test::level_set(IntersectionLevelSet{{a, b}}), 2);
  const Eigen::VectorXd left = vec({-0.5, 0.3}), right = vec({2.2, -0.4}), middle = vec({0.6, 0.1});
  EXPECT_EQ(uni.hessian(left), fa.hessian(left));
  EXPECT_EQ(uni.hessian(right), fb.hessian(right));
  EXPECT_EQ(inter.hessian(left), fb.hessian(left));
  EXPECT_EQ(diff.hessian(middle), -fb.hessian(middle));  // max(a, −b) with −b active
  EXPECT_EQ(diff.hessian(left), fa.hessian(left));
  for (const auto* f : {&uni, &diff, &inter})
    for (const auto& x : {left, right, middle}) expect_hessian_matches_gradient(*f, x);
}

TEST(LevelSetHessian, BlendedCsgAddsTheBlendsCurvature) {
  // The paper 003 §4.2 domain with its edges rounded (blend 0.05): points inside and outside
  // the blends, 3D; and two circles in 2D.
  const auto cylinder = [](Eigen::Vector3d axis) {
    return test::level_set(CylinderLevelSet{vec({0.5, 0.5, 0.5}), axis, 0.15});
  };
  const double k = 0.05;
  const LevelSet box = test::level_set(BoxLevelSet{vec({0.5, 0.5, 0.5}), vec({0.5, 0.5, 0.5})});
  const LevelSet ball = test::sphere(vec({0.5, 0.5, 0.5}), 0.3);
  const LevelSet body = test::level_set(IntersectionLevelSet{{box, ball}, k});
  const LevelSet cx = cylinder({1, 0, 0}), cy = cylinder({0, 1, 0}), cz = cylinder({0, 0, 1});
  const LevelSet holes = test::level_set(UnionLevelSet{{cx, cy, cz}, k});
  const LevelSet solid = test::level_set(DifferenceLevelSet{{body, holes}, k});
  const LevelSetFunction f(solid, 3);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 0.8);
  for (int i = 0; i < 40; ++i) {
    const Eigen::VectorXd x = vec({u(rng), u(rng), u(rng)});
    expect_hessian_matches_gradient(f, x, 1e-6);
  }
  const LevelSet a = test::sphere(vec({0, 0}), 1), b = test::sphere(vec({1.5, 0}), 1);
  const LevelSet uab = test::level_set(UnionLevelSet{{a, b}, 0.3}), dab = test::level_set(DifferenceLevelSet{{a, b}, 0.3});
  for (const LevelSetFunction& g : {LevelSetFunction(uab, 2), LevelSetFunction(dab, 2)})
    for (const auto& x : {vec({0.75, 0.7}), vec({0.8, -0.62}), vec({-0.5, 0.3})}) expect_hessian_matches_gradient(g, x);
}

TEST(LevelSetHessian, MeshFieldsDifferentiateThePolynomialOfTheCellHoldingThePoint) {
  // A quadratic field on P2 triangles: the Hessian is the constant one of the field, also
  // next to cell boundaries (the stencil stays with one cell's polynomial).
  Mesh m = structured_mesh(ElementType::Triangle, 2, 4);
  Eigen::VectorXd values(m.x.cols());
  for (Eigen::Index j = 0; j < values.size(); ++j) {
    const double x = m.x(0, j), y = m.x(1, j);
    values(j) = x * x + 0.5 * x * y - 2 * y * y + x - 0.3;
  }
  const LevelSetFunction p2(m, values);
  Eigen::Matrix2d exact;
  exact << 2, 0.5, 0.5, -4;
  for (const auto& x : {vec({0.3, 0.4}), vec({0.25 + 1e-9, 0.6}), vec({0.5, 0.5}), vec({0.9, 0.05})}) {
    const Eigen::MatrixXd H = p2.hessian(x);
    EXPECT_LE((H - exact).norm(), 1e-8) << "x = " << x.transpose() << "\n" << H;
    EXPECT_EQ(H, H.transpose());
  }
  // P1 on simplices: the gradient is constant in a cell, so the Hessian is 0 (even on a
  // cell boundary, where differences of gradient() would see the jump).
  Mesh m1 = structured_mesh(ElementType::Tetrahedron, 1, 3);
  Eigen::VectorXd v1(m1.x.cols());
  for (Eigen::Index j = 0; j < v1.size(); ++j) v1(j) = (m1.x.col(j) - vec({0.5, 0.5, 0.5})).norm() - 0.3;
  const LevelSetFunction p1(m1, v1);
  for (const auto& x : {vec({0.3, 0.4, 0.2}), vec({1.0 / 3, 0.5, 0.5})}) EXPECT_LE(p1.hessian(x).norm(), 1e-10);
  // A cubic on Q3 quadrilaterals: the cell's polynomial, differentiated exactly.
  Mesh q = structured_mesh(ElementType::Quadrilateral, 3, 2);
  Eigen::VectorXd vq(q.x.cols());
  for (Eigen::Index j = 0; j < vq.size(); ++j) vq(j) = std::pow(q.x(0, j), 3) - q.x(0, j) * q.x(1, j);
  const LevelSetFunction q3(q, vq);
  for (const auto& x : {vec({0.3, 0.4}), vec({0.7, 0.2})}) {
    expect_hessian_matches_gradient(q3, x, 1e-7);
    Eigen::Matrix2d exact_q;
    exact_q << 6 * x(0), -1, -1, 0;
    EXPECT_LE((q3.hessian(x) - exact_q).norm(), 1e-11);
  }
  // Q2 hexahedra (the cells of a distance field): the exact Hessian of a field in the space.
  Mesh h = structured_mesh(ElementType::Hexahedron, 2, 2);
  Eigen::VectorXd vh(h.x.cols());
  for (Eigen::Index j = 0; j < vh.size(); ++j) vh(j) = h.x(0, j) * h.x(1, j) * h.x(2, j) - h.x(2, j) * h.x(2, j);
  const LevelSetFunction q2(h, vh);
  for (const auto& x : {vec({0.3, 0.4, 0.6}), vec({0.5, 0.25, 0.9})}) {
    Eigen::Matrix3d exact3;
    exact3 << 0, x(2), x(1), x(2), 0, x(0), x(1), x(0), -2;
    const Eigen::MatrixXd H = q2.hessian(x);
    EXPECT_LE((H - exact3).norm(), 1e-12) << "x = " << x.transpose() << "\n" << H;
    EXPECT_TRUE(H == H.transpose());
  }
}

TEST(LevelSetHessian, CurvedBackgroundCellsDifferentiateTheirIsoparametricField) {
  // P2 triangles bent by a smooth map: their maps are not affine, so points are located by
  // Newton and the Hessian is differenced.
  Mesh m = structured_mesh(ElementType::Triangle, 2, 3);
  for (Eigen::Index j = 0; j < m.x.cols(); ++j) {
    const double x = m.x(0, j), y = m.x(1, j);
    m.x(0, j) = x + 0.08 * std::sin(3 * y);
    m.x(1, j) = y + 0.06 * x * x;
  }
  Eigen::VectorXd values(m.x.cols());
  for (Eigen::Index j = 0; j < values.size(); ++j) values(j) = std::cos(2 * m.x(0, j)) + m.x(1, j) * m.x(1, j);
  const LevelSetFunction f(m, values);
  // σ at x(ξ) is the cell's interpolant Σ φ_a N_a(ξ).
  const CellBlock& block = m.cells.front();
  const LagrangeBasis& basis = lagrange_basis(block.type, block.order);
  for (std::size_t c : {std::size_t{0}, std::size_t{7}, std::size_t{13}}) {
    const Eigen::VectorXd xi = vec({0.2, 0.3});
    const Eigen::VectorXd N = basis.values(xi);
    Eigen::VectorXd x = Eigen::VectorXd::Zero(2);
    double expected = 0;
    for (int a = 0; a < basis.n(); ++a) {
      const std::int32_t node = block.cell(c)[a];
      x += N(a) * m.x.col(node);
      expected += N(a) * values(node);
    }
    EXPECT_NEAR(f.value(x), expected, 1e-13) << "cell " << c;
    expect_hessian_matches_gradient(f, x, 1e-6);
  }
}

}  // namespace
}  // namespace meshmorph

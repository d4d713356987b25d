// SPDX-License-Identifier: MIT
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "geometry/level_set_fixtures.h"

namespace meshmorph {
namespace {

using test::expect_closest_point;
using test::vec;

template <typename Shape>
LevelSetFunction make(const Shape& shape, int dim) {
  LevelSet ls;
  ls.shape.emplace<Shape>(shape);
  return {ls, dim};
}

/// Every primitive is an exact signed distance: at random points |x − p| = |σ(x)|,
/// p = x − σ∇σ (so x − p ∥ ∇σ), σ(p) = 0, |∇σ| = 1 and ∇σ matches differences.
void expect_signed_distance_properties(const LevelSetFunction& f, double box, int n = 40) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-box, box);
  for (int i = 0; i < n; ++i) {
    Eigen::VectorXd x(f.dim());
    for (int k = 0; k < f.dim(); ++k) x(k) = u(rng);
    SCOPED_TRACE(testing::Message() << "x = " << x.transpose());
    const double s = f.value(x);
    const Eigen::VectorXd g = f.gradient(x);
    EXPECT_NEAR(g.norm(), 1.0, 1e-14);
    const auto p = f.closest_point(x);
    ASSERT_TRUE(p.has_value());
    EXPECT_NEAR((*p - x).norm(), std::abs(s), 1e-13);
    EXPECT_LE((*p - (x - s * g)).norm(), 1e-13);
    EXPECT_LE(std::abs(f.value(*p)), 1e-13);
    test::expect_gradient_matches_fd(f, x);
  }
}

TEST(SphereLevelSet, ClosedFormsIn3D) {
  const LevelSetFunction f = make(SphereLevelSet{vec({1, 2, 3}), 2.0}, 3);
  EXPECT_DOUBLE_EQ(f.value(vec({4, 6, 3})), 3.0);
  EXPECT_DOUBLE_EQ(f.value(vec({1.3, 2.4, 3})), -1.5);
  EXPECT_LE((f.gradient(vec({4, 6, 3})) - vec({0.6, 0.8, 0})).norm(), 1e-15);
  expect_closest_point(f, vec({4, 6, 3}), vec({2.2, 3.6, 3}));
  expect_closest_point(f, vec({1.3, 2.4, 3}), vec({2.2, 3.6, 3}));
  // At the centre every surface point is closest: one of them, at distance r.
  const auto p = f.closest_point(vec({1, 2, 3}));
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR((*p - vec({1, 2, 3})).norm(), 2.0, 1e-15);
  expect_signed_distance_properties(f, 4);
}

TEST(SphereLevelSet, CircleIn2D) {
  const LevelSetFunction f = make(SphereLevelSet{vec({-1, 0.5}), 0.5}, 2);
  EXPECT_DOUBLE_EQ(f.value(vec({-1, 3})), 2.0);
  expect_closest_point(f, vec({-1, 3}), vec({-1, 1}));
  expect_closest_point(f, vec({-0.7, 0.9}), vec({-0.7, 0.9}));  // on the circle
  expect_signed_distance_properties(f, 3);
}

TEST(PlaneLevelSet, SignedDistanceToTheNormalSide) {
  const LevelSetFunction f = make(PlaneLevelSet{vec({0, 0, 1}), vec({0, 0, 2})}, 3);
  EXPECT_DOUBLE_EQ(f.value(vec({5, -2, 4})), 3.0);
  EXPECT_DOUBLE_EQ(f.value(vec({5, -2, -1})), -2.0);
  expect_closest_point(f, vec({5, -2, 4}), vec({5, -2, 1}));
  expect_signed_distance_properties(f, 3);
  const LevelSetFunction line = make(PlaneLevelSet{vec({1, 1}), vec({1, 1})}, 2);
  expect_closest_point(line, vec({0, 0}), vec({1, 1}));
  EXPECT_NEAR(line.value(vec({0, 0})), -std::sqrt(2.0), 1e-15);
  expect_signed_distance_properties(line, 3);
}

TEST(BoxLevelSet, OutsideFacesEdgesAndCornersIn3D) {
  const LevelSetFunction f = make(BoxLevelSet{vec({0, 0, 0}), vec({2, 4, 6})}, 3);
  EXPECT_DOUBLE_EQ(f.value(vec({3, 0.5, 1})), 2.0);  // face x = 1
  expect_closest_point(f, vec({3, 0.5, 1}), vec({1, 0.5, 1}));
  EXPECT_DOUBLE_EQ(f.value(vec({2, 3, 0})), std::sqrt(2.0));  // edge x = 1, y = 2
  expect_closest_point(f, vec({2, 3, 0}), vec({1, 2, 0}));
  EXPECT_LE((f.gradient(vec({2, 3, 0})) - vec({1, 1, 0}) / std::sqrt(2.0)).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(f.value(vec({-2, -4, 5})), 3.0);  // corner (−1, −2, 3)
  expect_closest_point(f, vec({-2, -4, 5}), vec({-1, -2, 3}));
  EXPECT_LE((f.gradient(vec({-2, -4, 5})) - vec({-1, -2, 2}) / 3.0).norm(), 1e-15);
}

TEST(BoxLevelSet, InsidePointsGoToTheNearestFace) {
  const LevelSetFunction f = make(BoxLevelSet{vec({0, 0, 0}), vec({2, 4, 6})}, 3);
  EXPECT_DOUBLE_EQ(f.value(vec({0.5, 0.1, 0.2})), -0.5);
  expect_closest_point(f, vec({0.5, 0.1, 0.2}), vec({1, 0.1, 0.2}));
  EXPECT_LE((f.gradient(vec({0.5, 0.1, 0.2})) - vec({1, 0, 0})).norm(), 0.0);
  EXPECT_DOUBLE_EQ(f.value(vec({-0.2, -1.5, 0.3})), -0.5);
  expect_closest_point(f, vec({-0.2, -1.5, 0.3}), vec({-0.2, -2, 0.3}));
  expect_closest_point(f, vec({0, 0, -2.9}), vec({0, 0, -3}));
  expect_signed_distance_properties(f, 5);
}

TEST(BoxLevelSet, RectangleIn2D) {
  const LevelSetFunction f = make(BoxLevelSet{vec({1, 1}), vec({2, 1})}, 2);  // [0, 2] × [0.5, 1.5]
  expect_closest_point(f, vec({3, 3}), vec({2, 1.5}));     // corner
  expect_closest_point(f, vec({1.2, -1}), vec({1.2, 0.5}));  // edge from outside
  expect_closest_point(f, vec({0.3, 1.1}), vec({0, 1.1}));   // inside
  EXPECT_DOUBLE_EQ(f.value(vec({0.3, 1.1})), -0.3);
  EXPECT_DOUBLE_EQ(f.value(vec({3, 3})), std::sqrt(1 + 1.5 * 1.5));
  expect_signed_distance_properties(f, 3);
}

TEST(CylinderLevelSet, DistanceFromTheAxisMinusRadius) {
  const LevelSetFunction f = make(CylinderLevelSet{vec({1, 0, 0}), vec({0, 0, 2}), 0.5}, 3);
  EXPECT_DOUBLE_EQ(f.value(vec({1.6, 0.8, 7})), 0.5);
  expect_closest_point(f, vec({1.6, 0.8, 7}), vec({1.3, 0.4, 7}));
  expect_closest_point(f, vec({1.06, 0.08, -3}), vec({1.3, 0.4, -3}));
  const LevelSetFunction tilted = make(CylinderLevelSet{vec({0.2, -0.1, 0.3}), vec({1, 2, -2}), 0.7}, 3);
  expect_signed_distance_properties(tilted, 3);
}

TEST(TorusLevelSet, DistanceFromTheCoreCircleMinusMinorRadius) {
  const LevelSetFunction f = make(TorusLevelSet{vec({0, 0, 0}), vec({0, 0, 3}), 2.0, 0.5}, 3);
  EXPECT_NEAR(f.value(vec({3, 0, 1})), std::sqrt(2.0) - 0.5, 1e-15);
  expect_closest_point(f, vec({3, 0, 1}), vec({2 + 0.5 / std::sqrt(2.0), 0, 0.5 / std::sqrt(2.0)}));
  expect_closest_point(f, vec({0, 2.1, 0}), vec({0, 2.5, 0}));  // inside the tube
  expect_closest_point(f, vec({0, -0.5, 0}), vec({0, -1.5, 0}));  // in the hole
  EXPECT_DOUBLE_EQ(f.value(vec({0, 0, 0})), 1.5);
  const LevelSetFunction tilted = make(TorusLevelSet{vec({0.3, 0.1, -0.2}), vec({1, 1, 1}), 1.5, 0.4}, 3);
  expect_signed_distance_properties(tilted, 2.5);
}

// LevelSetFunction::at answers as the separate calls, for a closed form (a box: its faces,
// edges and corners) and a difference of two of them.
TEST(LevelSetPoint, AnswersAsTheSeparateCalls) {
  LevelSet cut;
  cut.shape.emplace<DifferenceLevelSet>();
  auto& operands = std::get<DifferenceLevelSet>(cut.shape).operands;
  operands.resize(2);
  operands[0].shape.emplace<BoxLevelSet>(BoxLevelSet{vec({1, 0.5, 0.5}), vec({2, 1, 1})});
  operands[1].shape.emplace<SphereLevelSet>(SphereLevelSet{vec({2, 1, 1}), 0.5});
  for (const LevelSetFunction& f : {make(BoxLevelSet{vec({1, 0.5, 0.5}), vec({2, 1, 1})}, 3), LevelSetFunction(cut, 3)}) {
    std::mt19937 rng(2);
    std::uniform_real_distribution<double> u(-1.0, 3.0);
    for (int i = 0; i < 20; ++i) {
      const Eigen::VectorXd x = vec({u(rng), u(rng), u(rng)}), g = vec({u(rng), u(rng), u(rng)});
      SCOPED_TRACE(testing::Message() << "x = " << x.transpose());
      const LevelSetPoint at = f.at(x);
      EXPECT_EQ(at.value(), f.value(x));
      EXPECT_EQ(at.gradient(), f.gradient(x));
      const Eigen::ArrayXXd h = at.hessian().array(), h_f = f.hessian(x).array();
      EXPECT_TRUE((h == h_f || (h.isNaN() && h_f.isNaN())).all());
      EXPECT_EQ(at.stationarity(g), f.stationarity(x, g));
      EXPECT_EQ(at.step_normals(g), f.step_normals(x, g));
    }
  }
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "geometry/level_set_fixtures.h"

namespace meshmorph {
namespace {

using test::expect_closest_point;
using test::sphere;
using test::vec;

// Two unit circles centred 1.5 apart: they cross at (0.75, ±√0.4375).
const double kCrossY = std::sqrt(0.4375);
LevelSet circle_a() { return sphere(vec({0, 0}), 1.0); }
LevelSet circle_b() { return sphere(vec({1.5, 0}), 1.0); }

LevelSet csg(int op, std::vector<LevelSet> operands, double blend = 0.0) {
  if (op == 0) return test::level_set(UnionLevelSet{std::move(operands), blend});
  if (op == 1) return test::level_set(IntersectionLevelSet{std::move(operands), blend});
  return test::level_set(DifferenceLevelSet{std::move(operands), blend});
}

/// The box [c − s/2, c + s/2] as the intersection of 2·dim half-spaces.
LevelSet box_of_planes(const Eigen::VectorXd& c, const Eigen::VectorXd& s) {
  std::vector<LevelSet> planes;
  for (Eigen::Index k = 0; k < c.size(); ++k)
    for (double side : {-1.0, 1.0}) {
      Eigen::VectorXd n = Eigen::VectorXd::Zero(c.size()), p = c;
      n(k) = side;
      p(k) += side * s(k) / 2;
      planes.push_back(test::level_set(PlaneLevelSet{p, n}));
    }
  return csg(1, std::move(planes));
}

TEST(CsgLevelSet, ValuesAreMinMaxAndGradientsOfTheActiveOperand) {
  const LevelSetFunction u(csg(0, {circle_a(), circle_b()}), 2);
  const LevelSetFunction i(csg(1, {circle_a(), circle_b()}), 2);
  const LevelSetFunction d(csg(2, {circle_a(), circle_b()}), 2);
  const LevelSetFunction a(circle_a(), 2), b(circle_b(), 2);
  for (const Eigen::VectorXd& x : {vec({-0.4, 0.3}), vec({2.0, -1.0}), vec({0.9, 0.2}), vec({0.3, 1.7})}) {
    SCOPED_TRACE(testing::Message() << "x = " << x.transpose());
    EXPECT_EQ(u.value(x), std::min(a.value(x), b.value(x)));
    EXPECT_EQ(i.value(x), std::max(a.value(x), b.value(x)));
    EXPECT_EQ(d.value(x), std::max(a.value(x), -b.value(x)));
    EXPECT_EQ(u.gradient(x), a.value(x) <= b.value(x) ? a.gradient(x) : b.gradient(x));
    EXPECT_EQ(d.gradient(x), a.value(x) >= -b.value(x) ? a.gradient(x) : Eigen::VectorXd(-b.gradient(x)));
    for (const auto* f : {&u, &i, &d}) test::expect_gradient_matches_fd(*f, x);
  }
}

TEST(CsgLevelSet, BlendSmoothsOnlyWhereTheOperandsAreWithinIt) {
  const double k = 0.3;
  const LevelSetFunction a(circle_a(), 2), b(circle_b(), 2);
  for (int op : {0, 1, 2}) {
    const LevelSetFunction sharp(csg(op, {circle_a(), circle_b()}), 2), round(csg(op, {circle_a(), circle_b()}, k), 2);
    for (const Eigen::VectorXd& x : {vec({-0.4, 0.3}), vec({2.0, -1.0}), vec({0.9, 0.2}), vec({0.75, 0.7}),
                                     vec({0.8, -0.62}), vec({0.3, 1.7})}) {
      SCOPED_TRACE(testing::Message() << "op " << op << ", x = " << x.transpose());
      const double va = a.value(x), vb = op == 2 ? -b.value(x) : b.value(x), t = va - vb;
      const double sign = op == 0 ? 1.0 : -1.0;
      if (std::abs(t) >= k) EXPECT_EQ(round.value(x), sharp.value(x));
      else EXPECT_NEAR(round.value(x), 0.5 * (va + vb) - sign * (k / 4 + t * t / (4 * k)), 1e-15);
      // The union grows and the intersection shrinks, by at most k/4.
      EXPECT_LE(sign * (round.value(x) - sharp.value(x)), 0.0);
      EXPECT_LE(std::abs(round.value(x) - sharp.value(x)), k / 4 + 1e-15);
      test::expect_gradient_matches_fd(round, x);
    }
  }
}

TEST(CsgLevelSet, BlendedCornerOfTwoHalfPlanesIsCutBackByAQuarterOfTheBlend) {
  // x ≤ 0 ∩ y ≤ 0 with blend k: on the bisector σ = x + k/4 + 0, so the zero set crosses it
  // at (−k/4, −k/4); along x = −1 (|a − b| ≥ k) it is the sharp y = 0.
  const double k = 0.2;
  const LevelSet left = test::level_set(PlaneLevelSet{vec({0, 0}), vec({1, 0})});
  const LevelSet below = test::level_set(PlaneLevelSet{vec({0, 0}), vec({0, 1})});
  const LevelSetFunction corner(csg(1, {left, below}, k), 2);
  EXPECT_NEAR(corner.value(vec({-k / 4, -k / 4})), 0.0, 1e-15);
  EXPECT_EQ(corner.value(vec({-1, 0})), 0.0);
  // Its closest point from outside the rounded corner lies on it, straight along ∇σ.
  const std::optional<Eigen::VectorXd> p = corner.closest_point(vec({0.3, 0.25}));
  ASSERT_TRUE(p.has_value());
  EXPECT_LE(std::abs(corner.value(*p)), 1e-12);
  EXPECT_LE(test::tangential_residual(corner, vec({0.3, 0.25}), *p), 1e-10);
  EXPECT_LT((*p - vec({0, 0})).norm(), k);  // on the rounding, not on a sharp face
}

TEST(CsgLevelSet, UnionOfTwoCirclesClosestPoints) {
  const LevelSetFunction u(csg(0, {circle_a(), circle_b()}), 2);
  expect_closest_point(u, vec({-3, 0}), vec({-1, 0}));
  expect_closest_point(u, vec({3, 1}), vec({1.5, 0}) + vec({1.5, 1}).normalized());
  expect_closest_point(u, vec({0.7, 2}), vec({0.7, 2}).normalized());
  // Inside both circles near the cusp: each circle's own closest point lies inside the
  // other one, so the answer is the crossing point.
  expect_closest_point(u, vec({0.75, 0.5}), vec({0.75, kCrossY}));
  expect_closest_point(u, vec({0.8, -0.3}), vec({0.75, -kCrossY}));
  const auto p = u.closest_point(vec({0.75, 0}));  // two crossings equally close
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR((*p - vec({0.75, 0})).norm(), kCrossY, 1e-12);
}

TEST(CsgLevelSet, IntersectionAndDifferenceOfTwoCircles) {
  const LevelSetFunction lens(csg(1, {circle_a(), circle_b()}), 2);
  expect_closest_point(lens, vec({0.75, 3}), vec({0.75, kCrossY}));  // the lens's corner
  expect_closest_point(lens, vec({0.7, 0.1}), vec({1.5, 0}) + vec({-0.8, 0.1}).normalized());
  const LevelSetFunction moon(csg(2, {circle_a(), circle_b()}), 2);
  expect_closest_point(moon, vec({1.2, 0}), vec({0.5, 0}));  // inside the removed circle
  expect_closest_point(moon, vec({-2, 0}), vec({-1, 0}));
  // From (2, 1) circle a's own closest point lies inside b and b's outside a: the corner.
  expect_closest_point(moon, vec({2, 1}), vec({0.75, kCrossY}));
}

TEST(CsgLevelSet, HalfSpacesReproduceTheBoxIn2DAnd3D) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(testing::Message() << dim << "D");
    const Eigen::VectorXd c = dim == 2 ? vec({0.5, -0.25}) : vec({0.5, -0.25, 1});
    const Eigen::VectorXd s = dim == 2 ? vec({2, 1}) : vec({2, 1, 3});
    const LevelSetFunction planes(box_of_planes(c, s), dim);
    const LevelSetFunction box(test::level_set(BoxLevelSet{c, s}), dim);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-3, 3);
    for (int i = 0; i < 40; ++i) {
      Eigen::VectorXd x(dim);
      for (int k = 0; k < dim; ++k) x(k) = c(k) + u(rng);
      expect_closest_point(planes, x, *box.closest_point(x));  // faces, edges and corners
      if (box.value(x) < 0) {
        EXPECT_NEAR(planes.value(x), box.value(x), 1e-15);
      }
    }
  }
}

TEST(CsgLevelSet, NestedTreesAndExpressionLeavesAgreeWithPrimitives) {
  const Eigen::VectorXd c = vec({0, 0}), s = vec({1.6, 0.8});
  const LevelSetFunction nested(csg(0, {box_of_planes(c, s), sphere(vec({0.8, 0.4}), 0.5)}), 2);
  const LevelSetFunction flat(csg(0, {test::level_set(BoxLevelSet{c, s}), sphere(vec({0.8, 0.4}), 0.5)}), 2);
  const LevelSetFunction exprs(csg(0, {test::expr("sqrt(x^2+y^2)-1"), test::expr("sqrt((x-1.5)^2+y^2)-1")}), 2);
  const LevelSetFunction circles(csg(0, {circle_a(), circle_b()}), 2);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  for (int i = 0; i < 30; ++i) {
    const Eigen::VectorXd x = vec({u(rng), u(rng)});
    expect_closest_point(nested, x, *flat.closest_point(x));
    expect_closest_point(exprs, x + vec({0.75, 0}), *circles.closest_point(x + vec({0.75, 0})), 1e-10);
  }
}

}  // namespace
}  // namespace meshmorph

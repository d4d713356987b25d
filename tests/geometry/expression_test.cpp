// SPDX-License-Identifier: MIT
#include <cmath>
#include <numbers>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "geometry/level_set_fixtures.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

using std::numbers::pi;
using test::vec;

TEST(ExprLevelSet, EvaluatesInXYZWithPi) {
  const LevelSetFunction f(test::expr("x^2 + 2*y - z"), 3);
  EXPECT_DOUBLE_EQ(f.value(vec({1, 2, 3})), 2.0);
  const LevelSetFunction s(test::expr("sin(pi*x) + y"), 2);
  EXPECT_NEAR(s.value(vec({0.5, -1})), 0.0, 1e-15);
}

TEST(ExprLevelSet, GradientMatchesClosedFormIn2D) {
  const LevelSetFunction f(test::expr("y - 0.75 - 0.25*sin(pi*(0.5+2*x))"), 2);
  for (double x : {-0.7, 0.0, 0.13, 0.5, 1.9}) {
    const Eigen::VectorXd p = vec({x, 0.3});
    const Eigen::VectorXd g = vec({-0.25 * std::cos(pi * (0.5 + 2 * x)) * 2 * pi, 1});
    EXPECT_LE((f.gradient(p) - g).norm(), 1e-10 * g.norm()) << "x = " << x;
  }
}

TEST(ExprLevelSet, GradientMatchesClosedFormIn3DAtLargeCoordinates) {
  const LevelSetFunction f(test::expr("x*y*z + exp(x/10)"), 3);
  for (const Eigen::VectorXd& p : {vec({0.1, -0.2, 0.3}), vec({12, 7, -30}), vec({-150, 80, 40})}) {
    const Eigen::VectorXd g = vec({p(1) * p(2) + std::exp(p(0) / 10) / 10, p(0) * p(2), p(0) * p(1)});
    EXPECT_LE((f.gradient(p) - g).norm(), 1e-11 * std::max(1.0, g.norm())) << "x = " << p.transpose();
  }
}

TEST(ExprLevelSet, CircleClosestPointsMatchTheSphere) {
  const LevelSetFunction e(test::expr("sqrt(x^2+y^2)-1"), 2);
  const LevelSetFunction s(test::sphere(vec({0, 0}), 1.0), 2);
  // Outside far beyond the centre of curvature (the undamped step would diverge), near,
  // inside, and close to the centre.
  for (const Eigen::VectorXd& x : {vec({5, 3}), vec({-1.2, 0.4}), vec({0.3, -0.6}), vec({0.05, 0.02}),
                                   vec({-40, -0.5})}) {
    SCOPED_TRACE(testing::Message() << "x = " << x.transpose());
    const auto p = e.closest_point(x);
    ASSERT_TRUE(p.has_value());
    EXPECT_LE((*p - *s.closest_point(x)).norm(), 1e-10);
    EXPECT_LE(std::abs(e.value(*p)), 1e-14);
    EXPECT_LE(test::tangential_residual(e, x, *p), 1e-10 * std::max(1.0, x.norm()));
  }
}

TEST(ExprLevelSet, NonDistanceSphereIn3D) {
  const LevelSetFunction e(test::expr("x^2+y^2+z^2-4"), 3);
  const LevelSetFunction s(test::sphere(vec({0, 0, 0}), 2.0), 3);
  for (const Eigen::VectorXd& x : {vec({3, -1, 2}), vec({0.1, 0.2, -0.3}), vec({10, 10, 10})}) {
    const auto p = e.closest_point(x);
    ASSERT_TRUE(p.has_value());
    EXPECT_LE((*p - *s.closest_point(x)).norm(), 1e-10) << "x = " << x.transpose();
  }
}

TEST(ExprLevelSet, SineWallClosestPointIsOptimal) {
  const LevelSetFunction f(test::expr("y - 0.75 - 0.25*sin(pi*(0.5+2*x))"), 2);
  for (const Eigen::VectorXd& x : {vec({0.3, 0.9}), vec({0.1, 0.7}), vec({0.62, 0.45})}) {
    SCOPED_TRACE(testing::Message() << "x = " << x.transpose());
    const auto p = f.closest_point(x);
    ASSERT_TRUE(p.has_value());
    EXPECT_LE(std::abs(f.value(*p)), 1e-14);
    EXPECT_LE(test::tangential_residual(f, x, *p), 1e-10);
    // No sample of the curve within reach is closer.
    double nearest = 1e300;
    for (int i = -2000; i <= 4000; ++i) {
      const double t = i * 5e-4;
      nearest = std::min(nearest, std::hypot(t - x(0), 0.75 + 0.25 * std::sin(pi * (0.5 + 2 * t)) - x(1)));
    }
    EXPECT_LE((*p - x).norm(), nearest + 1e-12);
  }
}

TEST(ExprLevelSet, NoZeroSetGivesNoClosestPoint) {
  const LevelSetFunction f(test::expr("x^2+y^2+1"), 2);
  for (const Eigen::VectorXd& x : {vec({0, 0}), vec({1, 0.5}), vec({-30, 7})})
    EXPECT_FALSE(f.closest_point(x).has_value()) << "x = " << x.transpose();
  const LevelSetFunction flat(test::expr("1 + 0*x"), 3);
  EXPECT_FALSE(flat.closest_point(vec({1, 2, 3})).has_value());
}

TEST(ExprLevelSet, ConcurrentCallsGiveTheSerialResults) {
  const LevelSetFunction f(test::expr("sqrt((x-0.1)^2+y^2+(z+0.2)^2)-1 + 0.05*sin(3*x)"), 3);
  std::vector<Eigen::VectorXd> points;
  for (int i = 0; i < 60; ++i) points.push_back(vec({std::cos(i), std::sin(2.0 * i), 0.02 * i - 0.5}) * 1.4);
  std::vector<Eigen::VectorXd> serial;
  for (const auto& x : points) serial.push_back(*f.closest_point(x));
  std::vector<std::vector<Eigen::VectorXd>> parallel(4);
  std::vector<std::thread> threads;
  for (auto& out : parallel)
    threads.emplace_back([&f, &points, &out] {
      for (const auto& x : points) out.push_back(f.closest_point(x).value_or(Eigen::VectorXd()));
    });
  for (auto& t : threads) t.join();
  for (const auto& out : parallel)
    for (std::size_t i = 0; i < points.size(); ++i) EXPECT_EQ(out[i], serial[i]) << "point " << i;
}

TEST(ExprLevelSet, BadExpressionsNameTheKeyPath) {
  for (const char* bad : {"x +* y", "", "   ", "w + 1", "foo(x)", "(x + 1"}) {
    SCOPED_TRACE(bad);
    try {
      LevelSetFunction f(test::level_set(ExprLevelSet{bad}, "boundary[2].project"), 2, {"case.json", 1.0});
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("case.json: boundary[2].project.expr"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace meshmorph

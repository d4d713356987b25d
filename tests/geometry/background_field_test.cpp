// SPDX-License-Identifier: MIT
#include <cmath>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "geometry/level_set_fixtures.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"

namespace meshmorph {
namespace {

using test::vec;
using Field = std::function<double(const Eigen::VectorXd&)>;

LevelSetFunction sampled(ElementType type, int order, int n, const Field& f) {
  Mesh m = structured_mesh(type, order, n);
  Eigen::VectorXd values(static_cast<Eigen::Index>(m.n_nodes()));
  for (Eigen::Index j = 0; j < values.size(); ++j) values(j) = f(m.x.col(j));
  return {std::move(m), std::move(values)};
}

/// A field in the element's polynomial space is reproduced exactly, value and gradient
/// (the gradient against central differences of f, which are exact for quadratics).
void expect_reproduces(ElementType type, int order, const Field& f, int n = 3) {
  SCOPED_TRACE(testing::Message() << name_of(type) << " order " << order);
  const LevelSetFunction ls = sampled(type, order, n, f);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0.01, 0.99);
  for (int i = 0; i < 25; ++i) {
    Eigen::VectorXd x(ls.dim());
    for (int k = 0; k < ls.dim(); ++k) x(k) = u(rng);
    EXPECT_NEAR(ls.value(x), f(x), 1e-12) << "x = " << x.transpose();
    Eigen::VectorXd g(ls.dim());
    for (int k = 0; k < ls.dim(); ++k) {
      Eigen::VectorXd a = x, b = x;
      a(k) += 1e-3;
      b(k) -= 1e-3;
      g(k) = (f(a) - f(b)) / 2e-3;
    }
    EXPECT_LE((ls.gradient(x) - g).norm(), 1e-9) << "x = " << x.transpose();
  }
}

TEST(MeshLevelSet, ReproducesFieldsOfTheElementSpace) {
  const Field quadratic2 = [](const Eigen::VectorXd& x) { return x(0) * x(0) + 0.5 * x(0) * x(1) - x(1) + 0.3; };
  const Field quadratic3 = [](const Eigen::VectorXd& x) { return x(0) * x(2) - x(1) * x(1) + 0.2 * x(2) - 0.1; };
  const Field trilinear = [](const Eigen::VectorXd& x) { return 1 + x(0) - 2 * x(1) + x(0) * x(1) * x(2); };
  expect_reproduces(ElementType::Triangle, 2, quadratic2, 4);
  expect_reproduces(ElementType::Quadrilateral, 2, quadratic2);
  expect_reproduces(ElementType::Tetrahedron, 2, quadratic3);
  expect_reproduces(ElementType::Hexahedron, 1, trilinear);
  expect_reproduces(ElementType::Triangle, 4, quadratic2, 2);
}

TEST(MeshLevelSet, ExtrapolatesOutsideTheBackgroundMesh) {
  const Field linear = [](const Eigen::VectorXd& x) { return 0.3 + 2 * x(0) - x(1); };
  const LevelSetFunction ls = sampled(ElementType::Triangle, 1, 4, linear);
  for (const Eigen::VectorXd& x : {vec({1.5, -0.3}), vec({-2, 0.5}), vec({0.5, 7})}) {
    EXPECT_NEAR(ls.value(x), linear(x), 1e-12) << "x = " << x.transpose();
    EXPECT_LE((ls.gradient(x) - vec({2, -1})).norm(), 1e-12);
  }
}

TEST(MeshLevelSet, ClosestPointsOfAnInterpolatedCircleAndSphere) {
  const LevelSetFunction circle = sampled(ElementType::Triangle, 2, 6, [](const Eigen::VectorXd& x) {
    return (x(0) - 0.5) * (x(0) - 0.5) + (x(1) - 0.5) * (x(1) - 0.5) - 0.09;
  });
  const LevelSetFunction exact(test::sphere(vec({0.5, 0.5}), 0.3), 2);
  for (const Eigen::VectorXd& x : {vec({0.1, 0.1}), vec({0.55, 0.6}), vec({0.95, 0.4}), vec({0.5, 0.02})})
    test::expect_closest_point(circle, x, *exact.closest_point(x), 1e-10);
  const LevelSetFunction sphere = sampled(ElementType::Tetrahedron, 2, 3, [](const Eigen::VectorXd& x) {
    return (x - vec({0.5, 0.5, 0.5})).squaredNorm() - 0.09;
  });
  const LevelSetFunction exact3(test::sphere(vec({0.5, 0.5, 0.5}), 0.3), 3);
  for (const Eigen::VectorXd& x : {vec({0.1, 0.2, 0.9}), vec({0.45, 0.5, 0.6})})
    test::expect_closest_point(sphere, x, *exact3.closest_point(x), 1e-10);
}

TEST(MeshLevelSet, RejectsMismatchedFields) {
  Mesh m = structured_mesh(ElementType::Triangle, 1, 2);
  EXPECT_THROW(LevelSetFunction(m, Eigen::VectorXd::Zero(3)), InputError);
  Eigen::VectorXd bad = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m.n_nodes()));
  bad(0) = std::nan("");
  EXPECT_THROW(LevelSetFunction(m, bad), InputError);
  Mesh empty = m;
  empty.cells.clear();
  EXPECT_THROW(LevelSetFunction(empty, Eigen::VectorXd::Zero(static_cast<Eigen::Index>(m.n_nodes()))), InputError);
}

}  // namespace
}  // namespace meshmorph

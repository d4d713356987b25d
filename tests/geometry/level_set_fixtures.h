// SPDX-License-Identifier: MIT
#pragma once
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "meshmorph/geometry/level_set_function.h"
#include "support/derivative_check.h"

namespace meshmorph::test {

inline Eigen::VectorXd vec(std::initializer_list<double> v) {
  Eigen::VectorXd x(static_cast<Eigen::Index>(v.size()));
  Eigen::Index i = 0;
  for (double t : v) x(i++) = t;
  return x;
}

inline LevelSet level_set(decltype(LevelSet::shape) shape, std::string key_path = "boundary[0].project") {
  return LevelSet{std::move(shape), std::move(key_path)};
}

inline LevelSet sphere(Eigen::VectorXd c, double r) { return level_set(SphereLevelSet{std::move(c), r}); }
inline LevelSet expr(std::string e) { return level_set(ExprLevelSet{std::move(e)}); }

/// ∇σ against five-point differences of σ (step 1e-4: the test points stay ≥ 0.05 away
/// from kinks, so the truncation error is ≈ (1e-4/0.05)⁴ and rounding ≈ 1e-12).
inline void expect_gradient_matches_fd(const LevelSetFunction& f, const Eigen::VectorXd& x, double tol = 1e-8) {
  SCOPED_TRACE(testing::Message() << "x = " << x.transpose());
  auto value = [&](const Eigen::VectorXd& y) { return f.value(y); };
  Eigen::VectorXd fd(x.size());
  for (Eigen::Index i = 0; i < x.size(); ++i) fd(i) = five_point(value, x, static_cast<int>(i), 1e-4);
  EXPECT_LE((f.gradient(x) - fd).norm(), tol) << "gradient " << f.gradient(x).transpose() << " vs fd "
                                              << fd.transpose();
}

/// The closest point p of x: σ(p) ≈ 0, x − p ∥ ∇σ(p), and p equals `expected`.
inline void expect_closest_point(const LevelSetFunction& f, const Eigen::VectorXd& x,
                                 const Eigen::VectorXd& expected, double tol = 1e-12) {
  SCOPED_TRACE(testing::Message() << "x = " << x.transpose());
  const std::optional<Eigen::VectorXd> p = f.closest_point(x);
  ASSERT_TRUE(p.has_value());
  EXPECT_LE((*p - expected).norm(), tol) << "found " << p->transpose() << ", expected " << expected.transpose();
  EXPECT_LE(std::abs(f.value(*p)), tol);
}

/// x − p is parallel to ∇σ(p): its component orthogonal to ∇σ(p) vanishes.
inline double tangential_residual(const LevelSetFunction& f, const Eigen::VectorXd& x, const Eigen::VectorXd& p) {
  const Eigen::VectorXd n = f.gradient(p).normalized();
  const Eigen::VectorXd r = x - p;
  return (r - r.dot(n) * n).norm();
}

}  // namespace meshmorph::test

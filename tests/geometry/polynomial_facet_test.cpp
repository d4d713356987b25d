// SPDX-License-Identifier: MIT
// PolynomialFacet on randomly bent facets of every type and order, far from the origin: its
// monomial form against the Lagrange form, and its pruning bound, which must never exceed the
// distance to a point of the facet (else a closest-point search could skip the nearest facet).
#include "geometry/detail/polynomial_facet.h"

#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/mesh/element_type.h"

namespace meshmorph::detail {
namespace {

struct Kind {
  ElementType type;
  int order;
};

std::string name(const testing::TestParamInfo<Kind>& i) {
  return std::string(name_of(i.param.type)) + "_p" + std::to_string(i.param.order);
}

// The reference nodes bent into ℝ^d (d = 2 for lines), jittered and moved to (10, −5, 3).
Eigen::MatrixXd bent_nodes(const LagrangeBasis& basis, std::mt19937& rng) {
  std::uniform_real_distribution<double> jitter(-0.05, 0.05);
  const Eigen::MatrixXd& xi = basis.reference().nodes;
  const int d = basis.dim() + 1;
  Eigen::MatrixXd X(d, xi.cols());
  for (Eigen::Index a = 0; a < xi.cols(); ++a) {
    const double s = xi(0, a), t = d == 3 ? xi(1, a) : 0.0;
    Eigen::Vector3d x(s, t, 0.3 * std::sin(2.0 * s) + 0.2 * t * t);
    if (d == 2) x << s, 0.3 * std::sin(2.0 * s), 0.0;
    for (int k = 0; k < d; ++k) X(k, a) = x[k] + jitter(rng) + Eigen::Vector3d(10.0, -5.0, 3.0)[k];
  }
  return X;
}

// A random point of the reference facet.
FacetParam random_parameter(ElementType type, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  if (type == ElementType::Line) return FacetParam::Constant(1, 2.0 * u(rng) - 1.0);
  if (type == ElementType::Quadrilateral) return Eigen::Vector2d(2.0 * u(rng) - 1.0, 2.0 * u(rng) - 1.0);
  Eigen::Vector2d v(u(rng), u(rng));
  return v.sum() > 1.0 ? Eigen::Vector2d(1.0 - v[0], 1.0 - v[1]) : v;
}

Eigen::Vector3d lift(const Eigen::VectorXd& x) {
  Eigen::Vector3d y = Eigen::Vector3d::Zero();
  y.head(x.size()) = x;
  return y;
}

class PolynomialFacetKinds : public testing::TestWithParam<Kind> {};

// φ, ∂φ/∂u and ∂²φ/∂u² equal those of the Lagrange form to rounding (both invert a Vandermonde
// matrix: ~1e-14 of the facet's size at order 4). φ against x₀ + (X − x₀)N: N sums to 1 only to
// that rounding, which times coordinates ≈ 10 is ten times more.
TEST_P(PolynomialFacetKinds, MonomialsMatchTheLagrangeForm) {
  const LagrangeBasis& basis = lagrange_basis(GetParam().type, GetParam().order);
  std::mt19937 rng(1);
  const Eigen::MatrixXd X = bent_nodes(basis, rng);
  const PolynomialFacet facet(basis, X, {}, {});
  const Eigen::MatrixXd local = X.colwise() - X.col(0);
  for (int i = 0; i < 20; ++i) {
    const FacetParam u = random_parameter(basis.type(), rng);
    SCOPED_TRACE(testing::Message() << "u = " << u.transpose());
    const FacetPoint q = facet.evaluate(u);
    const Eigen::VectorXd uu = u, p = X.col(0) + local * basis.values(uu);
    EXPECT_LE((q.p - p).norm(), 5e-14);
    EXPECT_LE((facet.position(u) - p).norm(), 5e-14);
    EXPECT_LE((q.T - X * basis.gradients(uu)).norm(), 1e-11);
    EXPECT_LE((q.S - X * basis.hessians(uu)).norm(), 1e-10);
  }
}

// Zero at points of the facet, at most the distance to any point of it elsewhere, and
// positive beyond the facet's hull, so that it prunes.
TEST_P(PolynomialFacetKinds, LowerBoundNeverExceedsTheDistance) {
  const LagrangeBasis& basis = lagrange_basis(GetParam().type, GetParam().order);
  std::mt19937 rng(2);
  const Eigen::MatrixXd X = bent_nodes(basis, rng);
  const PolynomialFacet facet(basis, X, {}, {});
  std::vector<Eigen::VectorXd> on_facet;
  for (int i = 0; i < 400; ++i) on_facet.push_back(X * basis.values(Eigen::VectorXd(random_parameter(basis.type(), rng))));
  for (const Eigen::VectorXd& p : on_facet) EXPECT_EQ(facet.lower_bound2(lift(p)), 0.0) << p.transpose();
  std::uniform_real_distribution<double> offset(-1.5, 1.5);
  const Eigen::VectorXd center = X.rowwise().mean();
  for (int i = 0; i < 200; ++i) {
    Eigen::VectorXd x = center;
    for (Eigen::Index k = 0; k < x.size(); ++k) x[k] += offset(rng);
    double nearest = std::numeric_limits<double>::infinity();
    for (const Eigen::VectorXd& p : on_facet) nearest = std::min(nearest, (p - x).squaredNorm());
    EXPECT_LE(facet.lower_bound2(lift(x)), nearest) << x.transpose();
  }
  Eigen::VectorXd far = center;
  far[far.size() - 1] += 3.0;  // the bend spans less than 1 along the last axis
  EXPECT_GT(facet.lower_bound2(lift(far)), 1.0);
}

// From points near the facet (its map extended 0.3 beyond the reference facet, moved by up to
// 0.1: well inside the radius of curvature), a third of them nearest to an edge or corner:
// never farther than a point of the facet (the edges searched hold the minimum).
TEST_P(PolynomialFacetKinds, ClosestIsNoFartherThanAnyPointOfTheFacet) {
  const LagrangeBasis& basis = lagrange_basis(GetParam().type, GetParam().order);
  std::mt19937 rng(3);
  const Eigen::MatrixXd X = bent_nodes(basis, rng);
  const PolynomialFacet facet(basis, X, {}, {});
  std::vector<Eigen::VectorXd> on_facet;
  for (int i = 0; i < 2000; ++i) on_facet.push_back(X * basis.values(Eigen::VectorXd(random_parameter(basis.type(), rng))));
  std::uniform_real_distribution<double> beyond(-0.3, 0.3), offset(-0.1, 0.1);
  for (int i = 0; i < 100; ++i) {
    Eigen::VectorXd u = random_parameter(basis.type(), rng);
    if (i % 3 == 0) u += Eigen::VectorXd::NullaryExpr(u.size(), [&] { return beyond(rng); });
    Eigen::VectorXd x = X * basis.values(u);
    for (Eigen::Index k = 0; k < x.size(); ++k) x[k] += offset(rng);
    const FacetHit hit = facet.closest(x);
    EXPECT_NEAR(hit.dist2, (hit.at.p - x).squaredNorm(), 1e-14);
    for (const Eigen::VectorXd& p : on_facet) ASSERT_LE(hit.dist2, (p - x).squaredNorm() + 1e-13) << x.transpose();
  }
}

std::vector<Kind> kinds() {
  std::vector<Kind> out;
  for (ElementType type : {ElementType::Line, ElementType::Triangle, ElementType::Quadrilateral})
    for (int order = 1; order <= 4; ++order) out.push_back({type, order});
  return out;
}

INSTANTIATE_TEST_SUITE_P(AllFacets, PolynomialFacetKinds, testing::ValuesIn(kinds()), name);

}  // namespace
}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#include "meshmorph/fem/quadrature.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/fem/reference_element.h"

namespace meshmorph {
namespace {

double factorial(int n) { return n <= 1 ? 1.0 : n * factorial(n - 1); }

// Exact ∫ ξ^a η^b ζ^c over the reference element (unit simplex or [−1, 1]^d).
double exact_monomial(ElementType t, int a, int b, int c) {
  switch (t) {
    case ElementType::Line: return a % 2 ? 0.0 : 2.0 / (a + 1);
    case ElementType::Triangle: return factorial(a) * factorial(b) / factorial(a + b + 2);
    case ElementType::Tetrahedron: return factorial(a) * factorial(b) * factorial(c) / factorial(a + b + c + 3);
    case ElementType::Quadrilateral: return exact_monomial(ElementType::Line, a, 0, 0) * exact_monomial(ElementType::Line, b, 0, 0);
    case ElementType::Hexahedron:
      return exact_monomial(ElementType::Line, a, 0, 0) * exact_monomial(ElementType::Line, b, 0, 0) *
             exact_monomial(ElementType::Line, c, 0, 0);
    default: return 1.0;
  }
}

// The rule's sum of ξ^a η^b ζ^c (the powers beyond its dimension ignored).
double integrate_monomial(const QuadratureRule& rule, int a, int b, int c) {
  const auto dim = rule.points.rows();
  double sum = 0;
  for (int q = 0; q < rule.n_points(); ++q) {
    double v = std::pow(rule.points(0, q), a);
    if (dim > 1) v *= std::pow(rule.points(1, q), b);
    if (dim > 2) v *= std::pow(rule.points(2, q), c);
    sum += rule.weights(q) * v;
  }
  return sum;
}

TEST(QuadratureRule, ExactForEveryMonomialUpToItsDegree) {
  for (auto t : {ElementType::Line, ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron,
                 ElementType::Hexahedron}) {
    const int dim = topological_dim(t);
    for (int degree = 0; degree <= 12; ++degree) {
      const auto& rule = quadrature_rule(t, degree);
      for (int a = 0; a <= degree; ++a)
        for (int b = 0; b <= (dim > 1 ? degree : 0); ++b)
          for (int c = 0; c <= (dim > 2 ? degree : 0); ++c) {
            if (is_simplex(t) && a + b + c > degree) continue;
            EXPECT_NEAR(integrate_monomial(rule, a, b, c), exact_monomial(t, a, b, c), 1e-13)
                << name_of(t) << " degree " << degree << " monomial " << a << "," << b << "," << c;
          }
    }
  }
}

// Prism: the triangle's monomials times ζ^c on [−1, 1], exact for total degree ≤ degree in
// (ξ, η) and degree ≤ degree in ζ. Pyramid: ∫ ξ^a η^b ζ^c over the base [−1, 1]² shrinking to
// the apex, = ∫₀¹ (1 − ζ)^(a+b+2) ζ^c dζ · ∫u^a ∫v^b, exact for a + b + c ≤ degree.
TEST(QuadratureRule, PrismAndPyramidRulesAreExact) {
  for (int degree = 0; degree <= 8; ++degree) {
    const auto& prism = quadrature_rule(ElementType::Prism, degree);
    const auto& pyramid = quadrature_rule(ElementType::Pyramid, degree);
    EXPECT_TRUE((prism.weights.array() > 0).all() && (pyramid.weights.array() > 0).all());
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; c <= degree; ++c) {
          const double tri = exact_monomial(ElementType::Triangle, a, b, 0), line = exact_monomial(ElementType::Line, c, 0, 0);
          EXPECT_NEAR(integrate_monomial(prism, a, b, c), tri * line, 1e-13) << degree << ": " << a << b << c;
          if (a + b + c > degree) continue;
          const double beta = factorial(a + b + 2) * factorial(c) / factorial(a + b + c + 3);
          const double pyr = exact_monomial(ElementType::Line, a, 0, 0) * exact_monomial(ElementType::Line, b, 0, 0) * beta;
          EXPECT_NEAR(integrate_monomial(pyramid, a, b, c), pyr, 1e-13) << degree << ": " << a << b << c;
        }
  }
  EXPECT_NEAR(quadrature_rule(ElementType::Prism, 3).weights.sum(), 1.0, 1e-14);
  EXPECT_NEAR(quadrature_rule(ElementType::Pyramid, 3).weights.sum(), 4.0 / 3.0, 1e-14);
}

// The Lobatto prism rule (the collapsed triangle's Gauss–Lobatto(–Jacobi) product times
// Gauss–Lobatto in ζ): exact as the Gauss one, positive weights, the six corners among its points.
TEST(QuadratureRule, LobattoPrismRuleIsExactAndHoldsTheCorners) {
  for (int degree = 0; degree <= 10; ++degree) {
    const auto& prism = quadrature_rule(ElementType::Prism, degree, QuadratureFamily::Lobatto);
    EXPECT_TRUE((prism.weights.array() > 0).all()) << degree;
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; c <= degree; ++c) {
          const double tri = exact_monomial(ElementType::Triangle, a, b, 0), line = exact_monomial(ElementType::Line, c, 0, 0);
          EXPECT_NEAR(integrate_monomial(prism, a, b, c), tri * line, 1e-13) << degree << ": " << a << b << c;
        }
    const Eigen::MatrixXd& corners = reference_element(ElementType::Prism, 1).nodes;
    for (int i = 0; i < 6; ++i) {
      bool found = false;
      for (int p = 0; p < prism.n_points(); ++p) found = found || (prism.points.col(p) - corners.col(i)).norm() < 1e-15;
      EXPECT_TRUE(found) << degree << ": corner " << i;
    }
  }
}

// The prism rules of degree 9 (2p + 1 for quartic prisms; cubic ones take 7, above) and 10,
// exact as above.
TEST(QuadratureRule, PrismRulesAreExactToTheDegreesOfOrdersThreeAndFour) {
  for (const int degree : {9, 10}) {
    const auto& prism = quadrature_rule(ElementType::Prism, degree);
    EXPECT_TRUE((prism.weights.array() > 0).all());
    for (int a = 0; a <= degree; ++a)
      for (int b = 0; a + b <= degree; ++b)
        for (int c = 0; c <= degree; ++c) {
          const double tri = exact_monomial(ElementType::Triangle, a, b, 0), line = exact_monomial(ElementType::Line, c, 0, 0);
          EXPECT_NEAR(integrate_monomial(prism, a, b, c), tri * line, 1e-13) << degree << ": " << a << b << c;
        }
  }
}

// Gauss–Lobatto products: exact to their degree in each variable, the corners of the cell
// among the points, positive weights, and simplices unchanged.
TEST(QuadratureRule, LobattoProductsAreExactAndHoldTheCorners) {
  for (auto t : {ElementType::Line, ElementType::Quadrilateral, ElementType::Hexahedron}) {
    const int dim = topological_dim(t);
    for (int degree = 0; degree <= 11; ++degree) {
      const auto& rule = quadrature_rule(t, degree, QuadratureFamily::Lobatto);
      const int m = std::max(2, (degree + 4) / 2);
      EXPECT_EQ(rule.n_points(), static_cast<int>(std::pow(m, dim)));
      EXPECT_GT(rule.weights.minCoeff(), 0.0);
      EXPECT_GT((rule.points.cwiseAbs().colwise().minCoeff().array() == 1.0).count(), 0);  // a corner
      for (int a = 0; a <= degree; ++a)
        for (int b = 0; b <= (dim > 1 ? degree : 0); ++b)
          for (int c = 0; c <= (dim > 2 ? degree : 0); ++c) {
            EXPECT_NEAR(integrate_monomial(rule, a, b, c), exact_monomial(t, a, b, c), 1e-13) << name_of(t) << " degree " << degree;
          }
    }
  }
  EXPECT_EQ(&quadrature_rule(ElementType::Tetrahedron, 4, QuadratureFamily::Lobatto), &quadrature_rule(ElementType::Tetrahedron, 4));
}

TEST(QuadratureRule, PointsInsideAndWeightsPositive) {
  for (auto t : {ElementType::Triangle, ElementType::Tetrahedron, ElementType::Quadrilateral, ElementType::Hexahedron})
    for (int degree = 1; degree <= 10; ++degree) {
      const auto& rule = quadrature_rule(t, degree);
      EXPECT_GT(rule.weights.minCoeff(), 0.0);
      if (is_simplex(t)) {
        EXPECT_GT(rule.points.minCoeff(), 0.0);
        EXPECT_LT(rule.points.colwise().sum().maxCoeff(), 1.0);
      } else {
        EXPECT_LT(rule.points.cwiseAbs().maxCoeff(), 1.0);
      }
    }
}

// The tabulated simplex rules are fully symmetric: permuting the barycentric coordinates of
// the points maps the rule onto itself, weights included. They also use fewer points than
// the conical product of the same degree ((degree/2 + 1)^d).
TEST(QuadratureRule, SimplexRulesAreSymmetricAndSmall) {
  for (auto t : {ElementType::Triangle, ElementType::Tetrahedron}) {
    const int dim = topological_dim(t);
    for (int degree = 2; degree <= 8; ++degree) {
      const auto& rule = quadrature_rule(t, degree);
      const int conical = static_cast<int>(std::pow(degree / 2 + 1, dim));
      if (degree >= 4) {
        EXPECT_LT(rule.n_points(), conical) << name_of(t) << " degree " << degree;
      }
      std::vector<int> perm(static_cast<std::size_t>(dim + 1));
      for (int i = 0; i <= dim; ++i) perm[static_cast<std::size_t>(i)] = i;
      do {
        for (int q = 0; q < rule.n_points(); ++q) {
          Eigen::VectorXd bary(dim + 1);
          bary << 1 - rule.points.col(q).sum(), rule.points.col(q);
          Eigen::VectorXd image(dim);
          for (int k = 0; k < dim; ++k) image(k) = bary(perm[static_cast<std::size_t>(k + 1)]);
          bool found = false;
          for (int r = 0; r < rule.n_points() && !found; ++r)
            found = (rule.points.col(r) - image).norm() < 1e-12 && std::abs(rule.weights(r) - rule.weights(q)) < 1e-14;
          EXPECT_TRUE(found) << name_of(t) << " degree " << degree << " point " << q;
        }
      } while (std::next_permutation(perm.begin(), perm.end()));
    }
  }
}

TEST(QuadratureRule, LinearSimplexRuleIsTheCentroid) {
  const auto& rule = quadrature_rule(ElementType::Tetrahedron, 1);
  ASSERT_EQ(rule.n_points(), 1);
  EXPECT_NEAR((rule.points.col(0) - Eigen::Vector3d::Constant(0.25)).norm(), 0.0, 1e-15);
  EXPECT_NEAR(rule.weights(0), 1.0 / 6.0, 1e-15);
}

}  // namespace
}  // namespace meshmorph

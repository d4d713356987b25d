// SPDX-License-Identifier: MIT
// facet_surface: closest points on the bottom facets of a structured mesh, flat (exact
// answers) and bent into the paraboloid (parabola in 2D) z = c|x|², which P2 and P3 facets
// reproduce exactly, so the discrete surface is smooth there and σ is a signed distance
// whose derivatives differences can check.
#include "meshmorph/geometry/facet_surface.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <random>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "geometry/level_set_fixtures.h"
#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"

namespace meshmorph {
namespace {

constexpr double bend = 0.4;  // c of z = c|x|²: radius of curvature ≥ 1.25, far beyond the test points' 0.05

struct Case {
  ElementType type;
  int order;
};

std::string name(const testing::TestParamInfo<Case>& i) {
  return std::string(name_of(i.param.type)) + "_p" + std::to_string(i.param.order);
}

// The structured mesh, bent (or not), and its "bottom" facets (last coordinate 0 before bending).
struct Bottom {
  Mesh mesh;
  Topology topology;
  std::vector<std::int32_t> facets;
};

Bottom bottom(const Case& c, bool bent) {
  Bottom b{structured_mesh(c.type, c.order, 3), {}, {}};
  const int d = b.mesh.dim;
  b.topology = build_topology(b.mesh);
  for (std::int32_t f : b.topology.boundary_facets) {
    const CellFacet cf = b.topology.facets[static_cast<std::size_t>(f)][0];
    const auto [blk, cell] = b.topology.locate(cf.cell);
    bool on = true;
    for (std::int32_t n : facet_nodes(b.mesh.cells[blk], cell, cf.local)) on = on && std::abs(b.mesh.x(d - 1, n)) < 1e-12;
    if (on) b.facets.push_back(f);
  }
  if (bent)
    for (Eigen::Index i = 0; i < b.mesh.x.cols(); ++i) b.mesh.x(d - 1, i) += bend * b.mesh.x.col(i).head(d - 1).squaredNorm();
  return b;
}

// Random points 0.05–0.15 above and below the bottom (bent or not), their foot in
// [0.2, 0.8]^(d−1), away from the rim.
std::vector<Eigen::VectorXd> points(int d, bool bent, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.2, 0.8), h(0.05, 0.15);
  std::vector<Eigen::VectorXd> out;
  for (int i = 0; i < 12; ++i) {
    Eigen::VectorXd x(d);
    for (int k = 0; k + 1 < d; ++k) x[k] = u(rng);
    x[d - 1] = (bent ? bend * x.head(d - 1).squaredNorm() : 0.0) + (i % 2 ? 1.0 : -1.0) * h(rng);
    out.push_back(x);
  }
  return out;
}

class FacetSurfaceFlat : public testing::TestWithParam<Case> {};

// A piece of a plane: the foot is the orthogonal projection to rounding, σ = −z (the outward
// normal of the bottom is −e_z), and a point of the surface is its own foot.
TEST_P(FacetSurfaceFlat, ClosestPointIsTheProjection) {
  const Bottom b = bottom(GetParam(), false);
  const int d = b.mesh.dim;
  const LevelSetFunction sigma = facet_surface(b.mesh, b.topology, b.facets);
  for (const Eigen::VectorXd& x : points(d, false, 3)) {
    Eigen::VectorXd p = x;
    p[d - 1] = 0.0;
    test::expect_closest_point(sigma, x, p, 1e-14);
    EXPECT_NEAR(sigma.value(x), -x[d - 1], 1e-14);
    EXPECT_LE((sigma.gradient(x) + Eigen::VectorXd::Unit(d, d - 1)).norm(), 1e-13);
    EXPECT_LE((sigma.hessian(x)).norm(), 1e-12);
    EXPECT_LE((*sigma.closest_point(p) - p).norm(), 1e-14);
  }
  // Beyond the rim x = 1 (off the patch): the foot is on the rim, σ the tangent-plane continuation.
  Eigen::VectorXd x = Eigen::VectorXd::Constant(d, 0.5);
  x[0] = 1.2;
  x[d - 1] = 0.1;
  Eigen::VectorXd p = x;
  p[0] = 1.0;
  p[d - 1] = 0.0;
  test::expect_closest_point(sigma, x, p, 1e-14);
  EXPECT_NEAR(sigma.value(x), -0.1, 1e-14);
}

INSTANTIATE_TEST_SUITE_P(AllFacets, FacetSurfaceFlat,
                         testing::Values(Case{ElementType::Triangle, 1}, Case{ElementType::Triangle, 3},
                                         Case{ElementType::Quadrilateral, 2}, Case{ElementType::Tetrahedron, 1},
                                         Case{ElementType::Tetrahedron, 2}, Case{ElementType::Tetrahedron, 3},
                                         Case{ElementType::Hexahedron, 1}, Case{ElementType::Hexahedron, 2},
                                         Case{ElementType::Hexahedron, 3}),
                         name);

class FacetSurfaceCurved : public testing::TestWithParam<Case> {};

// The distance from x to the nearest column of S. A plain loop: it runs ~10⁷ times per test,
// and Eigen's expressions are slow unoptimized (the sanitizer build).
double nearest(const Eigen::MatrixXd& S, const Eigen::VectorXd& x) {
  const double* y = x.data();
  const double* s = S.data();
  double best = std::numeric_limits<double>::infinity();
  for (Eigen::Index c = 0; c < S.cols(); ++c, s += S.rows()) {
    double r2 = 0.0;
    for (Eigen::Index k = 0; k < S.rows(); ++k) r2 += (s[k] - y[k]) * (s[k] - y[k]);
    best = std::min(best, r2);
  }
  return std::sqrt(best);
}

// The foot against the nearest of a 400-per-direction sampling of every facet: never
// farther (up to rounding), and closer by at most the sampling's error (spacing² · curvature).
TEST_P(FacetSurfaceCurved, ClosestPointMatchesAFineSampling) {
  const Bottom b = bottom(GetParam(), true);
  const int d = b.mesh.dim;
  const LevelSetFunction sigma = facet_surface(b.mesh, b.topology, b.facets);
  // The basis at the lattice once per facet type (one matrix), each facet's samples X times it.
  const int k = d == 2 ? 4000 : 400;
  std::map<ElementType, Eigen::MatrixXd> lattice_values;
  std::vector<Eigen::MatrixXd> samples;  // d × lattice size, per facet
  for (std::int32_t f : b.facets) {
    const CellFacet cf = b.topology.facets[static_cast<std::size_t>(f)][0];
    const auto [blk, cell] = b.topology.locate(cf.cell);
    const CellBlock& block = b.mesh.cells[blk];
    const ElementType ft = facet_type(block.type, cf.local);
    const LagrangeBasis& basis = lagrange_basis(ft, block.order);
    const auto [values, added] = lattice_values.try_emplace(ft);
    if (added) {
      std::vector<Eigen::VectorXd> columns;
      for (int j = 0; j <= (d == 2 ? 0 : k); ++j)
        for (int i = 0; i <= k; ++i) {
          Eigen::VectorXd u(d - 1);
          if (d == 2) u << -1.0 + 2.0 * i / k;
          else if (ft == ElementType::Triangle) {
            if (i + j > k) continue;
            u << double(i) / k, double(j) / k;
          } else {
            u << -1.0 + 2.0 * i / k, -1.0 + 2.0 * j / k;
          }
          columns.push_back(basis.values(u));
        }
      values->second.resize(basis.n(), static_cast<Eigen::Index>(columns.size()));
      for (std::size_t c = 0; c < columns.size(); ++c) values->second.col(static_cast<Eigen::Index>(c)) = columns[c];
    }
    samples.push_back(b.mesh.x(Eigen::all, facet_nodes(block, cell, cf.local)) * values->second);
  }
  for (const Eigen::VectorXd& x : points(d, true, 4)) {
    const Eigen::VectorXd p = *sigma.closest_point(x);
    double sampled = std::numeric_limits<double>::infinity();
    for (const Eigen::MatrixXd& S : samples) sampled = std::min(sampled, nearest(S, x));
    const double found = (p - x).norm();
    EXPECT_LE(found, sampled + 1e-14) << x.transpose();
    EXPECT_GE(found, sampled - 1e-5) << x.transpose();
    EXPECT_NEAR(std::abs(sigma.value(x)), found, 1e-15);
    // On the paraboloid, and x − p along its normal there (the first-order condition).
    EXPECT_NEAR(p[d - 1], bend * p.head(d - 1).squaredNorm(), 1e-14);
    EXPECT_LE(test::tangential_residual(sigma, x, p), 1e-13);
    EXPECT_LE(std::abs(sigma.value(p)), 1e-14);
  }
}

// ∇σ and ∇²σ against differences (level_set_fixtures.h: five points, step 1e-4); the points
// lie 0.05–0.15 from the surface, far from its medial axis (curvature radius ≥ 1.25).
TEST_P(FacetSurfaceCurved, DerivativesMatchDifferences) {
  const Bottom b = bottom(GetParam(), true);
  const LevelSetFunction sigma = facet_surface(b.mesh, b.topology, b.facets);
  for (const Eigen::VectorXd& x : points(b.mesh.dim, true, 5)) {
    test::expect_gradient_matches_fd(sigma, x, 1e-9);
    const Eigen::MatrixXd H = sigma.hessian(x);
    EXPECT_LE((H - H.transpose()).norm(), 1e-14);
    test::expect_hessian_matches_fd([&](const Eigen::VectorXd& y) { return sigma.gradient(y); }, x, H, 1e-4, 1e-8);
  }
}

INSTANTIATE_TEST_SUITE_P(CurvedFacets, FacetSurfaceCurved,
                         testing::Values(Case{ElementType::Triangle, 2}, Case{ElementType::Quadrilateral, 3},
                                         Case{ElementType::Tetrahedron, 2}, Case{ElementType::Tetrahedron, 3},
                                         Case{ElementType::Hexahedron, 2}, Case{ElementType::Hexahedron, 3}),
                         name);

// σ, ∇σ, ∇²σ and the closest point at one point.
struct Answer {
  double value;
  Eigen::VectorXd gradient, closest;
  Eigen::MatrixXd hessian;
};

Answer answer(const LevelSetFunction& sigma, const Eigen::VectorXd& x) {
  return {sigma.value(x), sigma.gradient(x), *sigma.closest_point(x), sigma.hessian(x)};
}

void expect_same(const Answer& a, const Answer& b) {
  EXPECT_EQ(a.value, b.value);
  EXPECT_EQ(a.gradient, b.gradient);
  EXPECT_EQ(a.closest, b.closest);
  EXPECT_EQ(a.hessian, b.hessian);
}

// Answers do not depend on the order of the queries, nor on the surface that lived at the
// same address before (a flat and a bent bottom differ at every point).
TEST(FacetSurface, AnswersDoNotDependOnTheQueriesBefore) {
  const Case c{ElementType::Tetrahedron, 2};
  const Bottom flat = bottom(c, false), bent = bottom(c, true);
  const std::vector<Eigen::VectorXd> xs = points(3, true, 6);
  std::vector<Answer> first;
  {
    const LevelSetFunction sigma = facet_surface(bent.mesh, bent.topology, bent.facets);
    for (const Eigen::VectorXd& x : xs) first.push_back(answer(sigma, x));
  }
  std::optional<LevelSetFunction> sigma;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    SCOPED_TRACE(testing::Message() << "x = " << xs[i].transpose());
    sigma.emplace(facet_surface(flat.mesh, flat.topology, flat.facets));
    EXPECT_NEAR(sigma->value(xs[i]), -xs[i][2], 1e-14);
    sigma.reset();
    sigma.emplace(facet_surface(bent.mesh, bent.topology, bent.facets));  // often where the flat one was
    expect_same(answer(*sigma, xs[i]), first[i]);
    const std::size_t j = xs.size() - 1 - i;  // the other end of the list, then back
    expect_same(answer(*sigma, xs[j]), first[j]);
    expect_same(answer(*sigma, xs[i]), first[i]);
  }
}

TEST(FacetSurface, ConcurrentCallsGiveTheSerialResults) {
  const Bottom b = bottom(Case{ElementType::Hexahedron, 3}, true);
  const LevelSetFunction sigma = facet_surface(b.mesh, b.topology, b.facets);
  const std::vector<Eigen::VectorXd> xs = points(3, true, 7);
  std::vector<Answer> serial;
  for (const Eigen::VectorXd& x : xs) serial.push_back(answer(sigma, x));
  std::vector<std::vector<Answer>> parallel(4);
  std::vector<std::thread> threads;
  for (std::vector<Answer>& out : parallel)
    threads.emplace_back([&sigma, &xs, &out] {
      for (const Eigen::VectorXd& x : xs) out.push_back(answer(sigma, x));
    });
  for (std::thread& t : threads) t.join();
  for (const std::vector<Answer>& out : parallel)
    for (std::size_t i = 0; i < xs.size(); ++i) expect_same(out[i], serial[i]);
}

// at(x) answers from one search what the separate calls answer from one each, bit for bit:
// off the surface, on it inside a facet, and at facet edges and corners (creases of a bent
// P1 bottom, where stationarity and step normals take the facets' cones).
TEST(FacetSurface, AnswersAtAPointEqualTheSeparateCalls) {
  for (const Case c : {Case{ElementType::Hexahedron, 2}, Case{ElementType::Tetrahedron, 1}, Case{ElementType::Triangle, 1}}) {
    const Bottom b = bottom(c, true);
    const int d = b.mesh.dim;
    const LevelSetFunction sigma = facet_surface(b.mesh, b.topology, b.facets);
    std::vector<Eigen::VectorXd> xs = points(d, true, 8);
    for (std::size_t i = 0, n = xs.size(); i < n; ++i) xs.push_back(*sigma.closest_point(xs[i]));
    for (std::int32_t f : b.facets) {
      const CellFacet cf = b.topology.facets[static_cast<std::size_t>(f)][0];
      const auto [blk, cell] = b.topology.locate(cf.cell);
      for (std::int32_t node : facet_nodes(b.mesh.cells[blk], cell, cf.local)) xs.push_back(b.mesh.x.col(node));
    }
    std::mt19937 rng(4);
    std::normal_distribution<double> normal;
    for (const Eigen::VectorXd& x : xs) {
      SCOPED_TRACE(testing::Message() << name_of(c.type) << " p" << c.order << ", x = " << x.transpose());
      Eigen::VectorXd g(d);
      for (int k = 0; k < d; ++k) g[k] = normal(rng);
      const LevelSetPoint at = sigma.at(x);
      EXPECT_EQ(at.value(), sigma.value(x));
      EXPECT_EQ(at.gradient(), sigma.gradient(x));
      EXPECT_EQ(at.hessian(), sigma.hessian(x));
      EXPECT_EQ(at.stationarity(g), sigma.stationarity(x, g));
      EXPECT_EQ(at.step_normals(g), sigma.step_normals(x, g));
    }
  }
}

}  // namespace
}  // namespace meshmorph

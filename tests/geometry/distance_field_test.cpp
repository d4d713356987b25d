// SPDX-License-Identifier: MIT
#include "meshmorph/geometry/distance_field.h"

#include <cmath>
#include <stdexcept>

#include <gtest/gtest.h>

#include "meshmorph/fem/validity.h"
#include "meshmorph/geometry/level_set_function.h"

namespace meshmorph {
namespace {

using Vec = Eigen::VectorXd;

DistanceFieldOptions unit_box(int dim, int cells, int levels, int order) {
  DistanceFieldOptions o;
  o.lower = Vec::Zero(dim);
  o.upper = Vec::Ones(dim);
  o.cells = cells;
  o.levels = levels;
  o.order = order;
  return o;
}

// Over the nodes for which `counts` holds (all by default).
double max_error(const DistanceField& f, const std::function<double(const Vec&)>& exact,
                 const std::function<bool(const Vec&)>& counts = [](const Vec&) { return true; }) {
  double e = 0;
  for (Eigen::Index n = 0; n < f.values.size(); ++n)
    if (counts(f.background.x.col(n))) e = std::max(e, std::abs(f.values[n] - exact(f.background.x.col(n))));
  return e;
}

// A plane is reconstructed exactly by marching simplices, so the field is its signed
// distance to rounding at every node whose foot on the plane lies in the box (the surface
// ends at the box), however coarse the cells far from it.
TEST(DistanceField, IsExactForAPlane) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(dim);
    Vec n = Vec::LinSpaced(dim, 0.3, 1.0).normalized();
    const Vec p = Vec::Constant(dim, 0.43);
    const auto exact = [&](const Vec& x) { return (x - p).dot(n); };
    const DistanceField f = distance_field([&](const Vec& x) { return exact(x) < 0; }, dim, unit_box(dim, 4, 3, 2));
    EXPECT_GT(f.surface_facets, 0u);
    const auto foot_in_box = [&](const Vec& x) {
      const Vec foot = x - exact(x) * n;
      return foot.minCoeff() >= 0 && foot.maxCoeff() <= 1;
    };
    EXPECT_LT(max_error(f, exact, foot_in_box), 1e-12);
  }
}

// A circle / sphere: the reconstructed surface is a polygon / polyhedron with chords of the
// finest size h, so the distance error is O(h²): below h²/r on every level, and falling
// (about 4x per level once the chords are regular).
TEST(DistanceField, ConvergesQuadraticallyForACircleAndASphere) {
  for (int dim : {2, 3}) {
    SCOPED_TRACE(dim);
    const Vec c = Vec::Constant(dim, 0.5);
    const double r = 0.3;
    const auto exact = [&](const Vec& x) { return (x - c).norm() - r; };
    double previous = 0;
    for (int levels = 2; levels <= (dim == 2 ? 5 : 4); ++levels) {
      const DistanceField f =
          distance_field([&](const Vec& x) { return exact(x) < 0; }, dim, unit_box(dim, 8, levels, 1));
      const double e = max_error(f, exact), h = f.finest_size;
      EXPECT_LT(e, h * h / r) << "levels " << levels;
      if (previous > 0) {
        EXPECT_LT(e, previous / 1.5) << "levels " << levels;
      }
      previous = e;
    }
  }
}

// The background cells are refined only near the zero set: a band of finest cells there,
// root-size cells far away; every cell is a valid hexahedron of the requested order, and
// the field interpolated on them (a `mesh` level set) vanishes on the circle to O(h²).
TEST(DistanceField, RefinesOnlyNearTheZeroSetAndInterpolates) {
  const Vec c = Vec::Constant(3, 0.5);
  const double r = 0.3;
  const DistanceField f =
      distance_field([&](const Vec& x) { return (x - c).norm() < r; }, 3, unit_box(3, 8, 3, 2));
  const Mesh& m = f.background;
  ASSERT_EQ(m.cells.size(), 1u);
  EXPECT_EQ(m.cells[0].type, ElementType::Hexahedron);
  EXPECT_EQ(m.cells[0].order, 2);
  const std::size_t uniform = 64 * 64 * 64;
  EXPECT_LT(m.n_cells(), uniform / 8);
  EXPECT_EQ(count_invalid_cells(m), 0u);
  double coarse = 0, fine = 1;
  for (std::size_t e = 0; e < m.cells[0].n_cells(); ++e) {
    const std::int32_t* nodes = m.cells[0].cell(e);
    const double size = (m.x.col(nodes[6]) - m.x.col(nodes[0])).cwiseAbs().maxCoeff();
    coarse = std::max(coarse, size);
    fine = std::min(fine, size);
  }
  EXPECT_DOUBLE_EQ(coarse, 1.0 / 8);
  EXPECT_DOUBLE_EQ(fine, f.finest_size);
  EXPECT_DOUBLE_EQ(fine, 1.0 / 64);
  const LevelSetFunction sigma(f.background, f.values);
  for (int i = 0; i < 50; ++i) {
    const Vec d = Vec::Random(3).normalized();
    const Vec on = c + r * d;
    EXPECT_LT(std::abs(sigma.value(on)), f.finest_size * f.finest_size / r);
    EXPECT_NEAR(sigma.gradient(on).dot(d), 1.0, 0.05);
    EXPECT_NEAR(sigma.value(c + (r + 0.1) * d), 0.1, 0.01);
  }
}

TEST(DistanceField, RejectsBadOptionsAndAnIndicatorWithoutSignChange) {
  const auto everywhere = [](const Vec&) { return true; };
  const auto half = [](const Vec& x) { return x[0] < 0.5; };
  EXPECT_THROW(distance_field(everywhere, 2, unit_box(2, 4, 2, 1)), std::invalid_argument);
  EXPECT_THROW(distance_field(half, 4, unit_box(2, 4, 2, 1)), std::invalid_argument);
  EXPECT_THROW(distance_field(half, 2, unit_box(2, 0, 2, 1)), std::invalid_argument);
  EXPECT_THROW(distance_field(half, 2, unit_box(2, 4, 13, 1)), std::invalid_argument);
  EXPECT_THROW(distance_field(half, 2, unit_box(2, 4, 2, 4)), std::invalid_argument);
  DistanceFieldOptions flat = unit_box(2, 4, 2, 1);
  flat.upper[1] = 0;
  EXPECT_THROW(distance_field(half, 2, flat), std::invalid_argument);
  EXPECT_THROW(distance_field(half, 3, unit_box(2, 4, 2, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
// closest_on_segment and closest_on_triangle: exact answers in each region of a segment and
// of a triangle (its vertices, edges and face) on dyadic coordinates, where every operation is
// exact, and no sample of a random triangle closer than the answer.
#include "meshmorph/geometry/closest_on_simplex.h"

#include <random>

#include <gtest/gtest.h>

namespace meshmorph {
namespace {

using V = Eigen::Vector3d;

TEST(ClosestOnSegment, EndsAndInterior) {
  const V a(1, 0, 0), b(3, 2, 0);
  EXPECT_EQ(closest_on_segment(V(0, -1, 4), a, b), a);
  EXPECT_EQ(closest_on_segment(V(5, 2, -1), a, b), b);
  EXPECT_EQ(closest_on_segment(V(1, 2, 3), a, b), V(2, 1, 0));  // (p − a)·(b − a) = 4 of 8
  EXPECT_EQ(closest_on_segment(V(2, 1, 0), a, b), V(2, 1, 0));  // a point of the segment
  EXPECT_EQ(closest_on_segment(V(7, 7, 7), a, a), a);           // zero length
}

TEST(ClosestOnSegment, TwoDimensionalPointsPadded) {
  const Eigen::Vector2d a(0, 0), b(4, 0), p(1, 3);
  EXPECT_EQ(padded_3d(p), V(1, 3, 0));
  EXPECT_EQ(closest_on_segment(padded_3d(p), padded_3d(a), padded_3d(b)), V(1, 0, 0));
}

// The triangle (0,0,0), (2,0,0), (0,2,0): each Voronoi region of a point above or below it.
TEST(ClosestOnTriangle, VertexEdgeAndFaceRegions) {
  const V a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_EQ(closest_on_triangle(V(-1, -1, 3), a, b, c), a);
  EXPECT_EQ(closest_on_triangle(V(3, -1, 1), a, b, c), b);
  EXPECT_EQ(closest_on_triangle(V(-1, 3, -2), a, b, c), c);
  EXPECT_EQ(closest_on_triangle(V(1, -1, 5), a, b, c), V(1, 0, 0));    // edge ab
  EXPECT_EQ(closest_on_triangle(V(-1, 1.5, 2), a, b, c), V(0, 1.5, 0));  // edge ca
  EXPECT_EQ(closest_on_triangle(V(2, 1, -1), a, b, c), V(1.5, 0.5, 0));  // edge bc
  EXPECT_EQ(closest_on_triangle(V(0.5, 0.25, 7), a, b, c), V(0.5, 0.25, 0));  // face
  EXPECT_EQ(closest_on_triangle(V(0.5, 0.25, 0), a, b, c), V(0.5, 0.25, 0));  // a point of the face
  // The order of the corners does not matter.
  EXPECT_EQ(closest_on_triangle(V(2, 1, -1), c, a, b), V(1.5, 0.5, 0));
  EXPECT_EQ(closest_on_triangle(V(-1, -1, 3), b, c, a), a);
}

// Collinear corners: the closest point of the edges.
TEST(ClosestOnTriangle, DegenerateTriangleIsItsEdges) {
  const V a(0, 0, 0), b(1, 1, 0), c(4, 4, 0);
  EXPECT_EQ(closest_on_triangle(V(2, 4, 1), a, b, c), V(3, 3, 0));
  EXPECT_EQ(closest_on_triangle(V(-2, -1, 0), a, b, c), a);
  EXPECT_EQ(closest_on_triangle(V(5, 5, 5), a, a, a), a);
}

// Random triangles and points: the answer lies on the triangle (its barycentric coordinates
// are ≥ 0 to rounding) and no point of a fine sampling of the triangle is closer.
TEST(ClosestOnTriangle, NoSampleIsCloser) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto random = [&] { return V(u(rng), u(rng), u(rng)); };
  for (int t = 0; t < 50; ++t) {
    const V a = random(), b = random(), c = random(), p = 2.0 * random();
    const V q = closest_on_triangle(p, a, b, c);
    const V n = (b - a).cross(c - a);
    const double area2 = n.squaredNorm();
    const double la = n.dot((b - q).cross(c - q)) / area2, lb = n.dot((c - q).cross(a - q)) / area2;
    EXPECT_NEAR(n.dot(q - a) / n.norm(), 0.0, 1e-12);
    EXPECT_GE(la, -1e-12);
    EXPECT_GE(lb, -1e-12);
    EXPECT_GE(1.0 - la - lb, -1e-12);
    const double d2 = (q - p).squaredNorm();
    constexpr int n_samples = 40;
    for (int i = 0; i <= n_samples; ++i)
      for (int j = 0; i + j <= n_samples; ++j) {
        const V y = a + (b - a) * i / n_samples + (c - a) * j / n_samples;
        EXPECT_LE(d2, (y - p).squaredNorm() * (1 + 1e-12));
      }
  }
}

}  // namespace
}  // namespace meshmorph

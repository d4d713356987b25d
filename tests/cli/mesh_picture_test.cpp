// SPDX-License-Identifier: MIT
#include "cli/detail/mesh_picture.h"

#include <cmath>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"

namespace meshmorph::detail {
namespace {

// The screen position of a point seen from mesh_faces's view (elevation 20°, azimuth 60°).
Eigen::Vector2d seen(const Eigen::Vector3d& p) {
  const double el = 20.0 * M_PI / 180.0, az = 60.0 * M_PI / 180.0;
  const Eigen::Vector3d eye(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
  const Eigen::Vector3d right(-std::sin(az), std::cos(az), 0.0);
  return {p.dot(right), p.dot(eye.cross(right))};
}

Eigen::Vector2d centroid(const Face& f) {
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : f.outline) c += p;
  return c / static_cast<double>(f.outline.size());
}

TEST(WorstCells, NumpyLinearQuantileOfTheFiniteValues) {
  // 21 values 0.1, ..., 0.3 (shuffled) and a NaN: the 5 % quantile is at 0.05 · 20 = 1,
  // exactly the second smallest, 0.11; the NaN is outlined, the rest not.
  std::vector<double> v;
  for (int k = 20; k >= 0; --k) v.push_back(0.1 + 0.01 * k);
  v.push_back(NAN);
  const std::vector<bool> w = worst_cells(v, 0.05);
  for (std::size_t i = 0; i < 21; ++i) EXPECT_EQ(w[i], v[i] <= 0.11 + 1e-12) << i;
  EXPECT_TRUE(w[21]);
  // Between two values: 11 values 1..11, the quantile at 0.05 · 10 = 0.5 is 1.5.
  std::vector<double> u;
  for (int k = 1; k <= 11; ++k) u.push_back(k);
  const std::vector<bool> wu = worst_cells(u, 0.05);
  EXPECT_TRUE(wu[0]);
  EXPECT_FALSE(wu[1]);
}

TEST(WorstCells, NegativeCellsAlwaysOneValueNever) {
  const std::vector<bool> w = worst_cells({-0.5, 0.0, 0.9, 0.9, 0.9}, 0.0);
  EXPECT_EQ(w, (std::vector<bool>{true, true, false, false, false}));
  EXPECT_EQ(worst_cells({0.7, 0.7, 0.7 * (1 - 1e-15)}, 0.05), (std::vector<bool>{false, false, false}));
}

TEST(MeshFaces, CurvedTriangleThroughItsEdgeNodes) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 2, 1);
  const std::vector<Face> faces = mesh_faces(mesh);
  ASSERT_EQ(faces.size(), 2u);
  const CellBlock& b = mesh.cells[0];
  for (std::size_t c = 0; c < 2; ++c) {
    EXPECT_EQ(faces[c].cell, static_cast<std::int32_t>(c));
    // Gmsh's P2 triangle: corners 0 1 2, then the nodes of edges 01, 12, 20.
    const int loop[] = {0, 3, 1, 4, 2, 5};
    ASSERT_EQ(faces[c].outline.size(), 6u);
    for (int k = 0; k < 6; ++k) EXPECT_EQ(faces[c].outline[k], Eigen::Vector2d(mesh.x.col(b.cell(c)[loop[k]])));
  }
}

TEST(MeshFaces, CutCubeBoundaryFarToNear) {
  // 2 × 2 × 2 hexahedra: the 4 with centres at y = 0.25 stay, a 2 × 1 × 2 slab of 16 faces.
  const Mesh mesh = structured_mesh(ElementType::Hexahedron, 1, 2);
  const std::vector<Face> faces = mesh_faces(mesh);
  ASSERT_EQ(faces.size(), 16u);
  for (const Face& f : faces) {
    ASSERT_EQ(f.outline.size(), 4u);
    double y = 0.0;
    for (int k = 0; k < 8; ++k) y += mesh.x(1, mesh.cells[0].cell(static_cast<std::size_t>(f.cell))[k]);
    EXPECT_LT(y / 8, 0.5);
  }
  // Farthest from the eye: the face at y = 0 by the origin; nearest: the cut's face at x, z = 1.
  EXPECT_TRUE(centroid(faces.front()).isApprox(seen({0.25, 0.0, 0.25}), 1e-12));
  EXPECT_TRUE(centroid(faces.back()).isApprox(seen({0.75, 0.5, 0.75}), 1e-12));
}

TEST(MeshFaces, CurvedHexahedronFacesThroughTheirEdgeNodes) {
  // Straight-sided P2: each face's loop alternates corners and the midpoints of its edges.
  const std::vector<Face> faces = mesh_faces(structured_mesh(ElementType::Hexahedron, 2, 1));
  ASSERT_EQ(faces.size(), 6u);
  for (const Face& f : faces) {
    ASSERT_EQ(f.outline.size(), 8u);
    for (std::size_t k = 1; k < 8; k += 2)
      EXPECT_TRUE(f.outline[k].isApprox(0.5 * (f.outline[k - 1] + f.outline[(k + 1) % 8]), 1e-12));
  }
}

TEST(CellField, DisplacementIsTheMeanOverTheCellsNodes) {
  const Mesh reference = structured_mesh(ElementType::Quadrilateral, 1, 2);
  Mesh moved = reference;
  moved.x(0, 0) += 0.4;  // node 0 is a corner of one cell only
  const CellField f = cell_field(moved, "displacement", &reference);
  ASSERT_EQ(f.values.size(), 4u);
  int touched = 0;
  for (const double v : f.values) {
    EXPECT_TRUE(v == 0.0 || std::abs(v - 0.1) < 1e-15) << v;
    touched += v > 0.0;
  }
  EXPECT_EQ(touched, 1);
  for (const double q : cell_field(reference, "shape_quality", nullptr).values) EXPECT_NEAR(q, 1.0, 1e-12);
}

TEST(CellField, NeedsTheReferenceAndAKnownName) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 1);
  EXPECT_THROW(cell_field(mesh, "quality", nullptr), InputError);
  EXPECT_THROW(cell_field(mesh, "displacement", nullptr), InputError);
  EXPECT_THROW(cell_field(mesh, "colour", nullptr), InputError);
}

}  // namespace
}  // namespace meshmorph::detail

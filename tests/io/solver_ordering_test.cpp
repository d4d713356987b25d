// SPDX-License-Identifier: MIT
#include "meshmorph/io/solver_ordering.h"

#include <algorithm>
#include <numeric>
#include <vector>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/validity.h"

namespace meshmorph {
namespace {

const std::vector<std::pair<ElementType, int>>& all_types() {
  static const std::vector<std::pair<ElementType, int>> out = [] {
    std::vector<std::pair<ElementType, int>> v;
    for (const ElementType t : {ElementType::Line, ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron,
                                ElementType::Hexahedron, ElementType::Prism, ElementType::Pyramid})
      for (int p = 1; p <= max_order_of(t); ++p) v.emplace_back(t, p);
    return v;
  }();
  return out;
}

// Every family and order meshmorph holds has a CGNS element, and a permutation that puts
// CGNS's reference points on the internal reference nodes.
TEST(SolverOrdering, CgnsPointsLandOnTheReferenceNodes) {
  for (const auto& [type, order] : all_types()) {
    SCOPED_TRACE(std::string(name_of(type)) + std::to_string(order));
    const int cgns = cgns_element_type(type, order);
    ASSERT_NE(cgns, 0);
    EXPECT_EQ(cgns_type_order(cgns), std::optional(TypeOrder{type, order}));
    const std::vector<int>& perm = cgns_to_gmsh_permutation(type, order);
    const Eigen::MatrixXd cg = cgns_reference_points(type, order);
    const Eigen::MatrixXd& ref = reference_element(type, order).nodes;
    ASSERT_EQ(static_cast<Eigen::Index>(perm.size()), ref.cols());
    for (std::size_t i = 0; i < perm.size(); ++i)
      EXPECT_LT((cg.col(static_cast<Eigen::Index>(i)) - ref.col(perm[i])).norm(), 1e-12) << "CGNS node " << i;
    std::vector<int> sorted = perm;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int> iota(perm.size());
    std::iota(iota.begin(), iota.end(), 0);
    EXPECT_EQ(sorted, iota);
    // Corners come first, in the same order in both conventions.
    for (int c = 0; c < n_corners_of(type); ++c) EXPECT_EQ(perm[static_cast<std::size_t>(c)], c);
  }
}

// A cell given in CGNS's (or Exodus's) node order at an affine image A x + b of CGNS's reference
// points, read through the permutation, has the Jacobian A everywhere: min det = det A > 0.
TEST(SolverOrdering, ReferenceCellsReadInHaveTheJacobianOfTheirMap) {
  for (const auto& [type, order] : all_types()) {
    if (topological_dim(type) < 2) continue;
    SCOPED_TRACE(std::string(name_of(type)) + std::to_string(order));
    const int d = topological_dim(type);
    Eigen::MatrixXd A = Eigen::MatrixXd::Identity(d, d) * 2.0;
    A(0, 1) = 0.3;
    A(d - 1, 0) = -0.2;
    const Eigen::MatrixXd cgns = (A * cgns_reference_points(type, order)).colwise() + Eigen::VectorXd::Constant(d, 0.5);
    for (const bool exodus : {false, true}) {
      if (exodus && order > 2) continue;
      const std::vector<int>& perm = exodus ? exodus_to_gmsh_permutation(type, order) : cgns_to_gmsh_permutation(type, order);
      // The file's points: Exodus node i is the CGNS node that lands on the same Gmsh node.
      const std::vector<int>& cp = cgns_to_gmsh_permutation(type, order);
      Eigen::MatrixXd in_file(d, cgns.cols());
      for (std::size_t i = 0; i < perm.size(); ++i)
        in_file.col(static_cast<Eigen::Index>(i)) = cgns.col(std::find(cp.begin(), cp.end(), perm[i]) - cp.begin());
      Eigen::MatrixXd gmsh(d, static_cast<Eigen::Index>(perm.size()));
      for (std::size_t i = 0; i < perm.size(); ++i) gmsh.col(perm[i]) = in_file.col(static_cast<Eigen::Index>(i));
      EXPECT_NEAR(min_jacobian_det(type, order, gmsh), A.determinant(), 1e-9) << (exodus ? "Exodus" : "CGNS");
    }
  }
}

// Tables read off the CGNS SIDS and the Exodus II manual, node by node against Gmsh's
// documented orders (tet10: Gmsh's nodes 8 and 9 lie on edges 2–3 and 1–3; hex27: Gmsh's
// edges (0 1) (0 3) (0 4) (1 2) (1 5) (2 3) (2 6) (3 7) (4 5) (4 7) (5 6) (6 7), faces -z -y
// -x +x +y +z, centre).
TEST(SolverOrdering, PermutationTables) {
  const std::vector<int> tet10{0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
  EXPECT_EQ(cgns_to_gmsh_permutation(ElementType::Tetrahedron, 2), tet10);
  EXPECT_EQ(exodus_to_gmsh_permutation(ElementType::Tetrahedron, 2), tet10);
  const std::vector<int> edges{8, 11, 13, 9, 10, 12, 14, 15, 16, 18, 19, 17};
  std::vector<int> cgns_hex27{0, 1, 2, 3, 4, 5, 6, 7};
  cgns_hex27.insert(cgns_hex27.end(), edges.begin(), edges.end());
  std::vector<int> exodus_hex27 = cgns_hex27;
  cgns_hex27.insert(cgns_hex27.end(), {20, 21, 23, 24, 22, 25, 26});    // -z, 4 sides from (1 2 6 5), +z, centre
  exodus_hex27.insert(exodus_hex27.end(), {26, 20, 25, 22, 23, 21, 24});  // centre, -z, +z, -x, +x, -y, +y
  EXPECT_EQ(cgns_to_gmsh_permutation(ElementType::Hexahedron, 2), cgns_hex27);
  EXPECT_EQ(exodus_to_gmsh_permutation(ElementType::Hexahedron, 2), exodus_hex27);
  // Triangles and quadrilaterals of order 2 and the linear cells agree with Gmsh.
  for (const auto& [type, order] : {std::pair{ElementType::Triangle, 2}, {ElementType::Quadrilateral, 2}, {ElementType::Prism, 1},
                                    {ElementType::Pyramid, 1}, {ElementType::Triangle, 3}}) {
    std::vector<int> id(static_cast<std::size_t>(n_nodes_of(type, order)));
    std::iota(id.begin(), id.end(), 0);
    EXPECT_EQ(cgns_to_gmsh_permutation(type, order), id) << name_of(type) << order;
  }
}

TEST(SolverOrdering, ExodusNamesAndSides) {
  EXPECT_EQ(exodus_element_name(ElementType::Hexahedron, 2), "HEX27");
  EXPECT_EQ(exodus_element_name(ElementType::Prism, 2), "WEDGE18");
  EXPECT_EQ(exodus_element_name(ElementType::Pyramid, 2), "PYRAMID14");
  EXPECT_EQ(exodus_element_name(ElementType::Tetrahedron, 3), "");
  EXPECT_EQ(exodus_type_order("tetra", 10), std::optional(TypeOrder{ElementType::Tetrahedron, 2}));
  EXPECT_EQ(exodus_type_order("TET4", 4), std::optional(TypeOrder{ElementType::Tetrahedron, 1}));
  EXPECT_EQ(exodus_type_order("HEX", 20), std::nullopt);  // serendipity
  EXPECT_EQ(exodus_type_order("SHELL4", 4), std::nullopt);
  // Every side's corners are a facet of the cell, each facet once.
  for (const ElementType t : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron,
                              ElementType::Prism, ElementType::Pyramid}) {
    SCOPED_TRACE(name_of(t));
    const auto& sides = exodus_sides(t);
    ASSERT_EQ(sides.size(), static_cast<std::size_t>(t == ElementType::Triangle ? 3 : t == ElementType::Quadrilateral ? 4
                                                      : t == ElementType::Tetrahedron ? 4 : t == ElementType::Hexahedron ? 6 : 5));
    // Exodus sides face outward: their corners' normal (3D) or direction (2D) as the
    // reference cell's own facets have it, checked by the centroid lying behind each side.
    const Eigen::MatrixXd& x = reference_element(t, 1).nodes;
    const Eigen::VectorXd centre = x.rowwise().mean();
    for (const auto& s : sides) {
      const Eigen::VectorXd a = x.col(s[0]), b = x.col(s[1]);
      double outward = 0;
      if (x.rows() == 2) {
        const Eigen::Vector2d e = b - a, n(e(1), -e(0));
        outward = n.dot(a - centre);
      } else {
        const Eigen::Vector3d c = x.col(s[2]);
        outward = (Eigen::Vector3d(b - a)).cross(Eigen::Vector3d(c - a)).dot(Eigen::Vector3d(a - centre));
      }
      EXPECT_GT(outward, 0) << "side " << s[0] << s[1];
    }
  }
}

}  // namespace
}  // namespace meshmorph

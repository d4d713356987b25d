// SPDX-License-Identifier: MIT
#include "meshmorph/fem/reference_element.h"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/mesh/topology.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

using test::ElementCase;

class ReferenceElementSweep : public ::testing::TestWithParam<ElementCase> {};

TEST_P(ReferenceElementSweep, HasDistinctNodesStartingWithTheCorners) {
  const auto& ref = reference_element(GetParam().type, GetParam().order);
  ASSERT_EQ(ref.n_nodes(), n_nodes_of(ref.type, ref.order));
  const auto& corners = reference_element(ref.type, 1).nodes;
  EXPECT_EQ((ref.nodes.leftCols(corners.cols()) - corners).norm(), 0.0);
  for (int a = 0; a < ref.n_nodes(); ++a)
    for (int b = a + 1; b < ref.n_nodes(); ++b) EXPECT_GT((ref.nodes.col(a) - ref.nodes.col(b)).norm(), 1e-3);
}

// The trace of facet f lists the facet element's nodes: all on the facet's corners' plane,
// the right count, corners first and equal to corner_facets.
TEST_P(ReferenceElementSweep, TraceListsTheFacetNodesInFacetOrder) {
  const auto& ref = reference_element(GetParam().type, GetParam().order);
  const auto facets = corner_facets(ref.type);
  ASSERT_EQ(ref.facet_nodes.size(), facets.size());
  for (std::size_t f = 0; f < facets.size(); ++f) {
    const auto ft = facet_type(ref.type, static_cast<int>(f));
    const auto& tr = ref.facet_nodes[f];
    ASSERT_EQ(static_cast<int>(tr.size()), n_nodes_of(ft, ref.order));
    for (std::size_t i = 0; i < facets[f].size(); ++i) EXPECT_EQ(tr[i], facets[f][i]);
    // Each trace node is the facet map of the facet element's own reference node.
    const auto& fref = reference_element(ft, ref.order);
    for (std::size_t j = 0; j < tr.size(); ++j) {
      const auto w = corner_weights(ft, fref.nodes.col(static_cast<Eigen::Index>(j)));
      Eigen::VectorXd x = Eigen::VectorXd::Zero(ref.dim);
      for (std::size_t i = 0; i < facets[f].size(); ++i) x += w(static_cast<Eigen::Index>(i)) * ref.nodes.col(facets[f][i]);
      EXPECT_LT((ref.nodes.col(tr[j]) - x).norm(), 1e-12);
    }
  }
}

TEST_P(ReferenceElementSweep, FacetNormalsPointOutward) {
  const auto& ref = reference_element(GetParam().type, 1);
  const Eigen::VectorXd centroid = ref.nodes.rowwise().mean();
  for (const auto& f : corner_facets(ref.type)) {
    Eigen::VectorXd n(ref.dim);
    const Eigen::VectorXd a = ref.nodes.col(f[0]), b = ref.nodes.col(f[1]);
    if (ref.dim == 2) {
      n << (b - a)(1), -(b - a)(0);  // right of the edge direction
    } else {
      const Eigen::Vector3d u = ref.nodes.col(f[1]) - ref.nodes.col(f[0]), v = ref.nodes.col(f.back()) - ref.nodes.col(f[0]);
      n = u.cross(v);
    }
    EXPECT_GT(n.dot(a - centroid), 0.0);
  }
}

INSTANTIATE_TEST_SUITE_P(AllCells, ReferenceElementSweep, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());
INSTANTIATE_TEST_SUITE_P(PrismPyramid, ReferenceElementSweep, ::testing::ValuesIn(test::prism_pyramid_cases()), test::CaseName());

TEST(CornerWeights, AreOneAtTheirCornerAndSumToOne) {
  for (auto t : {ElementType::Line, ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron,
                 ElementType::Hexahedron}) {
    const auto& ref = reference_element(t, 1);
    for (int a = 0; a < ref.n_nodes(); ++a) {
      const auto w = corner_weights(t, ref.nodes.col(a));
      for (int b = 0; b < ref.n_nodes(); ++b) EXPECT_DOUBLE_EQ(w(b), a == b ? 1.0 : 0.0);
    }
    EXPECT_NEAR(corner_weights(t, ref.nodes.rowwise().mean()).sum(), 1.0, 1e-15);
  }
}

}  // namespace
}  // namespace meshmorph

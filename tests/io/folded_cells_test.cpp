// SPDX-License-Identifier: MIT
// Curved cells read from files whose det A is negative between the validity samples.
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

// Cells that QA found folded between the validity samples (det A < 0 on part of each, by
// dense sampling; a test at the samples alone calls them valid): every sample is positive, and the
// Bernstein bounds find the fold.
TEST(FoldedCells, BernsteinBoundsCatchFoldsBetweenTheSamples) {
  for (const char* name : {"triangle_3", "triangle_4", "quadrilateral_3", "tetrahedron_3", "hexahedron_2"}) {
    SCOPED_TRACE(name);
    const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/folded_between_samples/" + name + ".msh");
    const CellBlock& b = mesh.cells.at(0);
    const Eigen::MatrixXd X = cell_coordinates(mesh, b, 0);
    const std::vector<std::uint8_t> keep(static_cast<std::size_t>(validity_samples(b.type, b.order).n_points()), 0);
    EXPECT_GT(min_jacobian_det(b.type, b.order, X, keep), 0.0);
    EXPECT_LE(min_jacobian_det(b.type, b.order, X), 0.0);
    EXPECT_EQ(count_invalid_cells(mesh), 1u);
  }
}

}  // namespace
}  // namespace meshmorph

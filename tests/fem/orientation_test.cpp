// SPDX-License-Identifier: MIT
#include "meshmorph/fem/orientation.h"

#include <gtest/gtest.h>

#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/validity.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

using test::ElementCase;

class OrientationSweep : public ::testing::TestWithParam<ElementCase> {
 protected:
  // The unit square or cube under (x, y[, z]) → (x + 0.1xy, y + 0.1x², z), curved where the
  // order holds the quadratic map exactly; its volume is ∫ 1 + 0.1y − 0.02x² = 1.05 − 0.02/3.
  Mesh curved() const {
    Mesh mesh = structured_mesh(GetParam().type, GetParam().order, 2);
    if (GetParam().order >= 2) {
      for (Eigen::Index j = 0; j < mesh.x.cols(); ++j) {
        const double x = mesh.x(0, j), y = mesh.x(1, j);
        mesh.x(0, j) = x + 0.1 * x * y;
        mesh.x(1, j) = y + 0.1 * x * x;
      }
    }
    return mesh;
  }
  double exact_volume() const { return GetParam().order >= 2 ? 1.05 - 0.02 / 3.0 : 1.0; }
};

TEST_P(OrientationSweep, AStructuredMeshIsOrientedAlikeAndItsVolumeIsExact) {
  const Mesh mesh = curved();
  const Topology topo = build_topology(mesh);
  const std::vector<double> volumes = signed_volumes(mesh);
  const CellOrientation o = cell_orientation(mesh, topo, volumes);
  EXPECT_TRUE(o.consistent());
  const VolumeBalance v = volume_balance(mesh, topo, volumes, o);
  EXPECT_NEAR(v.cells, exact_volume(), 1e-13);
  EXPECT_NEAR(v.enclosed, exact_volume(), 1e-13);
  EXPECT_TRUE(v.balanced());
}

TEST_P(OrientationSweep, AMirroredCellIsNamedAndTheVolumesDifferByTwiceItsVolume) {
  Mesh mesh = curved();
  const Topology topo = build_topology(mesh);
  const std::vector<double> before = signed_volumes(mesh);
  const auto cell = static_cast<std::int32_t>(mesh.n_cells() / 2);
  mirror_cells(mesh, topo, {cell});
  // The mirrored cell is the same point set listed the other way: its volume changes sign.
  const std::vector<double> after = signed_volumes(mesh);
  EXPECT_NEAR(after[static_cast<std::size_t>(cell)], -before[static_cast<std::size_t>(cell)], 1e-14);
  EXPECT_EQ(count_invalid_cells(mesh), 1u);

  const Topology mirrored = build_topology(mesh);
  const CellOrientation o = cell_orientation(mesh, mirrored, after);
  EXPECT_EQ(o.flipped, std::vector<std::int32_t>{cell});
  EXPECT_EQ(o.twisted_cell, -1);
  const VolumeBalance v = volume_balance(mesh, mirrored, after, o);
  EXPECT_FALSE(v.balanced());
  EXPECT_NEAR(v.enclosed, exact_volume(), 1e-13);
  EXPECT_NEAR(v.cells, exact_volume() - 2.0 * before[static_cast<std::size_t>(cell)], 1e-13);

  // Mirrored back, the mesh is the one it was.
  mirror_cells(mesh, mirrored, o.flipped);
  EXPECT_EQ(mesh.cells.at(0).nodes, curved().cells.at(0).nodes);
}

// A mesh whose every cell is listed mirrored has no cell unlike its neighbours, but its
// boundary is inside out: every cell is flipped against the orientation of positive volume.
TEST_P(OrientationSweep, AMeshMirroredWholeHasEveryCellFlipped) {
  Mesh mesh = curved();
  const Topology topo = build_topology(mesh);
  std::vector<std::int32_t> all(mesh.n_cells());
  for (std::size_t c = 0; c < all.size(); ++c) all[c] = static_cast<std::int32_t>(c);
  mirror_cells(mesh, topo, all);
  const Topology mirrored = build_topology(mesh);
  const std::vector<double> volumes = signed_volumes(mesh);
  const CellOrientation o = cell_orientation(mesh, mirrored, volumes);
  EXPECT_EQ(o.flipped, all);
  const VolumeBalance v = volume_balance(mesh, mirrored, volumes, o);
  EXPECT_NEAR(v.cells, -exact_volume(), 1e-13);
  EXPECT_NEAR(v.enclosed, exact_volume(), 1e-13);
}

INSTANTIATE_TEST_SUITE_P(AllCells, OrientationSweep, ::testing::ValuesIn(test::all_cell_cases()), test::CaseName());
INSTANTIATE_TEST_SUITE_P(PrismPyramid, OrientationSweep, ::testing::ValuesIn(test::prism_pyramid_cases()), test::CaseName());

// The balance does not depend on where the mesh lies: far from the origin, the boundary terms
// are taken about the middle of the mesh.
TEST(VolumeBalance, AMeshFarFromTheOriginBalancesToRounding) {
  Mesh mesh = structured_mesh(ElementType::Hexahedron, 2, 3);
  mesh.x.array() += 1e7;
  const Topology topo = build_topology(mesh);
  const std::vector<double> volumes = signed_volumes(mesh);
  const VolumeBalance v = volume_balance(mesh, topo, volumes, cell_orientation(mesh, topo, volumes));
  EXPECT_TRUE(v.balanced());
  EXPECT_NEAR(v.enclosed, 1.0, 1e-8);
}

}  // namespace
}  // namespace meshmorph

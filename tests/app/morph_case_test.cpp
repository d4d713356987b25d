// SPDX-License-Identifier: MIT
// The hybrid boundary-layer benchmark (bench/cases/hybrid_bl_sphere_move.json) on a small
// version of its mesh: tests/data/hybrid_bl_sphere.msh is bench/geo/hybrid_bl_sphere.geo with
// `-setnumber h_wall 0.3 -setnumber h_far 2 -setnumber B 3 -setnumber n_layers 10` (gmsh
// 4.8.4, one thread): the sphere of diameter 1 under 10 layers of prisms and hexahedra, the
// first 5e-4 thick, pyramids on the hexahedra's top faces, tetrahedra out to the box [-3, 3]³.
#include "meshmorph/app/morph_case.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

const std::filesystem::path kData = MESHMORPH_TEST_DATA;

const CellTypeMinima* minima_of(const Report& r, const std::string& type) {
  for (const CellTypeMinima& t : r.cell_types)
    if (t.type == type) return &t;
  return nullptr;
}

// The wall turns 30° about the z axis through the sphere's centre and moves by one diameter
// along x: one rotation by 30° about the parallel axis through (1/2, 1/2 cot 15°, 0), the
// form the case file takes. The result is valid, on its target to 1e-8 of the body's size,
// and its prisms keep 0.5 of their input quality.
TEST(MorphCase, AHybridBoundaryLayerTurnsAndTranslates) {
  const std::string text = R"({
    "mesh": "hybrid_bl_sphere.msh",
    "boundary": [
      {"group": "wall", "rotate": {"center": [0.5, 1.8660254037844386, 0], "axis": [0, 0, 1], "degrees": 30}},
      {"group": "farfield", "fixed": true}
    ]})";
  const CaseFile c = parse_case_file(text, kData / "hybrid_bl_sphere_move.json");
  MorphRunner runner(c, read_mesh(c.mesh), 0);
  const MorphOutput run = runner.run();
  const Report& r = run.report;
  ASSERT_TRUE(r.valid) << r.message;
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.inverted_elements, 0u);
  ASSERT_TRUE(r.boundary_error_max);
  EXPECT_LE(*r.boundary_error_max, 1e-8);

  const double a = M_PI / 6.0;
  const Mesh& in = runner.input();
  const auto wall = in.find_group("wall");
  ASSERT_TRUE(wall);
  double off = 0.0;
  for (std::int32_t n : in.group_nodes(*wall)) {
    const Eigen::Vector3d x = in.x.col(n);
    const Eigen::Vector3d moved(std::cos(a) * x.x() - std::sin(a) * x.y() + 1.0, std::sin(a) * x.x() + std::cos(a) * x.y(), x.z());
    off = std::max(off, (run.moved.x.col(n) - moved).norm());
  }
  EXPECT_LE(off, 1e-8);

  ASSERT_EQ(r.cell_types.size(), 4u);
  const CellTypeMinima* prism = minima_of(r, "prism");
  ASSERT_TRUE(prism && prism->min_quality);
  EXPECT_EQ(prism->elements, 1120u);
  EXPECT_GE(*prism->min_quality, 0.5);
  EXPECT_GE(*r.min_quality, 0.5);
  EXPECT_EQ(*r.min_quality, std::min({*prism->min_quality, *minima_of(r, "pyramid")->min_quality,
                                       *minima_of(r, "hexahedron")->min_quality, *minima_of(r, "tetrahedron")->min_quality}));
}

}  // namespace
}  // namespace meshmorph

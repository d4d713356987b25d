// SPDX-License-Identifier: MIT
// What fit picks when a case holds only the mesh and the level set (docs/fit.md, Choices).
#include "meshmorph/app/fit_case.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/validity.h"

namespace meshmorph {
namespace {

FitSetup set_up(const Mesh& mesh, const std::string& options) {
  const std::string centre = mesh.dim == 2 ? "[0.5, 0.5]" : "[0.5, 0.5, 0.5]";
  const CaseFile c = parse_case_file(R"({"interface": {"sphere": {"center": )" + centre +
                                         R"(, "radius": 0.3}}, "options": )" + options + "}",
                                     "case.json", false);
  return prepare_fit(c, mesh, read_fit_settings(c, 1), "case.json");
}

// A sphere in cubes: both sides are pillowed, no cell keeps two interface facets, the mesh
// stays valid, and the target is the input (the layers are thin); eps_sigma is 1e-9 of the
// diagonal. Without pillowing the cells with two facets stay and the cubes keep the ideal
// target.
TEST(FitCase, PillowsHexahedraAndPicksTheirTarget) {
  const Mesh cubes = structured_mesh(ElementType::Hexahedron, 1, 6);
  const FitSetup s = set_up(cubes, "{}");
  EXPECT_GT(s.pillowed_cells, 0u);
  EXPECT_EQ(s.mesh.n_cells(), cubes.n_cells() + s.pillowed_cells);
  EXPECT_EQ(s.two_facet_cells, 0u);
  EXPECT_EQ(count_invalid_cells(s.mesh), 0u);
  EXPECT_EQ(s.fit.target, TargetKind::Input);
  EXPECT_DOUBLE_EQ(s.fit.eps_sigma, 1e-9 * std::sqrt(3.0));
  for (const char* key : {"eps_sigma", "materials", "pillow", "target", "solver"}) EXPECT_TRUE(s.choices.contains(key)) << key;
  EXPECT_EQ(s.choices["pillow"]["cells_added"], s.pillowed_cells);

  const FitSetup plain = set_up(cubes, R"({"pillow": false, "eps_sigma": 1e-6})");
  EXPECT_EQ(plain.pillowed_cells, 0u);
  EXPECT_GT(plain.two_facet_cells, 0u);
  EXPECT_EQ(plain.fit.target, TargetKind::Ideal);
  EXPECT_EQ(plain.fit.eps_sigma, 1e-6);
  EXPECT_FALSE(plain.choices.contains("eps_sigma"));
}

// Quadrilaterals are pillowed only when asked (in place of the splits).
TEST(FitCase, PillowsQuadrilateralsOnlyWhenAsked) {
  const Mesh quads = structured_mesh(ElementType::Quadrilateral, 1, 10);
  EXPECT_EQ(set_up(quads, "{}").pillowed_cells, 0u);
  const FitSetup s = set_up(quads, R"({"pillow": true})");
  EXPECT_GT(s.pillowed_cells, 0u);
  EXPECT_EQ(s.split_cells, 0u);
  EXPECT_EQ(s.two_facet_cells, 0u);
  EXPECT_EQ(count_invalid_cells(s.mesh), 0u);
  // Eq. 12 leaves no triangle with two interface facets: nothing to pillow.
  EXPECT_EQ(set_up(structured_mesh(ElementType::Triangle, 1, 10), R"({"pillow": true})").pillowed_cells, 0u);
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph::test {

/// One (family, order) of a cell type, for parameterized sweeps.
struct ElementCase {
  ElementType type;
  int order;
};

/// Every simplex and tensor cell family at every supported order: triangles and tetrahedra
/// 1–4, quadrilaterals and hexahedra 1–3.
inline std::vector<ElementCase> all_cell_cases() {
  std::vector<ElementCase> out;
  for (auto t : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron, ElementType::Hexahedron})
    for (int p = 1; p <= max_order_of(t); ++p) out.push_back({t, p});
  return out;
}

/// Prisms 1–4 and pyramids 1–2: a second instantiation of the sweeps that hold for any cell
/// (those written for simplices and tensor cells only keep all_cell_cases).
inline std::vector<ElementCase> prism_pyramid_cases() {
  std::vector<ElementCase> out;
  for (auto t : {ElementType::Prism, ElementType::Pyramid})
    for (int p = 1; p <= max_order_of(t); ++p) out.push_back({t, p});
  return out;
}

inline std::string case_name(const ElementCase& c) { return std::string(name_of(c.type)) + "_p" + std::to_string(c.order); }

/// Test-name generator for INSTANTIATE_TEST_SUITE_P over ElementCase.
struct CaseName {
  std::string operator()(const ::testing::TestParamInfo<ElementCase>& p) const { return case_name(p.param); }
};

}  // namespace meshmorph::test

// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph::detail {

/// An element type of SU2 files: its VTK id and family (linear cells only).
struct Su2Type {
  int id;
  ElementType type;
};

inline constexpr Su2Type k_su2_types[] = {
    {3, ElementType::Line},         {5, ElementType::Triangle},    {9, ElementType::Quadrilateral},
    {10, ElementType::Tetrahedron}, {12, ElementType::Hexahedron}, {13, ElementType::Prism},
    {14, ElementType::Pyramid},
};

/// The type of VTK id `id`, or null.
inline const Su2Type* su2_type(int id) {
  for (const Su2Type& t : k_su2_types)
    if (t.id == id) return &t;
  return nullptr;
}

/// The VTK id of a family.
inline int su2_id(ElementType type) {
  for (const Su2Type& t : k_su2_types)
    if (t.type == type) return t.id;
  return 0;
}

/// "5 (triangle), 9 (quadrilateral)": the ids of the families of topological dimension `dim`.
inline std::string su2_types_of_dim(int dim) {
  std::string s;
  for (const Su2Type& t : k_su2_types)
    if (topological_dim(t.type) == dim)
      s += (s.empty() ? "" : ", ") + std::to_string(t.id) + " (" + std::string(name_of(t.type)) + ")";
  return s;
}

}  // namespace meshmorph::detail

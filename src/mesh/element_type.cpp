// SPDX-License-Identifier: MIT
#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

std::string_view name_of(ElementType t) {
  switch (t) {
    case ElementType::Point: return "point";
    case ElementType::Line: return "line";
    case ElementType::Triangle: return "triangle";
    case ElementType::Quadrilateral: return "quadrilateral";
    case ElementType::Tetrahedron: return "tetrahedron";
    case ElementType::Hexahedron: return "hexahedron";
    case ElementType::Prism: return "prism";
    case ElementType::Pyramid: return "pyramid";
  }
  return "unknown";
}

}  // namespace meshmorph

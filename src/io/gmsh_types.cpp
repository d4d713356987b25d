// SPDX-License-Identifier: MIT
#include "io/detail/gmsh_types.h"

#include <array>

#include "io/detail/promote.h"
#include "meshmorph/error.h"

namespace meshmorph::detail {
namespace {

struct Entry {
  int code;
  ElementType type;
  int order;
};

// GmshDefines.h numbers of the complete Lagrange elements of our families.
constexpr std::array<Entry, 27> k_types{{
    {15, ElementType::Point, 1},
    {1, ElementType::Line, 1}, {8, ElementType::Line, 2}, {26, ElementType::Line, 3}, {27, ElementType::Line, 4},
    {2, ElementType::Triangle, 1}, {9, ElementType::Triangle, 2}, {21, ElementType::Triangle, 3}, {23, ElementType::Triangle, 4},
    {3, ElementType::Quadrilateral, 1}, {10, ElementType::Quadrilateral, 2}, {36, ElementType::Quadrilateral, 3}, {37, ElementType::Quadrilateral, 4},
    {4, ElementType::Tetrahedron, 1}, {11, ElementType::Tetrahedron, 2}, {29, ElementType::Tetrahedron, 3}, {30, ElementType::Tetrahedron, 4},
    {5, ElementType::Hexahedron, 1}, {12, ElementType::Hexahedron, 2}, {92, ElementType::Hexahedron, 3}, {93, ElementType::Hexahedron, 4},
    {6, ElementType::Prism, 1}, {13, ElementType::Prism, 2}, {90, ElementType::Prism, 3}, {91, ElementType::Prism, 4},
    {7, ElementType::Pyramid, 1}, {14, ElementType::Pyramid, 2},
}};

// The incomplete (serendipity) types read as the complete quadratic cells.
constexpr std::array<Entry, 4> k_incomplete{{
    {16, ElementType::Quadrilateral, 2}, {17, ElementType::Hexahedron, 2}, {18, ElementType::Prism, 2}, {19, ElementType::Pyramid, 2},
}};

}  // namespace

std::optional<FamilyOrder> from_gmsh_type(int code) {
  for (const Entry& e : k_types)
    if (e.code == code) return FamilyOrder{e.type, e.order};
  for (const Entry& e : k_incomplete)
    if (e.code == code) return FamilyOrder{e.type, e.order, incomplete_nodes_of(e.type)};
  return std::nullopt;
}

std::string describe_unsupported_gmsh_type(int code) {
  const char* what = nullptr;
  switch (code) {
    case 20: what = "serendipity/incomplete element type 20 (TRI_9)"; break;
    case 22: what = "serendipity/incomplete element type 22 (TRI_12)"; break;
    case 24: what = "serendipity/incomplete element type 24 (TRI_15I)"; break;
    case 32: what = "serendipity/incomplete element type 32 (TET_22)"; break;
    case 33: what = "serendipity/incomplete element type 33 (TET_28)"; break;
    case 39: what = "serendipity/incomplete element type 39 (QUA_12)"; break;
    case 40: what = "serendipity/incomplete element type 40 (QUA_16I)"; break;
    case 99: what = "serendipity/incomplete element type 99 (HEX_32)"; break;
    default: break;
  }
  if (what) return std::string(what) + " is not supported (complete Lagrange elements only)";
  return "unsupported element type " + std::to_string(code);
}

int gmsh_type_of(ElementType type, int order) {
  if (type == ElementType::Point) return 15;
  for (const Entry& e : k_types)
    if (e.type == type && e.order == order) return e.code;
  throw InputError("MSH has no element type for " + std::string(name_of(type)) + " of order " + std::to_string(order));
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string_view>

namespace meshmorph {

/// Geometric element families. Cells are Triangle/Quadrilateral (2D) and
/// Tetrahedron/Hexahedron/Prism (wedge)/Pyramid (3D); Point, Line and the 2D families also
/// serve as facets and as lower-dimensional tagged entities.
enum class ElementType : std::uint8_t { Point, Line, Triangle, Quadrilateral, Tetrahedron, Hexahedron, Prism, Pyramid };

/// Topological dimension of a family (Point 0, Line 1, Triangle/Quadrilateral 2, else 3).
constexpr int topological_dim(ElementType t) {
  switch (t) {
    case ElementType::Point: return 0;
    case ElementType::Line: return 1;
    case ElementType::Triangle:
    case ElementType::Quadrilateral: return 2;
    default: return 3;
  }
}

/// Point, Line, Triangle and Tetrahedron (a Line is also a tensor cell of one axis).
constexpr bool is_simplex(ElementType t) {
  return t == ElementType::Point || t == ElementType::Line || t == ElementType::Triangle || t == ElementType::Tetrahedron;
}

/// Quadrilateral and Hexahedron: products of segments on [−1, 1]^d.
constexpr bool is_tensor(ElementType t) { return t == ElementType::Quadrilateral || t == ElementType::Hexahedron; }

/// Number of Lagrange nodes of a family at order p (complete elements; Point: 1).
constexpr int n_nodes_of(ElementType t, int p) {
  switch (t) {
    case ElementType::Point: return 1;
    case ElementType::Line: return p + 1;
    case ElementType::Triangle: return (p + 1) * (p + 2) / 2;
    case ElementType::Quadrilateral: return (p + 1) * (p + 1);
    case ElementType::Tetrahedron: return (p + 1) * (p + 2) * (p + 3) / 6;
    case ElementType::Hexahedron: return (p + 1) * (p + 1) * (p + 1);
    case ElementType::Prism: return (p + 1) * (p + 1) * (p + 2) / 2;
    case ElementType::Pyramid: return (p + 1) * (p + 2) * (2 * p + 3) / 6;
  }
  return 0;
}

/// Number of corner vertices of a family.
constexpr int n_corners_of(ElementType t) { return n_nodes_of(t, 1); }

/// Highest supported order: 4 for simplices and prisms, 3 for tensor cells, 2 for pyramids
/// (Point: 0).
constexpr int max_order_of(ElementType t) {
  switch (t) {
    case ElementType::Point: return 0;
    case ElementType::Prism: return 4;
    case ElementType::Pyramid: return 2;
    default: return is_simplex(t) ? 4 : 3;
  }
}

/// Lower-case name: "point", "line", "triangle", "quadrilateral", "tetrahedron", "hexahedron",
/// "prism", "pyramid".
std::string_view name_of(ElementType t);

}  // namespace meshmorph

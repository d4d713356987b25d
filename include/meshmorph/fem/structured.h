// SPDX-License-Identifier: MIT
#pragma once
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// A straight-sided mesh of the unit square (Triangle, Quadrilateral) or unit cube
/// (Tetrahedron, Hexahedron, Prism, Pyramid) with n cells per side (triangles: 2 per square;
/// tetrahedra: 6 per cube, Kuhn subdivision; prisms: 2 per cube; pyramids: 6 per cube around
/// a node at its centre), elevated to `order`. Prisms' boundary facets are a triangle block
/// and a quadrilateral block. Groups: the cells are "domain"
/// (tag 1, dimension d); the boundary facets are "left" (x = 0), "right" (x = 1),
/// "bottom", "top" (y = 0, 1 in 2D; z = 0, 1 in 3D) and in 3D "front", "back" (y = 0, 1),
/// tags 1–6 in that order, dimension d − 1. For tests, benchmarks and examples.
Mesh structured_mesh(ElementType type, int order, int n);

}  // namespace meshmorph

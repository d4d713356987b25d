// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstddef>
#include <cstdint>

#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// Where the boundary of a mesh passes through itself. With cells listed alike and every cell
/// positive, the map of a mesh is injective exactly when its boundary does not meet itself
/// (docs/metrics.md, Injectivity); a boundary motion that drives one part of the boundary
/// through another leaves every cell positive and the mesh folded over itself.
struct BoundaryCrossings {
  std::size_t count = 0;                  ///< crossing pairs of boundary pieces
  std::array<std::int32_t, 2> first{-1, -1};  ///< the Topology facets of the first pair found
};

/// Pairs of boundary pieces that cross: segments in 2D, triangles in 3D, the pieces of a
/// curved facet (or of a bilinear quadrilateral, halved across a diagonal) those of the
/// polygon through its nodes. Only proper crossings count — pieces that share a node, or that
/// merely touch or lie on top of each other (the two sides of a slit), do not. Candidates come
/// from a uniform grid of the pieces' boxes; the result does not depend on the thread count.
BoundaryCrossings boundary_crossings(const Mesh& mesh, const Topology& topology);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshmorph/mesh/mesh.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// A mesh after pillow(), and where its cells come from.
struct Pillowed {
  Mesh mesh;
  /// Per cell of `mesh` (global order): the input cell it is, or, for an added cell, the
  /// input cell whose facet it lines.
  std::vector<std::int32_t> source;
  /// Per cell: the local facet that lies on the surface for an added cell, −1 for the
  /// input's cells.
  std::vector<std::int32_t> surface_facet;
  std::size_t added = 0;  ///< cells added
};

/// Pillowing: one layer of cells along a surface of facets, on one side of it. `marked`
/// holds, per cell (global order), one flag per local facet for the cells of the side that
/// gets the layer, nothing for the others; the flagged facets are the surface. Every corner
/// node of a flagged facet is duplicated for the cells of that side around it (once per
/// group of them joined through facets that hold the node), the copy moved by `depth` of
/// the way towards the mean centroid of its group (along the mesh boundary where the node
/// lies on an unflagged boundary facet); each flagged facet gets a new cell between its
/// nodes and their copies, appended to its cell's block with its tags. The facets of the
/// surface end up in the new cells, one in each, and no cell of the side keeps a node of
/// the surface: no cell of that side has two facets on it. Neighbours stay conforming,
/// the mesh covers the same region. Boundary facet elements follow their cells; new nodes
/// copy the tags (numbered after the largest) and field values of the nodes they copy.
///
/// Only linear quadrilaterals and hexahedra can carry flags (the new cells are of their
/// type); raise the order afterwards. Throws std::invalid_argument otherwise, and where the
/// surface has saddle nodes (pillow_saddles).
Pillowed pillow(const Mesh& mesh, const Topology& topology, const std::vector<std::vector<std::uint8_t>>& marked,
                double depth = 0.5);

/// The surface nodes (sorted) where pillow() would fold a new cell: a copy's move (towards
/// its group's centroid) makes an angle of more than about 78° with the inward normal of a
/// flagged facet of the group at the node, as where the side's cells around a node lie in
/// opposite octants. Giving every cell around such a node to the side removes it from the
/// surface.
std::vector<std::int32_t> pillow_saddles(const Mesh& mesh, const Topology& topology,
                                         const std::vector<std::vector<std::uint8_t>>& marked);

}  // namespace meshmorph

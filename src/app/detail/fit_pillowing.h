// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshmorph/mesh/mesh.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph::detail {

/// For each cell whose flag is `side`: one flag per local facet, set where the neighbour
/// has the other flag (the boundary is not flagged); nothing for the other cells. The
/// `marked` argument of pillow() for that side.
std::vector<std::vector<std::uint8_t>> facets_of_side(const Topology& topology, const std::vector<std::uint8_t>& flags,
                                                      std::uint8_t side);

/// Whether some cell of `marked` has two or more flagged facets.
bool crowded(const std::vector<std::vector<std::uint8_t>>& marked);

/// Before pillowing (docs/fit.md, Pillowing): every cell around a saddle node of the side's
/// surface (pillow_saddles) takes the side's flag, until none is left (at most 100 rounds).
/// Returns the number of cells that changed.
std::size_t fill_saddles(const Mesh& mesh, const Topology& topology, std::vector<std::uint8_t>& flags, std::uint8_t side);

}  // namespace meshmorph::detail

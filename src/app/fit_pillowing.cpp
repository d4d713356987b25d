// SPDX-License-Identifier: MIT
#include "app/detail/fit_pillowing.h"

#include <algorithm>

#include "meshmorph/mesh/pillow.h"

namespace meshmorph::detail {

std::vector<std::vector<std::uint8_t>> facets_of_side(const Topology& topology, const std::vector<std::uint8_t>& flags,
                                                      std::uint8_t side) {
  std::vector<std::vector<std::uint8_t>> marked(flags.size());
  for (std::size_t k = 0; k < flags.size(); ++k) {
    if (flags[k] != side) continue;
    for (auto j = topology.cell_neighbor_offset[k]; j < topology.cell_neighbor_offset[k + 1]; ++j) {
      const std::int32_t other = topology.cell_neighbors[static_cast<std::size_t>(j)];
      marked[k].push_back(other >= 0 && flags[static_cast<std::size_t>(other)] != side);
    }
  }
  return marked;
}

bool crowded(const std::vector<std::vector<std::uint8_t>>& marked) {
  return std::ranges::any_of(marked, [](const std::vector<std::uint8_t>& m) { return std::ranges::count(m, 1) >= 2; });
}

std::size_t fill_saddles(const Mesh& mesh, const Topology& topology, std::vector<std::uint8_t>& flags, std::uint8_t side) {
  std::size_t filled = 0;
  for (int round = 0; round < 100; ++round) {
    const std::vector<std::int32_t> saddles = pillow_saddles(mesh, topology, facets_of_side(topology, flags, side));
    if (saddles.empty()) break;
    for (std::int32_t v : saddles)
      for (std::int32_t k : topology.cells_of(static_cast<std::size_t>(v)))
        if (flags[static_cast<std::size_t>(k)] != side) {
          flags[static_cast<std::size_t>(k)] = side;
          ++filled;
        }
  }
  return filled;
}

}  // namespace meshmorph::detail

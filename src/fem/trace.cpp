// SPDX-License-Identifier: MIT
#include "meshmorph/fem/trace.h"

#include <algorithm>

#include "meshmorph/fem/reference_element.h"

namespace meshmorph {

std::vector<std::int32_t> facet_nodes(const CellBlock& block, std::size_t cell, int local) {
  const auto& table = reference_element(block.type, block.order).facet_nodes[static_cast<std::size_t>(local)];
  std::vector<std::int32_t> out(table.size());
  const auto* v = block.cell(cell);
  for (std::size_t i = 0; i < table.size(); ++i) out[i] = v[table[i]];
  return out;
}

std::vector<std::int32_t> boundary_nodes(const Mesh& mesh, const Topology& topology) {
  std::vector<std::int32_t> out;
  for (auto f : topology.boundary_facets) {
    const auto& where = topology.facets[static_cast<std::size_t>(f)][0];
    const auto [b, c] = topology.locate(where.cell);
    const auto nodes = facet_nodes(mesh.cells[b], c, where.local);
    out.insert(out.end(), nodes.begin(), nodes.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace meshmorph

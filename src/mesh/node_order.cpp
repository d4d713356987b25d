// SPDX-License-Identifier: MIT
#include "meshmorph/mesh/node_order.h"

#include <algorithm>
#include <numeric>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

// Breadth-first search from `root` over the nodes not yet stamped with `stamp`, neighbours
// taken in increasing degree (cells around them), then index: the Cuthill–McKee order.
// Appends the nodes reached to `out`.
void search(const Topology& t, std::int32_t root, int stamp, std::vector<int>& stamps, std::vector<std::int32_t>& out) {
  const auto degree = [&](std::int32_t v) { return t.node_cell_offset[v + 1] - t.node_cell_offset[v]; };
  std::size_t head = out.size();
  out.push_back(root);
  stamps[root] = stamp;
  std::vector<std::int32_t> around;
  while (head < out.size()) {
    const std::int32_t v = out[head++];
    around.clear();
    for (std::int64_t k = t.node_node_offset[v]; k < t.node_node_offset[v + 1]; ++k) {
      const std::int32_t u = t.node_nodes[k];
      if (stamps[u] != stamp) {
        stamps[u] = stamp;
        around.push_back(u);
      }
    }
    std::sort(around.begin(), around.end(),
              [&](std::int32_t a, std::int32_t b) { return degree(a) != degree(b) ? degree(a) < degree(b) : a < b; });
    out.insert(out.end(), around.begin(), around.end());
  }
}

}  // namespace

std::vector<std::int32_t> locality_order(const Topology& topology) {
  MESHMORPH_CHECK(!topology.node_node_offset.empty(), "locality_order: the topology has no node neighbours");
  const std::size_t n = topology.node_node_offset.size() - 1;
  std::vector<int> stamps(n, 0);
  std::vector<std::int32_t> order, probe;
  order.reserve(n);
  int stamp = 0;
  for (std::size_t v = 0; v < n; ++v) {
    if (stamps[v] != 0) continue;
    // A first search finds a node far from v (the last it reaches); the order starts there.
    // Its stamps are negative so that the nodes stay unplaced.
    probe.clear();
    search(topology, static_cast<std::int32_t>(v), --stamp, stamps, probe);
    const std::size_t placed = order.size();
    search(topology, probe.back(), 1, stamps, order);
    // The nodes that the first search stamped are exactly the ones the second reaches.
    MESHMORPH_CHECK(order.size() - placed == probe.size(), "locality_order: inconsistent searches");
  }
  std::reverse(order.begin(), order.end());
  return order;
}

Mesh renumber_nodes(const Mesh& mesh, std::span<const std::int32_t> order) {
  const std::size_t n = mesh.n_nodes();
  MESHMORPH_CHECK(order.size() == n, "renumber_nodes: the order does not list every node");
  std::vector<std::int32_t> new_index(n, -1);
  for (std::size_t k = 0; k < n; ++k) {
    MESHMORPH_CHECK(order[k] >= 0 && static_cast<std::size_t>(order[k]) < n && new_index[order[k]] < 0,
                    "renumber_nodes: the order is not a permutation");
    new_index[order[k]] = static_cast<std::int32_t>(k);
  }
  Mesh out;
  out.dim = mesh.dim;
  out.groups = mesh.groups;
  out.x.resize(mesh.x.rows(), static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k) out.x.col(static_cast<Eigen::Index>(k)) = mesh.x.col(order[k]);
  if (mesh.node_tags.size() == n) {
    out.node_tags.resize(n);
    for (std::size_t k = 0; k < n; ++k) out.node_tags[k] = mesh.node_tags[order[k]];
  }
  for (const auto& [name, field] : mesh.node_fields) {
    Eigen::VectorXd moved(static_cast<Eigen::Index>(n));
    for (std::size_t k = 0; k < n; ++k) moved[static_cast<Eigen::Index>(k)] = field[order[k]];
    out.node_fields.emplace(name, std::move(moved));
  }
  const auto renumbered = [&](const CellBlock& b, bool sort) {
    const int m = b.n_nodes_per_cell();
    std::vector<std::int32_t> key(b.n_cells());
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      key[c] = static_cast<std::int32_t>(n);
      for (int a = 0; a < m; ++a) key[c] = std::min(key[c], new_index[b.cell(c)[a]]);
    }
    std::vector<std::size_t> cells(b.n_cells());
    std::iota(cells.begin(), cells.end(), std::size_t{0});
    if (sort) std::stable_sort(cells.begin(), cells.end(), [&](std::size_t p, std::size_t q) { return key[p] < key[q]; });
    CellBlock r;
    r.type = b.type;
    r.order = b.order;
    r.nodes.reserve(b.nodes.size());
    for (std::size_t c : cells)
      for (int a = 0; a < m; ++a) r.nodes.push_back(new_index[b.cell(c)[a]]);
    if (b.physical.size() == b.n_cells())
      for (std::size_t c : cells) r.physical.push_back(b.physical[c]);
    if (b.entity.size() == b.n_cells())
      for (std::size_t c : cells) r.entity.push_back(b.entity[c]);
    return r;
  };
  for (const CellBlock& b : mesh.cells) out.cells.push_back(renumbered(b, true));
  for (const CellBlock& b : mesh.facets) out.facets.push_back(renumbered(b, false));
  return out;
}

}  // namespace meshmorph

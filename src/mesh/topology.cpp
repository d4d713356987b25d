// SPDX-License-Identifier: MIT
#include "meshmorph/mesh/topology.h"

#include <algorithm>
#include <string>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

const std::vector<std::vector<int>> k_point_facets{};
const std::vector<std::vector<int>> k_line_facets{{0}, {1}};
const std::vector<std::vector<int>> k_tri_facets{{0, 1}, {1, 2}, {2, 0}};
const std::vector<std::vector<int>> k_quad_facets{{0, 1}, {1, 2}, {2, 3}, {3, 0}};
const std::vector<std::vector<int>> k_tet_facets{{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}};
const std::vector<std::vector<int>> k_hex_facets{{0, 3, 2, 1}, {0, 1, 5, 4}, {0, 4, 7, 3},
                                                 {1, 2, 6, 5}, {2, 3, 7, 6}, {4, 5, 6, 7}};
// Gmsh's face order (MPrism, MPyramid): the triangles first on a prism, last the base on a pyramid.
const std::vector<std::vector<int>> k_prism_facets{{0, 2, 1}, {3, 4, 5}, {0, 1, 4, 3}, {0, 3, 5, 2}, {1, 2, 5, 4}};
const std::vector<std::vector<int>> k_pyramid_facets{{0, 1, 4}, {3, 0, 4}, {1, 2, 4}, {2, 3, 4}, {0, 3, 2, 1}};

const std::vector<std::array<int, 2>> k_no_edges{};
const std::vector<std::array<int, 2>> k_line_edges{{0, 1}};
const std::vector<std::array<int, 2>> k_tri_edges{{0, 1}, {1, 2}, {2, 0}};
const std::vector<std::array<int, 2>> k_quad_edges{{0, 1}, {1, 2}, {2, 3}, {3, 0}};
const std::vector<std::array<int, 2>> k_tet_edges{{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
const std::vector<std::array<int, 2>> k_hex_edges{{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 5}, {2, 3},
                                                  {2, 6}, {3, 7}, {4, 5}, {4, 7}, {5, 6}, {6, 7}};
const std::vector<std::array<int, 2>> k_prism_edges{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 4}, {2, 5}, {3, 4}, {3, 5}, {4, 5}};
const std::vector<std::array<int, 2>> k_pyramid_edges{{0, 1}, {0, 3}, {0, 4}, {1, 2}, {1, 4}, {2, 3}, {2, 4}, {3, 4}};

// A facet identified by its sorted corner nodes (−1 pads 2- and 3-corner facets).
struct FacetKey {
  std::array<std::int32_t, 4> corners;
  CellFacet where;
};

// A node as the user knows it: its file tag, else its 1-based number.
std::string node_label(const Mesh& mesh, std::int32_t node) {
  const auto i = static_cast<std::size_t>(node);
  return std::to_string(i < mesh.node_tags.size() ? mesh.node_tags[i] : static_cast<std::int64_t>(node) + 1);
}

template <class Csr>
void prefix_sum(Csr& offsets) {
  for (std::size_t i = 1; i < offsets.size(); ++i) offsets[i] += offsets[i - 1];
}

}  // namespace

std::span<const std::vector<int>> corner_facets(ElementType t) {
  switch (t) {
    case ElementType::Point: return k_point_facets;
    case ElementType::Line: return k_line_facets;
    case ElementType::Triangle: return k_tri_facets;
    case ElementType::Quadrilateral: return k_quad_facets;
    case ElementType::Tetrahedron: return k_tet_facets;
    case ElementType::Hexahedron: return k_hex_facets;
    case ElementType::Prism: return k_prism_facets;
    case ElementType::Pyramid: return k_pyramid_facets;
  }
  return k_point_facets;
}

std::span<const std::array<int, 2>> corner_edges(ElementType t) {
  switch (t) {
    case ElementType::Point: return k_no_edges;
    case ElementType::Line: return k_line_edges;
    case ElementType::Triangle: return k_tri_edges;
    case ElementType::Quadrilateral: return k_quad_edges;
    case ElementType::Tetrahedron: return k_tet_edges;
    case ElementType::Hexahedron: return k_hex_edges;
    case ElementType::Prism: return k_prism_edges;
    case ElementType::Pyramid: return k_pyramid_edges;
  }
  return k_no_edges;
}

ElementType facet_type(ElementType t, int f) {
  switch (t) {
    case ElementType::Triangle:
    case ElementType::Quadrilateral: return ElementType::Line;
    case ElementType::Tetrahedron: return ElementType::Triangle;
    case ElementType::Hexahedron: return ElementType::Quadrilateral;
    case ElementType::Prism: return f < 2 ? ElementType::Triangle : ElementType::Quadrilateral;
    case ElementType::Pyramid: return f < 4 ? ElementType::Triangle : ElementType::Quadrilateral;
    default: return ElementType::Point;
  }
}

std::pair<std::size_t, std::size_t> Topology::locate(std::int32_t cell) const {
  const auto it = std::upper_bound(block_offset.begin(), block_offset.end(), static_cast<std::size_t>(cell));
  const auto b = static_cast<std::size_t>(it - block_offset.begin()) - 1;
  return {b, static_cast<std::size_t>(cell) - block_offset[b]};
}

Topology build_topology(const Mesh& mesh, TopologyParts parts) {
  Topology topo;
  const auto n_nodes = mesh.n_nodes();
  topo.block_offset.push_back(0);
  for (const auto& b : mesh.cells) topo.block_offset.push_back(topo.block_offset.back() + b.n_cells());
  const auto n_cells = topo.block_offset.back();

  // Facets and edges by sorting corner keys: O(n log n) with no hash tables.
  // Both lists are reserved at their final length: grown by doubling, they would peak at up
  // to three times it while reallocating (1.2 GB for the keys of 6M tetrahedra).
  std::vector<FacetKey> keys;
  std::vector<std::array<std::int32_t, 2>> edges;
  std::size_t n_keys = 0, n_edges = 0;
  for (const auto& b : mesh.cells) {
    n_keys += b.n_cells() * corner_facets(b.type).size();
    if (parts == TopologyParts::All) n_edges += b.n_cells() * corner_edges(b.type).size();
  }
  keys.reserve(n_keys);
  edges.reserve(n_edges);
  topo.cell_neighbor_offset.assign(n_cells + 1, 0);
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    const auto& b = mesh.cells[bi];
    const auto facets = corner_facets(b.type);
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      const auto* v = b.cell(c);
      const auto gc = static_cast<std::int32_t>(topo.block_offset[bi] + c);
      topo.cell_neighbor_offset[static_cast<std::size_t>(gc) + 1] = static_cast<std::int64_t>(facets.size());
      for (std::size_t f = 0; f < facets.size(); ++f) {
        FacetKey k{{-1, -1, -1, -1}, {gc, static_cast<std::int32_t>(f)}};
        // Insertion into sorted order (at most four corners; std::sort on the first m of four
        // draws GCC 12's false -Warray-bounds).
        for (std::size_t i = 0; i < facets[f].size(); ++i) {
          std::size_t j = i;
          const std::int32_t corner = v[facets[f][i]];
          for (; j > 0 && k.corners[j - 1] > corner; --j) k.corners[j] = k.corners[j - 1];
          k.corners[j] = corner;
        }
        keys.push_back(k);
      }
      if (parts == TopologyParts::All)
        for (const auto& e : corner_edges(b.type)) edges.push_back({std::min(v[e[0]], v[e[1]]), std::max(v[e[0]], v[e[1]])});
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  edges.shrink_to_fit();  // each edge was listed by every cell around it (6 per tetrahedron)
  topo.edges = std::move(edges);

  std::sort(keys.begin(), keys.end(), [](const FacetKey& a, const FacetKey& b) {
    return a.corners != b.corners ? a.corners < b.corners : a.where.cell < b.where.cell;
  });
  prefix_sum(topo.cell_neighbor_offset);
  topo.cell_neighbors.assign(static_cast<std::size_t>(topo.cell_neighbor_offset.back()), -1);
  std::size_t n_facets = keys.empty() ? 0 : 1;
  for (std::size_t i = 1; i < keys.size(); ++i) n_facets += keys[i].corners != keys[i - 1].corners;
  topo.facets.reserve(n_facets);
  std::vector<std::int32_t> corners;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i + 1;
    while (j < keys.size() && keys[j].corners == keys[i].corners) ++j;
    if (j - i > 2)
      throw InputError("mesh: the facet with corner nodes " + node_label(mesh, keys[i].corners[0]) + ", " +
                       node_label(mesh, keys[i].corners[1]) + ", ... is shared by " + std::to_string(j - i) +
                       " cells (a non-manifold mesh, or overlapping cells)");
    const auto a = keys[i].where;
    const auto b = j - i == 2 ? keys[i + 1].where : CellFacet{};
    if (b.cell >= 0) {
      topo.cell_neighbors[static_cast<std::size_t>(topo.cell_neighbor_offset[static_cast<std::size_t>(a.cell)] + a.local)] = b.cell;
      topo.cell_neighbors[static_cast<std::size_t>(topo.cell_neighbor_offset[static_cast<std::size_t>(b.cell)] + b.local)] = a.cell;
    } else {
      topo.boundary_facets.push_back(static_cast<std::int32_t>(topo.facets.size()));
      for (auto c : keys[i].corners)
        if (c >= 0) corners.push_back(c);
    }
    topo.facets.push_back({a, b});
    i = j;
  }
  std::sort(corners.begin(), corners.end());
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  topo.boundary_corners = std::move(corners);
  if (parts == TopologyParts::Facets) return topo;

  // node → cells
  topo.node_cell_offset.assign(n_nodes + 1, 0);
  for (const auto& b : mesh.cells)
    for (auto v : b.nodes) ++topo.node_cell_offset[static_cast<std::size_t>(v) + 1];
  prefix_sum(topo.node_cell_offset);
  topo.node_cells.resize(static_cast<std::size_t>(topo.node_cell_offset.back()));
  {
    std::vector<std::int64_t> fill(topo.node_cell_offset.begin(), topo.node_cell_offset.end() - 1);
    for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
      const auto& b = mesh.cells[bi];
      const int n = b.n_nodes_per_cell();
      for (std::size_t c = 0; c < b.n_cells(); ++c)
        for (int a = 0; a < n; ++a) {
          const auto v = static_cast<std::size_t>(b.cell(c)[a]);
          topo.node_cells[static_cast<std::size_t>(fill[v]++)] = static_cast<std::int32_t>(topo.block_offset[bi] + c);
        }
    }
  }

  // node → nodes: union of the nodes of the cells around each node. Rows go into one flat
  // buffer per chunk of nodes, not one vector per node: a million nodes' vectors, each with
  // room for the duplicates of every cell around the node, would take several times the result.
  constexpr std::size_t k_chunk = 4096;
  const std::size_t n_chunks = (n_nodes + k_chunk - 1) / k_chunk;
  std::vector<std::vector<std::int32_t>> chunks(n_chunks);
  topo.node_node_offset.assign(n_nodes + 1, 0);
#pragma omp parallel
  {
    std::vector<std::int32_t> row;
#pragma omp for schedule(dynamic)
    for (std::int64_t k = 0; k < static_cast<std::int64_t>(n_chunks); ++k) {
      auto& out = chunks[static_cast<std::size_t>(k)];
      const std::size_t first = static_cast<std::size_t>(k) * k_chunk;
      for (std::size_t i = first; i < std::min(n_nodes, first + k_chunk); ++i) {
        row.assign(1, static_cast<std::int32_t>(i));
        for (auto c = topo.node_cell_offset[i]; c < topo.node_cell_offset[i + 1]; ++c) {
          const auto [bi, cell] = topo.locate(topo.node_cells[static_cast<std::size_t>(c)]);
          const auto& b = mesh.cells[bi];
          row.insert(row.end(), b.cell(cell), b.cell(cell) + b.n_nodes_per_cell());
        }
        std::sort(row.begin(), row.end());
        row.erase(std::unique(row.begin(), row.end()), row.end());
        out.insert(out.end(), row.begin(), row.end());
        topo.node_node_offset[i + 1] = static_cast<std::int64_t>(row.size());
      }
    }
  }
  prefix_sum(topo.node_node_offset);
  topo.node_nodes.reserve(static_cast<std::size_t>(topo.node_node_offset.back()));
  for (auto& out : chunks) {
    topo.node_nodes.insert(topo.node_nodes.end(), out.begin(), out.end());
    std::vector<std::int32_t>().swap(out);
  }
  return topo;
}

}  // namespace meshmorph

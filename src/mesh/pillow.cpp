// SPDX-License-Identifier: MIT
#include "meshmorph/mesh/pillow.h"

#include <algorithm>
#include <map>
#include <numeric>
#include <stdexcept>

#include <Eigen/Geometry>

namespace meshmorph {
namespace {

constexpr int kMaxCorners = 8;
// The least cosine between a copy's move and the inward normal of a flagged facet at its
// node: 1 on a flat surface, 1/sqrt(3) at a convex corner of a staircase.
constexpr double kMinCosine = 0.2;

// The local facet of a cell family whose corners are exactly `corners` (any order).
int facet_with_corners(ElementType type, std::vector<int> corners) {
  std::ranges::sort(corners);
  const std::span<const std::vector<int>> facets = corner_facets(type);
  for (std::size_t f = 0; f < facets.size(); ++f) {
    std::vector<int> c = facets[f];
    std::ranges::sort(c);
    if (c == corners) return static_cast<int>(f);
  }
  throw std::logic_error("pillow: no facet with these corners");
}

struct AddedCell {
  std::vector<std::int32_t> nodes;
  std::int32_t physical = 0, entity = 0, source = 0;
};

// The unit normal of local facet `f` of a linear quadrilateral / hexahedron (corners v),
// towards the cell.
Eigen::VectorXd inward_normal(const Mesh& mesh, ElementType type, const std::int32_t* v, const std::vector<int>& f) {
  Eigen::VectorXd n(mesh.dim), centre = Eigen::VectorXd::Zero(mesh.dim), cell = centre;
  for (int a : f) centre += mesh.x.col(v[a]) / static_cast<double>(f.size());
  for (int a = 0; a < n_corners_of(type); ++a) cell += mesh.x.col(v[a]) / n_corners_of(type);
  if (mesh.dim == 2) {
    const Eigen::Vector2d e = mesh.x.col(v[f[1]]) - mesh.x.col(v[f[0]]);
    n = Eigen::Vector2d(-e.y(), e.x());
  } else {
    const Eigen::Vector3d d1 = mesh.x.col(v[f[2]]) - mesh.x.col(v[f[0]]), d2 = mesh.x.col(v[f[3]]) - mesh.x.col(v[f[1]]);
    n = d1.cross(d2);
  }
  if (n.dot(cell - centre) < 0.0) n = -n;
  return n.normalized();
}

// pillow(), or with `plan_only` the saddles alone (nothing built).
Pillowed build(const Mesh& mesh, const Topology& topology, const std::vector<std::vector<std::uint8_t>>& marked,
               double depth, std::vector<std::int32_t>& saddles, bool plan_only) {
  const std::size_t n_cells = mesh.n_cells();
  if (marked.size() != n_cells) throw std::invalid_argument("pillow: one list of facet flags per cell");
  const auto cell_of = [&](std::int32_t c) {
    const auto [b, k] = topology.locate(c);
    return std::pair<const CellBlock&, const std::int32_t*>(mesh.cells[b], mesh.cells[b].cell(k));
  };
  const auto neighbor = [&](std::int32_t c, int f) {
    return topology.cell_neighbors[static_cast<std::size_t>(topology.cell_neighbor_offset[static_cast<std::size_t>(c)] + f)];
  };
  const auto flagged = [&](std::int32_t c, int f) {
    const std::vector<std::uint8_t>& m = marked[static_cast<std::size_t>(c)];
    return static_cast<std::size_t>(f) < m.size() && m[static_cast<std::size_t>(f)] != 0;
  };
  std::vector<std::uint8_t> side(n_cells, 0), on_surface(mesh.n_nodes(), 0);
  for (std::size_t c = 0; c < n_cells; ++c) {
    if (marked[c].empty()) continue;
    side[c] = 1;
    if (std::ranges::none_of(marked[c], [](std::uint8_t m) { return m != 0; })) continue;
    const auto [block, v] = cell_of(static_cast<std::int32_t>(c));
    if (block.order != 1 || (block.type != ElementType::Quadrilateral && block.type != ElementType::Hexahedron))
      throw std::invalid_argument("pillow: only linear quadrilaterals and hexahedra can be pillowed");
    const std::span<const std::vector<int>> facets = corner_facets(block.type);
    for (std::size_t f = 0; f < facets.size(); ++f)
      if (flagged(static_cast<std::int32_t>(c), static_cast<int>(f)))
        for (int a : facets[f]) on_surface[static_cast<std::size_t>(v[a])] = 1;
  }

  // The copy of each surface node for each cell of the side that holds it.
  std::vector<std::int32_t> copy(n_cells * kMaxCorners, -1);
  std::vector<Eigen::VectorXd> new_x;
  std::vector<std::int32_t> copied;  // the node each new node copies
  const auto local_index = [&](std::int32_t c, std::int32_t node) {
    const auto [block, v] = cell_of(c);
    return static_cast<int>(std::find(v, v + n_corners_of(block.type), node) - v);
  };
  const auto centroid = [&](const std::int32_t* v, std::span<const int> locals) {
    Eigen::VectorXd m = Eigen::VectorXd::Zero(mesh.dim);
    for (int a : locals) m += mesh.x.col(v[a]);
    return Eigen::VectorXd(m / static_cast<double>(locals.size()));
  };
  for (std::size_t node = 0; node < mesh.n_nodes(); ++node) {
    if (!on_surface[node]) continue;
    std::vector<std::int32_t> cells;
    for (std::int32_t c : topology.cells_of(node))
      if (side[static_cast<std::size_t>(c)]) cells.push_back(c);
    std::vector<std::size_t> root(cells.size());
    std::iota(root.begin(), root.end(), 0);
    const auto find = [&](std::size_t i) {
      while (root[i] != i) i = root[i] = root[root[i]];
      return i;
    };
    std::vector<std::uint8_t> touches(cells.size(), 0);  // a flagged facet of the cell holds the node
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const auto [block, v] = cell_of(cells[i]);
      const int a = local_index(cells[i], static_cast<std::int32_t>(node));
      const std::span<const std::vector<int>> facets = corner_facets(block.type);
      for (std::size_t f = 0; f < facets.size(); ++f) {
        if (!std::ranges::count(facets[f], a)) continue;
        if (flagged(cells[i], static_cast<int>(f))) touches[i] = 1;
        const std::int32_t other = neighbor(cells[i], static_cast<int>(f));
        if (other < 0 || flagged(cells[i], static_cast<int>(f))) continue;
        if (const auto j = std::ranges::find(cells, other) - cells.begin(); j < static_cast<std::ptrdiff_t>(cells.size()))
          root[find(i)] = find(static_cast<std::size_t>(j));
      }
    }
    for (std::size_t r = 0; r < cells.size(); ++r) {
      if (find(r) != r) continue;
      bool any = false;
      for (std::size_t i = 0; i < cells.size(); ++i) any = any || (find(i) == r && touches[i]);
      if (!any) continue;
      // Towards the group's cells, or along the boundary where the node lies on it.
      Eigen::VectorXd inner = Eigen::VectorXd::Zero(mesh.dim), along = inner;
      int n_inner = 0, n_along = 0;
      for (std::size_t i = 0; i < cells.size(); ++i) {
        if (find(i) != r) continue;
        const auto [block, v] = cell_of(cells[i]);
        std::vector<int> all(static_cast<std::size_t>(n_corners_of(block.type)));
        std::iota(all.begin(), all.end(), 0);
        inner += centroid(v, all);
        ++n_inner;
        const int a = local_index(cells[i], static_cast<std::int32_t>(node));
        const std::span<const std::vector<int>> facets = corner_facets(block.type);
        for (std::size_t f = 0; f < facets.size(); ++f)
          if (std::ranges::count(facets[f], a) && neighbor(cells[i], static_cast<int>(f)) < 0 &&
              !flagged(cells[i], static_cast<int>(f))) {
            along += centroid(v, facets[f]);
            ++n_along;
          }
      }
      const Eigen::VectorXd x = mesh.x.col(static_cast<Eigen::Index>(node));
      const Eigen::VectorXd towards = n_along > 0 ? Eigen::VectorXd(along / n_along) : Eigen::VectorXd(inner / n_inner);
      // The copy must move into the side across every flagged facet at the node, or a new
      // cell folds (a saddle: the side's cells around it lie on opposite sides of it).
      bool folds = (towards - x).norm() == 0.0;
      for (std::size_t i = 0; i < cells.size() && !folds; ++i) {
        if (find(i) != r) continue;
        const auto [block, v] = cell_of(cells[i]);
        const int a = local_index(cells[i], static_cast<std::int32_t>(node));
        const std::span<const std::vector<int>> facets = corner_facets(block.type);
        for (std::size_t f = 0; f < facets.size() && !folds; ++f)
          if (std::ranges::count(facets[f], a) && flagged(cells[i], static_cast<int>(f)))
            folds = inward_normal(mesh, block.type, v, facets[f]).dot(towards - x) <= kMinCosine * (towards - x).norm();
      }
      if (folds) saddles.push_back(static_cast<std::int32_t>(node));
      if (plan_only) continue;
      const auto index = static_cast<std::int32_t>(mesh.n_nodes() + new_x.size());
      new_x.push_back(x + depth * (towards - x));
      copied.push_back(static_cast<std::int32_t>(node));
      for (std::size_t i = 0; i < cells.size(); ++i)
        if (find(i) == r)
          copy[static_cast<std::size_t>(cells[i]) * kMaxCorners + static_cast<std::size_t>(local_index(cells[i], static_cast<std::int32_t>(node)))] = index;
    }
  }
  if (plan_only) return {};
  const auto position = [&](std::int32_t node) {
    return node < static_cast<std::int32_t>(mesh.n_nodes()) ? Eigen::VectorXd(mesh.x.col(node))
                                                             : new_x[static_cast<std::size_t>(node) - mesh.n_nodes()];
  };

  // The new cells (one per flagged facet, between its nodes and their copies), per block.
  Pillowed out;
  out.mesh = mesh;
  std::vector<std::vector<AddedCell>> added(mesh.cells.size());
  std::map<std::vector<std::int32_t>, std::int32_t> boundary_facet_cell;  // sorted corners → its side cell
  for (std::size_t c = 0; c < n_cells; ++c) {
    if (!side[c]) continue;
    const auto gc = static_cast<std::int32_t>(c);
    const auto [b, k] = topology.locate(gc);
    const CellBlock& block = mesh.cells[b];
    const std::int32_t* v = block.cell(k);
    const std::span<const std::vector<int>> facets = corner_facets(block.type);
    for (std::size_t f = 0; f < facets.size(); ++f) {
      const std::vector<int>& fa = facets[f];
      if (!flagged(gc, static_cast<int>(f))) {
        if (neighbor(gc, static_cast<int>(f)) < 0) {
          std::vector<std::int32_t> key;
          for (int a : fa) key.push_back(v[a]);
          std::ranges::sort(key);
          boundary_facet_cell[key] = gc;
        }
        continue;
      }
      std::vector<std::int32_t> o, n;
      Eigen::VectorXd shift = Eigen::VectorXd::Zero(mesh.dim);
      for (int a : fa) {
        o.push_back(v[a]);
        n.push_back(copy[c * kMaxCorners + static_cast<std::size_t>(a)]);
        shift += position(n.back()) - position(o.back());
      }
      AddedCell cell{{}, block.physical.empty() ? 0 : block.physical[k], block.entity.empty() ? 0 : block.entity[k], gc};
      if (block.type == ElementType::Hexahedron) {
        const Eigen::Vector3d e1 = position(o[1]) - position(o[0]), e3 = position(o[3]) - position(o[0]);
        if (e1.cross(e3).dot(Eigen::Vector3d(shift)) > 0.0) cell.nodes = {o[0], o[1], o[2], o[3], n[0], n[1], n[2], n[3]};
        else cell.nodes = {o[0], o[3], o[2], o[1], n[0], n[3], n[2], n[1]};
      } else {
        const Eigen::Vector2d e = position(o[1]) - position(o[0]);
        if (e.x() * shift.y() - e.y() * shift.x() > 0.0) cell.nodes = {o[0], o[1], n[1], n[0]};
        else cell.nodes = {o[1], o[0], n[0], n[1]};
      }
      added[b].push_back(std::move(cell));
    }
    std::int32_t* w = out.mesh.cells[b].cell(k);
    for (int a = 0; a < n_corners_of(block.type); ++a)
      if (const std::int32_t to = copy[c * kMaxCorners + static_cast<std::size_t>(a)]; to >= 0) w[a] = to;
  }

  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    CellBlock& block = out.mesh.cells[b];
    for (std::size_t k = 0; k < mesh.cells[b].n_cells(); ++k) {
      out.source.push_back(static_cast<std::int32_t>(topology.block_offset[b] + k));
      out.surface_facet.push_back(-1);
    }
    const int surface = added[b].empty() ? -1
                                         : facet_with_corners(block.type, block.type == ElementType::Hexahedron
                                                                              ? std::vector<int>{0, 1, 2, 3}
                                                                              : std::vector<int>{0, 1});
    for (const AddedCell& cell : added[b]) {
      block.push_back(cell.nodes.data(), cell.physical, cell.entity);
      out.source.push_back(cell.source);
      out.surface_facet.push_back(surface);
      ++out.added;
    }
  }
  // Boundary facet elements of the side's cells take the cells' copies.
  for (CellBlock& facets : out.mesh.facets)
    for (std::size_t k = 0; k < facets.n_cells(); ++k) {
      std::int32_t* v = facets.cell(k);
      std::vector<std::int32_t> key(v, v + facets.n_nodes_per_cell());
      std::ranges::sort(key);
      const auto it = boundary_facet_cell.find(key);
      if (it == boundary_facet_cell.end()) continue;
      for (int a = 0; a < facets.n_nodes_per_cell(); ++a)
        if (const std::int32_t to = copy[static_cast<std::size_t>(it->second) * kMaxCorners +
                                         static_cast<std::size_t>(local_index(it->second, v[a]))];
            to >= 0)
          v[a] = to;
    }

  const auto n_old = static_cast<Eigen::Index>(mesh.n_nodes()), n_new = static_cast<Eigen::Index>(new_x.size());
  out.mesh.x.conservativeResize(Eigen::NoChange, n_old + n_new);
  std::int64_t next_tag = mesh.node_tags.empty() ? 0 : *std::ranges::max_element(mesh.node_tags);
  for (auto& [name, field] : out.mesh.node_fields) field.conservativeResize(n_old + n_new);
  for (Eigen::Index i = 0; i < n_new; ++i) {
    const std::int32_t from = copied[static_cast<std::size_t>(i)];
    out.mesh.x.col(n_old + i) = new_x[static_cast<std::size_t>(i)];
    if (!mesh.node_tags.empty()) out.mesh.node_tags.push_back(++next_tag);
    for (auto& [name, field] : out.mesh.node_fields) field[n_old + i] = field[from];
  }
  return out;
}

}  // namespace

Pillowed pillow(const Mesh& mesh, const Topology& topology, const std::vector<std::vector<std::uint8_t>>& marked,
                double depth) {
  std::vector<std::int32_t> saddles;
  Pillowed out = build(mesh, topology, marked, depth, saddles, false);
  if (!saddles.empty())
    throw std::invalid_argument("pillow: the layer would fold at " + std::to_string(saddles.size()) +
                                " saddle nodes of the surface (pillow_saddles)");
  return out;
}

std::vector<std::int32_t> pillow_saddles(const Mesh& mesh, const Topology& topology,
                                         const std::vector<std::vector<std::uint8_t>>& marked) {
  std::vector<std::int32_t> saddles;
  build(mesh, topology, marked, 0.5, saddles, true);
  std::ranges::sort(saddles);
  saddles.erase(std::unique(saddles.begin(), saddles.end()), saddles.end());
  return saddles;
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
// Choosing the fitted nodes of paper 003 §3.2: material indicators (eq. 10), their
// two-pass correction (eq. 12), conforming splits, and the interface's nodes.
#include <algorithm>
#include <array>
#include <span>
#include <stdexcept>

#include <Eigen/LU>

#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/shape_table.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/geometry/closest_on_simplex.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/methods/fit.h"

namespace meshmorph {
namespace {

// A block of the same type and order without cells.
CellBlock empty_like(const CellBlock& block) {
  CellBlock b;
  b.type = block.type;
  b.order = block.order;
  return b;
}

// Whether reference point p lies on the segment [a, b] (a point when a = b).
bool on_segment(const Eigen::VectorXd& p, const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  const Eigen::Vector3d p3 = padded_3d(p);
  return (closest_on_segment(p3, padded_3d(a), padded_3d(b)) - p3).norm() < 1e-9;
}

}  // namespace

std::vector<std::uint8_t> material_indicators(const Mesh& mesh, const LevelSetFunction& sigma) {
  std::vector<std::uint8_t> eta;
  eta.reserve(mesh.n_cells());
  for (const CellBlock& block : mesh.cells) {
    const ShapeTable& table = shape_table(block.type, block.order, metric_quadrature_degree(block.type, block.order));
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    const int n = block.n_nodes_per_cell();
    std::vector<std::uint8_t> local(block.n_cells());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      Eigen::MatrixXd X(mesh.dim, n);
      for (int a = 0; a < n; ++a) X.col(a) = mesh.x.col(block.nodes[static_cast<std::size_t>(c) * n + a]);
      double integral = 0.0;
      for (int q = 0; q < table.n_points(); ++q)
        integral += table.weights[q] * std::abs((X * table.grad(q)).determinant()) * sigma.value(X * table.N.col(q));
      local[static_cast<std::size_t>(c)] = integral >= 0.0 ? 0 : 1;
    }
    eta.insert(eta.end(), local.begin(), local.end());
  }
  return eta;
}

std::vector<int> interface_facet_counts(const Topology& topology, const std::vector<std::uint8_t>& eta) {
  std::vector<int> count(eta.size(), 0);
  for (std::size_t c = 0; c < eta.size(); ++c)
    for (auto k = topology.cell_neighbor_offset[c]; k < topology.cell_neighbor_offset[c + 1]; ++k) {
      const std::int32_t other = topology.cell_neighbors[static_cast<std::size_t>(k)];
      if (other >= 0 && eta[static_cast<std::size_t>(other)] != eta[c]) ++count[c];
    }
  return count;
}

std::vector<std::uint8_t> correct_indicators(const Topology& topology, std::vector<std::uint8_t> eta,
                                             std::vector<std::int32_t>& to_split, bool reduce_crowding,
                                             bool vertex_stars) {
  const auto marked = [&](std::size_t c) {
    int m = 0;
    for (auto k = topology.cell_neighbor_offset[c]; k < topology.cell_neighbor_offset[c + 1]; ++k) {
      const std::int32_t other = topology.cell_neighbors[static_cast<std::size_t>(k)];
      if (other >= 0 && eta[static_cast<std::size_t>(other)] != eta[c]) ++m;
    }
    return m;
  };
  for (std::uint8_t pass : {std::uint8_t{0}, std::uint8_t{1}})
    for (std::size_t c = 0; c < eta.size(); ++c) {
      if (eta[c] != pass) continue;
      const auto facets = topology.cell_neighbor_offset[c + 1] - topology.cell_neighbor_offset[c];
      if (marked(c) == facets - 1 && facets > 2) eta[c] = static_cast<std::uint8_t>(1 - eta[c]);
    }
  // Ours, beyond eq. 12 (which cannot help a tetrahedron or hexahedron with two interface
  // facets of four or six): give a cell, or every cell around a vertex, one indicator when
  // that lowers the number of cells with two or more interface facets among them and their
  // neighbours; sweep until no change helps. The vertex stars reach what single flips cannot,
  // such as a whole cube of a mesh that splits cubes into tetrahedra.
  std::vector<std::uint32_t> stamp(eta.size(), 0);
  std::uint32_t round = 0;
  std::vector<std::int32_t> region;
  const auto crowded_near = [&](std::span<const std::int32_t> cells) {
    ++round;
    region.clear();
    const auto add = [&](std::int32_t c) {
      if (c >= 0 && stamp[static_cast<std::size_t>(c)] != round) {
        stamp[static_cast<std::size_t>(c)] = round;
        region.push_back(c);
      }
    };
    for (std::int32_t c : cells) {
      add(c);
      for (auto k = topology.cell_neighbor_offset[static_cast<std::size_t>(c)];
           k < topology.cell_neighbor_offset[static_cast<std::size_t>(c) + 1]; ++k)
        add(topology.cell_neighbors[static_cast<std::size_t>(k)]);
    }
    return std::ranges::count_if(region, [&](std::int32_t c) { return marked(static_cast<std::size_t>(c)) >= 2; });
  };
  std::vector<std::uint8_t> saved;
  const auto improves = [&](std::span<const std::int32_t> cells, std::uint8_t value) {
    if (std::ranges::all_of(cells, [&](std::int32_t c) { return eta[static_cast<std::size_t>(c)] == value; })) return false;
    const auto before = crowded_near(cells);
    saved.clear();
    for (std::int32_t c : cells) {
      saved.push_back(eta[static_cast<std::size_t>(c)]);
      eta[static_cast<std::size_t>(c)] = value;
    }
    if (crowded_near(cells) < before) return true;
    for (std::size_t i = 0; i < cells.size(); ++i) eta[static_cast<std::size_t>(cells[i])] = saved[i];
    return false;
  };
  const std::size_t n_nodes = topology.node_cell_offset.empty() ? 0 : topology.node_cell_offset.size() - 1;
  for (bool changed = reduce_crowding; changed;) {
    changed = false;
    for (std::size_t c = 0; c < eta.size(); ++c) {
      const auto cell = static_cast<std::int32_t>(c);
      if (marked(c) >= 2 && improves({&cell, 1}, static_cast<std::uint8_t>(1 - eta[c]))) changed = true;
    }
    for (std::size_t v = 0; v < n_nodes && vertex_stars && !changed; ++v) {
      const std::span<const std::int32_t> star = topology.cells_of(v);
      if (std::ranges::none_of(star, [&](std::int32_t c) { return marked(static_cast<std::size_t>(c)) >= 2; })) continue;
      changed = improves(star, 0) || improves(star, 1);
    }
  }
  to_split.clear();
  for (std::size_t c = 0; c < eta.size(); ++c)
    if (marked(c) >= 2) to_split.push_back(static_cast<std::int32_t>(c));
  return eta;
}

Mesh split_cells(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& cells,
                 std::vector<std::uint8_t>& eta) {
  std::vector<std::uint8_t> split(mesh.n_cells(), 0);
  for (std::int32_t c : cells) split[static_cast<std::size_t>(c)] = 1;
  Mesh out = mesh;
  out.cells.clear();
  CellBlock triangles;
  triangles.type = ElementType::Triangle;
  std::vector<std::uint8_t> eta_kept, eta_new;
  std::int64_t next_tag = mesh.node_tags.empty() ? static_cast<std::int64_t>(mesh.n_nodes())
                                                 : *std::max_element(mesh.node_tags.begin(), mesh.node_tags.end());
  std::size_t global = 0;
  for (const CellBlock& block : mesh.cells) {
    CellBlock kept = empty_like(block);
    for (std::size_t c = 0; c < block.n_cells(); ++c, ++global) {
      const std::int32_t* v = block.cell(c);
      const std::int32_t physical = block.physical.empty() ? 0 : block.physical[c];
      const std::int32_t entity = block.entity.empty() ? 0 : block.entity[c];
      if (!split[global]) {
        kept.push_back(v, physical, entity);
        eta_kept.push_back(eta[global]);
        continue;
      }
      if (block.order != 1 || (block.type != ElementType::Triangle && block.type != ElementType::Quadrilateral))
        throw std::invalid_argument("split_cells: only linear triangles and quadrilaterals can be split");
      const int n = block.n_nodes_per_cell();
      // The interface facets of this cell (local facet f joins corners f and f + 1).
      std::vector<int> marked;
      for (int f = 0; f < n; ++f) {
        const std::int32_t other = topology.cell_neighbors[static_cast<std::size_t>(topology.cell_neighbor_offset[global]) + f];
        if (other >= 0 && eta[static_cast<std::size_t>(other)] != eta[global]) marked.push_back(f);
      }
      const auto add = [&](std::int32_t a, std::int32_t b, std::int32_t e) {
        const std::int32_t t[3] = {a, b, e};
        triangles.push_back(t, physical, entity);
        eta_new.push_back(eta[global]);
      };
      if (n == 4 && marked.size() == 2 && (marked[1] - marked[0] == 1 || marked[1] - marked[0] == 3)) {
        // Facets (v−1, v) and (v, v+1) meet at corner v: the diagonal from v bisects it.
        const int vtx = marked[1] - marked[0] == 1 ? marked[1] : marked[0];
        add(v[vtx], v[(vtx + 1) % 4], v[(vtx + 2) % 4]);
        add(v[vtx], v[(vtx + 2) % 4], v[(vtx + 3) % 4]);
        continue;
      }
      Eigen::VectorXd centre = Eigen::VectorXd::Zero(mesh.dim);
      for (int a = 0; a < n; ++a) centre += mesh.x.col(v[a]);
      centre /= n;
      const auto p = static_cast<std::int32_t>(out.x.cols());
      out.x.conservativeResize(Eigen::NoChange, p + 1);
      out.x.col(p) = centre;
      if (!out.node_tags.empty()) out.node_tags.push_back(++next_tag);
      for (auto& [name, field] : out.node_fields) {  // the new node takes the mean, like its position
        double mean = 0.0;
        for (int a = 0; a < n; ++a) mean += field[v[a]];
        field.conservativeResize(p + 1);
        field[p] = mean / n;
      }
      for (int a = 0; a < n; ++a) add(v[a], v[(a + 1) % n], p);
    }
    if (kept.n_cells() > 0) out.cells.push_back(std::move(kept));
  }
  eta = eta_kept;
  if (triangles.n_cells() > 0) {
    // Appended to a linear triangle block when there is one, else as a block of their own.
    auto same = std::find_if(out.cells.begin(), out.cells.end(),
                             [](const CellBlock& b) { return b.type == ElementType::Triangle && b.order == 1; });
    if (same == out.cells.end()) {
      out.cells.push_back(triangles);
      eta.insert(eta.end(), eta_new.begin(), eta_new.end());
    } else {
      std::size_t before = 0;
      for (auto it = out.cells.begin(); it != same + 1; ++it) before += it->n_cells();
      same->nodes.insert(same->nodes.end(), triangles.nodes.begin(), triangles.nodes.end());
      same->physical.insert(same->physical.end(), triangles.physical.begin(), triangles.physical.end());
      same->entity.insert(same->entity.end(), triangles.entity.begin(), triangles.entity.end());
      eta.insert(eta.begin() + static_cast<std::ptrdiff_t>(before), eta_new.begin(), eta_new.end());
    }
  }
  return out;
}

Mesh trim_cells(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& eta,
                std::vector<std::vector<std::uint8_t>>& cut) {
  Mesh out;
  out.dim = mesh.dim;
  out.groups = mesh.groups;
  cut.clear();
  std::vector<std::int32_t> renumber(mesh.n_nodes(), -1);
  std::int32_t used = 0;
  std::size_t global = 0;
  for (const CellBlock& block : mesh.cells) {
    CellBlock kept = empty_like(block);
    for (std::size_t c = 0; c < block.n_cells(); ++c, ++global) {
      if (!eta[global]) continue;
      std::vector<std::int32_t> v(block.cell(c), block.cell(c) + block.n_nodes_per_cell());
      for (std::int32_t& node : v) {
        if (renumber[static_cast<std::size_t>(node)] < 0) renumber[static_cast<std::size_t>(node)] = used++;
        node = renumber[static_cast<std::size_t>(node)];
      }
      kept.push_back(v.data(), block.physical.empty() ? 0 : block.physical[c], block.entity.empty() ? 0 : block.entity[c]);
      std::vector<std::uint8_t> flags;
      for (auto k = topology.cell_neighbor_offset[global]; k < topology.cell_neighbor_offset[global + 1]; ++k) {
        const std::int32_t other = topology.cell_neighbors[static_cast<std::size_t>(k)];
        flags.push_back(other >= 0 && !eta[static_cast<std::size_t>(other)]);
      }
      cut.push_back(std::move(flags));
    }
    if (kept.n_cells() > 0) out.cells.push_back(std::move(kept));
  }
  for (const CellBlock& block : mesh.facets) {
    CellBlock kept = empty_like(block);
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      std::vector<std::int32_t> v(block.cell(c), block.cell(c) + block.n_nodes_per_cell());
      if (std::any_of(v.begin(), v.end(), [&](std::int32_t node) { return renumber[static_cast<std::size_t>(node)] < 0; }))
        continue;
      for (std::int32_t& node : v) node = renumber[static_cast<std::size_t>(node)];
      kept.push_back(v.data(), block.physical.empty() ? 0 : block.physical[c], block.entity.empty() ? 0 : block.entity[c]);
    }
    if (kept.n_cells() > 0) out.facets.push_back(std::move(kept));
  }
  out.x.resize(mesh.dim, used);
  if (!mesh.node_tags.empty()) out.node_tags.resize(static_cast<std::size_t>(used));
  for (auto& [name, values] : mesh.node_fields) out.node_fields[name].resize(used);
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    const std::int32_t j = renumber[i];
    if (j < 0) continue;
    out.x.col(j) = mesh.x.col(static_cast<Eigen::Index>(i));
    if (!mesh.node_tags.empty()) out.node_tags[static_cast<std::size_t>(j)] = mesh.node_tags[i];
    for (auto& [name, values] : mesh.node_fields) out.node_fields[name][j] = values[static_cast<Eigen::Index>(i)];
  }
  return out;
}

std::vector<std::vector<std::int32_t>> cut_facets(const Mesh& mesh, const std::vector<std::vector<std::uint8_t>>& cut) {
  std::vector<std::vector<std::int32_t>> facets;
  std::size_t global = 0;
  for (const CellBlock& block : mesh.cells)
    for (std::size_t c = 0; c < block.n_cells(); ++c, ++global)
      for (std::size_t f = 0; f < cut[global].size(); ++f)
        if (cut[global][f]) facets.push_back(facet_nodes(block, c, static_cast<int>(f)));
  return facets;
}

std::vector<std::vector<std::int32_t>> interface_facets(const Mesh& mesh, const Topology& topology,
                                                        const std::vector<std::uint8_t>& eta) {
  std::vector<std::vector<std::int32_t>> facets;
  for (const auto& f : topology.facets) {
    if (f[1].cell < 0 || eta[static_cast<std::size_t>(f[0].cell)] == eta[static_cast<std::size_t>(f[1].cell)]) continue;
    const auto [b, c] = topology.locate(f[0].cell);
    facets.push_back(facet_nodes(mesh.cells[b], c, f[0].local));
  }
  return facets;
}

std::vector<std::int32_t> facets_nodes(const std::vector<std::vector<std::int32_t>>& facets) {
  std::vector<std::int32_t> nodes;
  for (const std::vector<std::int32_t>& on : facets) nodes.insert(nodes.end(), on.begin(), on.end());
  std::sort(nodes.begin(), nodes.end());
  nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
  return nodes;
}

FlatEdges flat_edges(const Mesh& mesh, const std::vector<std::uint8_t>& fitted) {
  FlatEdges out;
  for (const CellBlock& block : mesh.cells) {
    std::vector<std::int32_t>& mask_of = out.mask_of_cell.emplace_back(block.n_cells(), -1);
    const ReferenceElement& ref = reference_element(block.type, block.order);
    const std::span<const std::vector<int>> corners = corner_facets(block.type);
    const ShapeTable& samples = validity_samples(block.type, block.order);
    const int n = block.n_nodes_per_cell(), n_corners = n_corners_of(block.type);
    // The cell's edges in 3D (two corners on two common facets) and the local nodes on each.
    std::vector<std::array<int, 2>> edges;
    std::vector<std::vector<int>> edge_nodes;
    for (int a = 0; a < n_corners && mesh.dim == 3; ++a)
      for (int b = a + 1; b < n_corners; ++b) {
        int common = 0;
        for (const std::vector<int>& f : corners) common += std::ranges::count(f, a) && std::ranges::count(f, b);
        if (common != 2) continue;
        edges.push_back({a, b});
        std::vector<int>& on = edge_nodes.emplace_back();
        for (int k = 0; k < ref.n_nodes(); ++k)
          if (on_segment(ref.nodes.col(k), ref.nodes.col(a), ref.nodes.col(b))) on.push_back(k);
      }
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const auto all_fitted = [&](const std::vector<int>& local) {
        return std::ranges::all_of(local, [&](int a) { return fitted[static_cast<std::size_t>(block.nodes[c * n + a])] != 0; });
      };
      std::vector<std::uint8_t> mask;
      const auto flag = [&](int a, int b) {  // the samples on the segment between corners a and b
        mask.resize(static_cast<std::size_t>(samples.n_points()), 0);
        for (int q = 0; q < samples.n_points(); ++q)
          if (on_segment(samples.points.col(q), ref.nodes.col(a), ref.nodes.col(b))) mask[static_cast<std::size_t>(q)] = 1;
      };
      std::vector<int> on;  // the facets whose nodes are all fitted
      for (std::size_t f = 0; f < ref.facet_nodes.size(); ++f)
        if (all_fitted(ref.facet_nodes[f])) on.push_back(static_cast<int>(f));
      for (std::size_t i = 0; i < on.size(); ++i)
        for (std::size_t j = i + 1; j < on.size(); ++j) {
          std::vector<int> shared;  // the corners of the edge (3D) or the corner (2D) between them
          for (int a : corners[static_cast<std::size_t>(on[i])])
            if (std::ranges::count(corners[static_cast<std::size_t>(on[j])], a)) shared.push_back(a);
          if (static_cast<int>(shared.size()) == mesh.dim - 1) flag(shared.front(), shared.back());
        }
      // A corner whose three edges lie on the level set: their tangents span its tangent
      // plane only, so det A = 0 there even where no two of its facets are fitted.
      for (int a = 0; a < n_corners && !edges.empty(); ++a) {
        int incident = 0, fitted_edges = 0;
        for (std::size_t e = 0; e < edges.size(); ++e)
          if (edges[e][0] == a || edges[e][1] == a) {
            ++incident;
            fitted_edges += all_fitted(edge_nodes[e]);
          }
        if (fitted_edges == incident) flag(a, a);
      }
      if (mask.empty()) continue;
      mask_of[c] = static_cast<std::int32_t>(out.masks.size());
      out.masks.push_back(std::move(mask));
      ++out.cells;
    }
  }
  return out;
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
// What untangling does with the boundary: the surfaces its nodes slide on, and whether the
// inverted cells leave it a choice.
#include <algorithm>

#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/methods/optimize.h"
#include "meshmorph/methods/untangle.h"

namespace meshmorph {
namespace {

bool cell_valid(const Mesh& mesh, const CellBlock& block, std::size_t c, const Eigen::MatrixXd& x) {
  const int n = block.n_nodes_per_cell();
  Eigen::MatrixXd X(mesh.dim, n);
  for (int a = 0; a < n; ++a) X.col(a) = x.col(block.cell(c)[a]);
  return min_jacobian_det(block.type, block.order, X) > 0.0;
}

}  // namespace

std::vector<FitTerm> untangle_surfaces(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& facets,
                                       const std::vector<std::uint8_t>& may_slide, double feature_angle) {
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(mesh.dim) * mesh.n_nodes(), 0);
  std::vector<FitTerm> surfaces = boundary_slides(mesh, topology, facets, feature_angle, true, fixed);
  for (FitTerm& t : surfaces)
    std::erase_if(t.nodes, [&](std::int32_t node) { return may_slide[static_cast<std::size_t>(node)] == 0; });
  std::erase_if(surfaces, [](const FitTerm& t) { return t.nodes.empty(); });
  return surfaces;
}

std::size_t boundary_bound_inverted(const Mesh& mesh, const BoundaryTargets& bc, const std::vector<std::uint8_t>* invalid) {
  std::size_t count = 0, cell = 0;
  for (const CellBlock& block : mesh.cells) {
    const int corners = n_corners_of(block.type);
    for (std::size_t c = 0; c < block.n_cells(); ++c, ++cell) {
      const std::int32_t* nodes = block.cell(c);
      const bool bound = std::all_of(nodes, nodes + corners, [&](std::int32_t node) {
        return bc.role[static_cast<std::size_t>(node)] != NodeRole::Free;
      });
      if (bound && (invalid ? (*invalid)[cell] != 0 : !cell_valid(mesh, block, c, mesh.x))) ++count;
    }
  }
  return count;
}

LocalUntangle untangle_locally(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& may_slide,
                               double feature_angle, int layers, UntangleOptions options, Eigen::MatrixXd& x,
                               const std::vector<std::uint8_t>* invalid) {
  LocalUntangle local;
  // The patch: the inverted cells and `layers` rings of cells around them (sharing a node).
  const std::size_t n_cells = topology.block_offset.back();
  std::vector<std::uint8_t> in = invalid ? *invalid : std::vector<std::uint8_t>(n_cells, 0);
  std::vector<std::int32_t> patch;
  for (std::size_t b = 0; b < mesh.cells.size() && !invalid; ++b) {
    const auto n = static_cast<std::ptrdiff_t>(mesh.cells[b].n_cells());
#pragma omp parallel for schedule(dynamic, 256)
    for (std::ptrdiff_t c = 0; c < n; ++c)
      in[topology.block_offset[b] + static_cast<std::size_t>(c)] = !cell_valid(mesh, mesh.cells[b], static_cast<std::size_t>(c), x);
  }
  for (std::size_t cell = 0; cell < n_cells; ++cell)
    if (in[cell]) patch.push_back(static_cast<std::int32_t>(cell));
  if (patch.empty()) {
    local.result.converged = true;
    local.result.message = "no inverted cell";
    return local;
  }
  for (int ring = 0; ring < layers; ++ring)
    for (std::size_t k = 0, end = patch.size(); k < end; ++k) {
      const auto [b, c] = topology.locate(patch[k]);
      const CellBlock& block = mesh.cells[b];
      for (int a = 0; a < block.n_nodes_per_cell(); ++a)
        for (std::int32_t other : topology.cells_of(static_cast<std::size_t>(block.cell(c)[a])))
          if (!in[static_cast<std::size_t>(other)]) {
            in[static_cast<std::size_t>(other)] = 1;
            patch.push_back(other);
          }
    }
  // The patch as a mesh of its own, its nodes numbered in order of appearance.
  Mesh sub;
  sub.dim = mesh.dim;
  std::vector<std::int32_t> local_of(mesh.n_nodes(), -1), global_of;
  for (const CellBlock& block : mesh.cells) sub.cells.push_back(CellBlock{block.type, block.order, {}, {}, {}});
  std::sort(patch.begin(), patch.end());
  std::vector<std::int32_t> nodes;
  for (std::int32_t cell : patch) {
    const auto [b, c] = topology.locate(cell);
    const CellBlock& block = mesh.cells[b];
    nodes.assign(block.cell(c), block.cell(c) + block.n_nodes_per_cell());
    for (std::int32_t& node : nodes) {
      std::int32_t& l = local_of[static_cast<std::size_t>(node)];
      if (l < 0) {
        l = static_cast<std::int32_t>(global_of.size());
        global_of.push_back(node);
      }
      node = l;
    }
    sub.cells[b].push_back(nodes.data(), 0);
  }
  std::erase_if(sub.cells, [](const CellBlock& block) { return block.nodes.empty(); });
  sub.x = x(Eigen::all, global_of);
  // Fixed: the nodes the patch shares with the rest of the mesh and the boundary nodes that
  // do not slide; the sliding ones move on the surface of the patch's boundary facets (every
  // facet through a node not shared with the rest is one of them).
  std::vector<std::int32_t> facets;
  for (std::int32_t f : topology.boundary_facets)
    if (in[static_cast<std::size_t>(topology.facets[static_cast<std::size_t>(f)][0].cell)]) facets.push_back(f);
  const std::vector<FitTerm> surfaces = untangle_surfaces(mesh, topology, facets, may_slide, feature_angle);
  std::vector<std::uint8_t> cut(global_of.size(), 0), slides(mesh.n_nodes(), 0);
  for (std::size_t l = 0; l < global_of.size(); ++l)
    for (std::int32_t cell : topology.cells_of(static_cast<std::size_t>(global_of[l]))) cut[l] = cut[l] || !in[static_cast<std::size_t>(cell)];
  std::vector<FitTerm> sub_surfaces;
  for (const FitTerm& t : surfaces) {
    FitTerm s{t.sigma, {}};
    for (std::int32_t node : t.nodes) {
      const std::int32_t l = local_of[static_cast<std::size_t>(node)];
      if (l < 0 || cut[static_cast<std::size_t>(l)]) continue;
      s.nodes.push_back(l);
      slides[static_cast<std::size_t>(node)] = 1;
    }
    std::sort(s.nodes.begin(), s.nodes.end());
    if (!s.nodes.empty()) sub_surfaces.push_back(std::move(s));
  }
  BoundaryTargets bc;
  bc.role.assign(global_of.size(), NodeRole::Free);
  bc.target = sub.x;
  bc.normal = Eigen::MatrixXd::Zero(sub.dim, sub.x.cols());
  std::vector<std::uint8_t> on_boundary(mesh.n_nodes(), 0);
  for (std::int32_t node : boundary_nodes(mesh, topology)) on_boundary[static_cast<std::size_t>(node)] = 1;
  for (std::size_t l = 0; l < global_of.size(); ++l) {
    const auto g = static_cast<std::size_t>(global_of[l]);
    if (cut[l] || (on_boundary[g] && !slides[g])) bc.role[l] = NodeRole::Fixed;
  }
  const Topology sub_topology = build_topology(sub);
  options.reference = UntangleReference::InputWhereValid;
  options.certify = true;
  Untangler untangler(sub, sub_topology, bc, options, sub_surfaces);
  Eigen::MatrixXd y = sub.x;
  local.result = untangler.solve(sub.x, y);
  local.cells = patch.size();
  local.deviation = fit_error(sub_surfaces, y);
  x(Eigen::all, global_of) = y;
  return local;
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/methods/optimize_boundary.h"

#include <algorithm>

#include <Eigen/Eigenvalues>

#include "meshmorph/error.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/methods/optimize.h"
#include "meshmorph/methods/untangle.h"

namespace meshmorph {
namespace {

// The slide surfaces of the entries; fixed flags of their nodes set as they say.
std::vector<FitTerm> entry_slides(Mesh& mesh, const Topology& topology, const std::vector<OptimizeEntry>& entries,
                                  double feature_angle, const std::string& file, std::vector<std::uint8_t>& fixed) {
  const int d = mesh.dim;
  const double size = (mesh.x.rowwise().maxCoeff() - mesh.x.rowwise().minCoeff()).norm();
  LevelSetOptions lso;
  lso.source = file;
  lso.length_scale = size;
  std::vector<FitTerm> slides;
  for (const OptimizeEntry& e : entries) {
    std::vector<std::int32_t> nodes = e.nodes;
    const std::string where = file + ": " + e.key_path;
    if (e.kind == OptimizeEntry::Kind::Project) {
      LevelSetFunction sigma(*e.level_set, d, lso);
      double moved = 0.0;
      for (std::int32_t node : nodes) {
        const std::optional<Eigen::VectorXd> p = sigma.closest_point(mesh.x.col(node));
        if (!p)
          throw InputError(where + ".project: node " +
                           std::to_string(mesh.node_tags.empty() ? node + 1 : mesh.node_tags[static_cast<std::size_t>(node)]) +
                           " has no closest point on the level set");
        moved = std::max(moved, (*p - mesh.x.col(node)).norm());
        mesh.x.col(node) = *p;
      }
      if (const std::size_t bad = count_invalid_cells(mesh); bad > 0)
        throw InputError(where + ".project: moving the group's nodes onto the level set (by up to " + std::to_string(moved) +
                         ") inverts " + std::to_string(bad) + " cells; fit them onto it first");
      slides.push_back({std::move(sigma), std::move(nodes)});
    } else if (e.kind == OptimizeEntry::Kind::Slide) {
      // The group's plane: through its centroid, normal to its least-spread direction.
      const Eigen::MatrixXd X = mesh.x(Eigen::all, nodes);
      const Eigen::VectorXd centre = X.rowwise().mean();
      const Eigen::MatrixXd Y = X.colwise() - centre;
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Y * Y.transpose());
      const Eigen::VectorXd normal = eig.eigenvectors().col(0);
      if ((normal.transpose() * Y).cwiseAbs().maxCoeff() > 1e-10 * size) {
        // Curved: the boundary facets whose nodes are all in the group.
        std::vector<std::uint8_t> in(mesh.n_nodes(), 0);
        for (std::int32_t node : nodes) in[static_cast<std::size_t>(node)] = 1;
        std::vector<std::int32_t> facets;
        for (std::int32_t f : topology.boundary_facets) {
          const CellFacet cf = topology.facets[static_cast<std::size_t>(f)][0];
          const auto [blk, cell] = topology.locate(cf.cell);
          const std::vector<std::int32_t> fn = facet_nodes(mesh.cells[blk], cell, cf.local);
          if (std::all_of(fn.begin(), fn.end(), [&](std::int32_t n) { return in[static_cast<std::size_t>(n)] != 0; }))
            facets.push_back(f);
        }
        if (facets.empty()) throw InputError(where + ".slide: the group's nodes are not on one plane and hold no boundary facet");
        for (FitTerm& t : boundary_slides(mesh, topology, facets, feature_angle, true, fixed)) slides.push_back(std::move(t));
        continue;
      }
      slides.push_back({LevelSetFunction(LevelSet{PlaneLevelSet{centre, normal}, e.key_path}, d, lso), std::move(nodes)});
    } else {
      continue;  // Fixed: below, so that it wins over a slide entry whatever the order
    }
    for (std::int32_t node : slides.back().nodes) std::fill_n(fixed.begin() + d * node, d, 0);
  }
  for (const OptimizeEntry& e : entries)
    if (e.kind == OptimizeEntry::Kind::Fixed)
      for (std::int32_t node : e.nodes) std::fill_n(fixed.begin() + d * node, d, 1);
  return slides;
}

// A node on d or more surfaces (a corner) cannot slide: fixed and dropped from every entry.
void fix_corners(std::vector<FitTerm>& slides, int d, std::size_t n_nodes, std::vector<std::uint8_t>& fixed) {
  std::vector<int> count(n_nodes, 0);
  for (const FitTerm& t : slides)
    for (std::int32_t node : t.nodes) ++count[static_cast<std::size_t>(node)];
  for (FitTerm& t : slides)
    std::erase_if(t.nodes, [&](std::int32_t node) {
      const bool corner = count[static_cast<std::size_t>(node)] >= d || fixed[static_cast<std::size_t>(d * node)];
      if (corner) std::fill_n(fixed.begin() + d * node, d, 1);
      return corner;
    });
}

}  // namespace

OptimizeConstraints optimize_constraints(Mesh& start, const Topology& topology, const std::vector<OptimizeEntry>& entries,
                                         BoundaryTreatment treatment, double feature_angle, const std::string& file) {
  const int d = start.dim;
  OptimizeConstraints c;
  c.fixed.assign(static_cast<std::size_t>(d) * start.n_nodes(), 0);
  if (treatment != BoundaryTreatment::Fixed) {
    c.slides = boundary_slides(start, topology, topology.boundary_facets, feature_angle, treatment == BoundaryTreatment::Slide,
                               c.fixed);
  } else {
    for (std::int32_t node : boundary_nodes(start, topology)) std::fill_n(c.fixed.begin() + d * node, d, 1);
  }
  std::vector<FitTerm> named_slides = entry_slides(start, topology, entries, feature_angle, file, c.fixed);
  // A node that an entry names follows that entry, not the automatic planes.
  std::vector<std::uint8_t> named(start.n_nodes(), 0);
  for (const OptimizeEntry& e : entries)
    for (std::int32_t node : e.nodes) named[static_cast<std::size_t>(node)] = 1;
  for (FitTerm& t : c.slides) std::erase_if(t.nodes, [&](std::int32_t node) { return named[static_cast<std::size_t>(node)] != 0; });
  for (FitTerm& t : named_slides) c.slides.push_back(std::move(t));
  fix_corners(c.slides, d, start.n_nodes(), c.fixed);
  std::erase_if(c.slides, [](const FitTerm& t) { return t.nodes.empty(); });
  std::vector<std::uint8_t> seen(start.n_nodes(), 0);
  for (const FitTerm& t : c.slides)
    for (std::int32_t node : t.nodes) c.slide_nodes += seen[static_cast<std::size_t>(node)]++ == 0 ? 1 : 0;
  return c;
}

Eigen::MatrixXd untangled_start(const Mesh& mesh, const Topology& topology, int threads, const std::string& where,
                                long long& newton) {
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(mesh.dim, static_cast<Eigen::Index>(mesh.n_nodes()));
  std::vector<std::uint8_t> on_boundary(mesh.n_nodes(), 0);
  for (std::int32_t node : boundary_nodes(mesh, topology)) {
    bc.role[static_cast<std::size_t>(node)] = NodeRole::Fixed;
    on_boundary[static_cast<std::size_t>(node)] = 1;
  }
  UntangleOptions uo;
  uo.reference = UntangleReference::Regular;
  uo.threads = threads;
  // In 3D CG-AMG: the start needs only be valid, and CHOLMOD's factor of a high-order 3D
  // Hessian would be the run's peak (untangle3d: 158 MB, against 84 MB with CG-AMG).
  if (mesh.dim == 3) uo.solver = LinearSolverKind::Iterative;
  Mesh moved = mesh;
  // Cells inverted against the boundary: first a patch around them, the boundary sliding
  // along itself (as `untangle MESH` does).
  if (boundary_bound_inverted(mesh, bc) > 0) {
    for (const int layers : {1, 2}) {
      moved.x = mesh.x;
      const LocalUntangle l = untangle_locally(mesh, topology, on_boundary, 30.0, layers, uo, moved.x);
      newton += l.result.newton;
      if (count_invalid_cells(moved) == 0) return moved.x;
    }
  }
  Untangler untangler(mesh, topology, bc, uo);
  Eigen::MatrixXd x = mesh.x;
  const UntangleResult r = untangler.solve(mesh.x, x);
  newton += r.newton;
  moved.x = x;
  if (count_invalid_cells(moved) > 0)
    throw InputError(where + ": the mesh is tangled and untangling with its boundary fixed failed: " + r.message);
  return x;
}

}  // namespace meshmorph

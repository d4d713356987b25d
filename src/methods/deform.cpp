// SPDX-License-Identifier: MIT
#include "meshmorph/methods/deform.h"

#include <string>

#include "meshmorph/error.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/methods/baselines.h"
#include "methods/detail/convection_extension.h"
#include "methods/detail/scalar_fe.h"

namespace meshmorph {
namespace {

// Design nodes that also belong to a boundary facet off the design: where the design meets
// the rest of the boundary, which the CVT step must not move.
std::vector<std::uint8_t> design_rim(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& on_design) {
  std::vector<std::uint8_t> rim(mesh.n_nodes(), 0);
  for (std::int32_t f : topology.boundary_facets) {
    const CellFacet& cf = topology.facets[static_cast<std::size_t>(f)][0];
    const auto [bi, c] = topology.locate(cf.cell);
    const std::vector<std::int32_t> nodes = facet_nodes(mesh.cells[bi], c, cf.local);
    bool all = true;
    for (std::int32_t v : nodes) all = all && on_design[static_cast<std::size_t>(v)];
    if (!all)
      for (std::int32_t v : nodes)
        if (on_design[static_cast<std::size_t>(v)]) rim[static_cast<std::size_t>(v)] = 1;
  }
  return rim;
}

// The far-field nodes inside curved boundary facets that touch the design: their
// displacement is their facet corners' (the design's motion or zero), interpolated, which is
// the Dirichlet data a linear mesh has along that facet. Pinned at zero, the edge nodes next
// to a moving corner fold the facet: the P3 cell at the top of a fixed side wall inverts when
// the top slides down by a quarter of a cell.
void interpolate_far_field_rim(const Mesh& mesh, const Topology& topology, const BoundaryTargets& bc, Eigen::MatrixXd& v) {
  for (std::int32_t f : topology.boundary_facets) {
    const CellFacet& cf = topology.facets[static_cast<std::size_t>(f)][0];
    const auto [bi, c] = topology.locate(cf.cell);
    const CellBlock& block = mesh.cells[bi];
    if (block.order == 1) continue;
    const std::vector<std::int32_t> nodes = facet_nodes(block, c, cf.local);
    const ReferenceElement& ref = reference_element(facet_type(block.type, cf.local), block.order);
    const int corners = n_corners_of(ref.type);
    bool dirichlet = true, moving = false;
    for (int i = 0; i < corners; ++i) {
      const NodeRole role = bc.role[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])];
      dirichlet = dirichlet && (role == NodeRole::Prescribed || role == NodeRole::Fixed);
      moving = moving || role == NodeRole::Prescribed;
    }
    if (!dirichlet || !moving) continue;
    for (std::size_t j = static_cast<std::size_t>(corners); j < nodes.size(); ++j) {
      if (bc.role[static_cast<std::size_t>(nodes[j])] != NodeRole::Fixed) continue;
      const Eigen::VectorXd w = corner_weights(ref.type, ref.nodes.col(static_cast<Eigen::Index>(j)));
      v.col(nodes[j]).setZero();
      for (int i = 0; i < corners; ++i) v.col(nodes[j]) += w(i) * v.col(nodes[static_cast<std::size_t>(i)]);
    }
  }
}

// Where the extension inverts a curved cell, its inner nodes (edge, face and interior nodes
// that are neither design nor far field) go to the straight-sided places between its moved
// corners. The extension's field is steep where a design motion meets a fixed wall (a
// boundary layer a cell wide), and a P2/P3 cell that samples it at its inner nodes folds,
// though its corners alone make a valid linear cell. A straight simplex is valid exactly when
// its corners are; a straightened edge or face is shared, so a neighbour may now fold and is
// straightened in the next pass. Returns the number of cells straightened.
std::size_t straighten_inverted(const Mesh& mesh, const BoundaryTargets& bc, Eigen::MatrixXd& x) {
  Mesh moved = mesh;
  std::size_t straightened = 0;
  for (bool changed = true; changed;) {
    changed = false;
    moved.x = x;
    for (const CellBlock& block : mesh.cells) {
      if (block.order == 1) continue;
      const ReferenceElement& ref = reference_element(block.type, block.order);
      const int corners = n_corners_of(block.type);
      for (std::size_t c = 0; c < block.n_cells(); ++c) {
        if (min_jacobian_det(block.type, block.order, cell_coordinates(moved, block, c)) > 0.0) continue;
        const std::int32_t* nodes = block.cell(c);
        bool moved_node = false;
        for (int j = corners; j < ref.n_nodes(); ++j) {
          const auto v = static_cast<std::size_t>(nodes[j]);
          if (bc.role[v] == NodeRole::Prescribed || bc.role[v] == NodeRole::Fixed) continue;
          const Eigen::VectorXd w = corner_weights(block.type, ref.nodes.col(j));
          Eigen::VectorXd p = Eigen::VectorXd::Zero(mesh.dim);
          for (int i = 0; i < corners; ++i) p += w(i) * x.col(nodes[i]);
          if (p != x.col(nodes[j])) x.col(nodes[j]) = p, moved_node = true;
        }
        if (moved_node) ++straightened, changed = true;
      }
    }
  }
  return straightened;
}

Eigen::VectorXd normalized(const Eigen::VectorXd& e) {
  const double m = e.maxCoeff();
  return m > 0.0 ? Eigen::VectorXd(e / m) : e;
}

}  // namespace

DeformResult deform(const Mesh& mesh, const Topology& topology, const BoundaryTargets& bc,
                    const Eigen::MatrixXd& density_reference, const DeformOptions& options,
                    const SurfaceProjection& projection, const EikonalDistances& previous) {
  const int d = mesh.dim;
  const std::size_t n = mesh.n_nodes();
  MESHMORPH_CHECK(bc.n_nodes() == n && bc.target.cols() == static_cast<Eigen::Index>(n),
                  "deform: the boundary targets do not fit the mesh");
  std::vector<std::uint8_t> on_design(n, 0);
  std::vector<std::int32_t> design, far;
  for (std::size_t i = 0; i < n; ++i) {
    if (bc.role[i] == NodeRole::Prescribed) on_design[i] = 1, design.push_back(static_cast<std::int32_t>(i));
    if (bc.role[i] == NodeRole::Fixed) far.push_back(static_cast<std::int32_t>(i));
  }
  if (design.empty()) throw InputError("deform: no design node (no boundary group has a motion)");

  DeformResult result;
  Eigen::MatrixXd y = bc.target;  // the design's new positions
  if (options.cvt) {
    const DesignSurface surface = design_surface(mesh, topology, on_design);
    result.cvt = surface_cvt(surface, bc.target, density_reference, design_rim(mesh, topology, on_design),
                             options.cvt_options, projection);
    y = result.cvt.x;
  }

  if (options.method == DeformMethod::Laplace) {
    BoundaryTargets moved = bc;
    moved.target = y;
    BaselineOptions bo;
    bo.solver = options.solver;
    bo.threads = options.threads;
    const BaselineResult r = laplace_morph(mesh, topology, moved, bo);
    result.x = r.x;
    result.linear_solves = r.linear_solves;
    result.converged = r.linear.ok;
    result.message = r.linear.ok ? "Laplacian extension" : "laplace: " + r.linear.message;
    return result;
  }

  if (far.empty()) throw InputError("deform: the Eikonal method needs a far field (a fixed boundary part) for ε₁");
  EikonalOptions eo = options.eikonal;
  eo.threads = options.threads;
  const EikonalResult e1 = eikonal_distance(mesh, topology, far, eo, previous.far_field);
  const EikonalResult e2 = eikonal_distance(mesh, topology, design, eo, previous.design);
  result.newton = e1.newton + e2.newton;
  if (!e1.converged || !e2.converged) {
    result.x = mesh.x;
    result.message = !e1.converged ? "far-field " + e1.message : "design " + e2.message;
    return result;
  }
  result.distances = {e1.distance, e2.distance};
  const Eigen::VectorXd eps1 = normalized(e1.distance), eps2 = normalized(e2.distance);

  // Dirichlet: the design (its displacement), the far field and nodes in no cell (zero).
  std::vector<std::uint8_t> dirichlet(n, 1);
  for (const CellBlock& block : mesh.cells)
    for (std::int32_t v : block.nodes) dirichlet[static_cast<std::size_t>(v)] = 0;
  for (std::size_t i = 0; i < n; ++i)
    if (bc.role[i] == NodeRole::Prescribed || bc.role[i] == NodeRole::Fixed) dirichlet[i] = 1;
  const detail::ScalarAssembler assembler(mesh, topology, options.threads, "deform");
  const Eigen::SparseMatrix<double> A = detail::convection_diffusion_matrix(
      assembler, options.diffusion == DiffusionDistance::FarField ? eps1 : eps2, eps2, options.alpha, options.beta,
      options.conservative);
  detail::DirichletSolver solver(dirichlet);
  if (!solver.factorize(A)) {
    result.x = mesh.x;
    result.message = "the convection-diffusion matrix (eq. 3.8) is singular";
    return result;
  }
  result.x = mesh.x;
  Eigen::MatrixXd boundary_v = Eigen::MatrixXd::Zero(d, static_cast<Eigen::Index>(n));
  for (std::int32_t i : design) boundary_v.col(i) = y.col(i) - mesh.x.col(i);
  interpolate_far_field_rim(mesh, topology, bc, boundary_v);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(n));
  for (int k = 0; k < d; ++k) {
    Eigen::VectorXd v = boundary_v.row(k).transpose();
    solver.solve(zero, v);
    ++result.linear_solves;
    result.x.row(k) += v.transpose();
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    if (bc.role[i] == NodeRole::Prescribed) result.x.col(c) = y.col(c);  // exactly, not up to the solve
    if (bc.role[i] == NodeRole::Slide) {
      const Eigen::VectorXd nn = bc.normal.col(c).normalized();
      result.x.col(c) -= nn * nn.dot(result.x.col(c) - mesh.x.col(c));
    }
  }
  result.straightened_cells = straighten_inverted(mesh, bc, result.x);
  result.converged = true;
  result.message = "CVT + Eikonal convection";
  return result;
}

}  // namespace meshmorph

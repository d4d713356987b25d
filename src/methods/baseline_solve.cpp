// SPDX-License-Identifier: MIT
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "meshmorph/energy/slide_constraints.h"
#include "meshmorph/error.h"
#include "methods/detail/stiffness.h"

namespace meshmorph::detail {
namespace {

std::string singular_message(std::string_view method) {
  return std::string(method) +
         ": the linear system is singular; the Fixed and Prescribed nodes and the Slide planes must hold the mesh "
         "against every " + (method == "laplace" ? "translation" : "translation and rotation");
}

// Values of the kernel modes of K at point p (d × modes): the d translations and, with
// `rotations`, the infinitesimal rotations ω × p (one in 2D, three in 3D).
Eigen::MatrixXd modes_at(const Eigen::VectorXd& p, bool rotations) {
  const auto d = p.size();
  const Eigen::Index n_rot = rotations ? (d == 2 ? 1 : 3) : 0;
  Eigen::MatrixXd M = Eigen::MatrixXd::Zero(d, d + n_rot);
  M.leftCols(d).setIdentity();
  if (n_rot == 1) M.col(2) << -p[1], p[0];
  if (n_rot == 3)
    for (int r = 0; r < 3; ++r) M.col(3 + r) = Eigen::Vector3d::Unit(r).cross(Eigen::Vector3d(p));
  return M;
}

// Throws unless the constraints remove every kernel mode: the Gram matrix CᵀC of the
// constrained values C of the modes (coordinates centred and scaled to the mesh's extent, so
// that the test does not depend on units) must be well conditioned. A Cholesky factorization
// would miss these cases: rounding leaves small positive pivots on a singular matrix.
void check_anchored(const Mesh& mesh, const BoundaryTargets& bc, const std::vector<bool>& in_cell, bool rotations,
                    std::string_view method) {
  const Eigen::VectorXd lo = mesh.x.rowwise().minCoeff(), hi = mesh.x.rowwise().maxCoeff();
  const Eigen::VectorXd centre = 0.5 * (lo + hi);
  const double scale = std::max((hi - lo).maxCoeff(), 1e-300);
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(modes_at(centre, rotations).cols(), modes_at(centre, rotations).cols());
  for (std::size_t j = 0; j < bc.n_nodes(); ++j) {
    const auto c = static_cast<Eigen::Index>(j);
    if (!in_cell[j] || bc.role[j] == NodeRole::Free) continue;
    const Eigen::MatrixXd M = modes_at((mesh.x.col(c) - centre) / scale, rotations);
    if (bc.role[j] == NodeRole::Slide) {
      const Eigen::RowVectorXd row = bc.normal.col(c).normalized().transpose() * M;
      gram += row.transpose() * row;
    } else {
      gram += M.transpose() * M;
    }
  }
  const Eigen::VectorXd eig = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(gram, Eigen::EigenvaluesOnly).eigenvalues();
  if (!(eig[0] > 1e-10 * std::max(eig[eig.size() - 1], 1e-300))) throw InputError(singular_message(method));
}

}  // namespace

// u = P y + u_bc: the columns of P are the unknown directions (d unit vectors per Free node,
// the d − 1 tangents per Slide node), u_bc the prescribed displacements. Minimising the
// quadratic energy over y gives (Pᵀ K P) y = −Pᵀ K u_bc: an SPD system whenever the
// constraints remove the kernel of K, with n·u = 0 exact at Slide nodes by construction.
BaselineResult solve_constrained(const Mesh& mesh, const BoundaryTargets& bc, const Eigen::SparseMatrix<double>& K,
                                 bool rotations_in_kernel, const BaselineOptions& options, std::string_view method) {
  const int d = mesh.dim;
  const std::size_t n_nodes = mesh.n_nodes();
  const std::string name(method);
  MESHMORPH_CHECK(bc.n_nodes() == n_nodes && bc.target.rows() == d && static_cast<std::size_t>(bc.target.cols()) == n_nodes,
                  name + ": the boundary targets do not fit the mesh");
  const bool any_slide = !bc.nodes_with(NodeRole::Slide).empty();
  MESHMORPH_CHECK(!any_slide || (bc.normal.rows() == d && static_cast<std::size_t>(bc.normal.cols()) == n_nodes),
                  name + ": the slide normals do not fit the mesh");

  std::vector<bool> in_cell(n_nodes, false);
  for (const CellBlock& block : mesh.cells)
    for (std::int32_t v : block.nodes) in_cell[static_cast<std::size_t>(v)] = true;

  const auto n_dofs = static_cast<Eigen::Index>(d) * static_cast<Eigen::Index>(n_nodes);
  Eigen::VectorXd u_bc = Eigen::VectorXd::Zero(n_dofs);
  std::vector<Eigen::Triplet<double, int>> p_entries;
  std::vector<double> coordinates;  // of the Free nodes' unknowns, for PETSc's GAMG
  int m = 0;  // unknowns
  for (std::size_t j = 0; j < n_nodes; ++j) {
    const auto row = static_cast<int>(j) * d;
    switch (bc.role[j]) {
      case NodeRole::Prescribed:
        u_bc.segment(row, d) = bc.target.col(static_cast<Eigen::Index>(j)) - mesh.x.col(static_cast<Eigen::Index>(j));
        break;
      case NodeRole::Fixed: break;
      case NodeRole::Free:
        if (!in_cell[j]) break;  // no equation: the node stays where it is
        for (int k = 0; k < d; ++k) {
          p_entries.emplace_back(row + k, m++, 1.0);
          coordinates.push_back(mesh.x(k, static_cast<Eigen::Index>(j)));
        }
        break;
      case NodeRole::Slide: {
        if (!in_cell[j]) break;
        const Eigen::VectorXd n = bc.normal.col(static_cast<Eigen::Index>(j));
        if (!(n.norm() > 1e-12) || !n.allFinite())
          throw InputError(name + ": slide node " + std::to_string(j) + " has no normal (zero or not finite)");
        const Eigen::MatrixXd T = tangent_basis(n.normalized());
        for (Eigen::Index t = 0; t < T.cols(); ++t, ++m)
          for (int k = 0; k < d; ++k)
            if (T(k, t) != 0.0) p_entries.emplace_back(row + k, m, T(k, t));
        break;
      }
    }
  }
  if (!u_bc.allFinite()) throw InputError(name + ": a prescribed target is not finite");

  BaselineResult result;
  result.x = mesh.x;
  for (std::size_t j = 0; j < n_nodes; ++j)
    if (bc.role[j] == NodeRole::Prescribed)
      result.x.col(static_cast<Eigen::Index>(j)) = bc.target.col(static_cast<Eigen::Index>(j));  // exactly on target
  if (m == 0) {
    result.linear_solves = 0;
    result.linear.ok = true;
    return result;
  }
  check_anchored(mesh, bc, in_cell, rotations_in_kernel, method);

  Eigen::SparseMatrix<double> P(n_dofs, m);
  P.setFromTriplets(p_entries.begin(), p_entries.end());
  const Eigen::SparseMatrix<double> Pt = P.transpose();
  Eigen::SparseMatrix<double> A = Pt * K * P;
  if (any_slide) {
    // The rotated rows come out of the products with rounding in different orders.
    const Eigen::SparseMatrix<double> At = A.transpose();
    A = 0.5 * (A + At);
  }
  A.makeCompressed();
  const Eigen::VectorXd b = -(Pt * (K * u_bc));

  LinearSolverOptions lo;
  lo.kind = options.solver;
  lo.dim = d;
  lo.cell_nodes = mesh.max_cell_nodes();
  // Slide nodes carry d − 1 unknowns, which breaks the d-per-node blocks of the iterative backend.
  lo.block_size = any_slide ? 1 : d;
  lo.threads = options.threads;
  if (!any_slide) lo.coordinates = std::move(coordinates);
  auto solver = make_linear_solver(lo, static_cast<std::size_t>(m));
  if (!solver->factorize(A)) throw InputError(singular_message(method));
  Eigen::VectorXd y;
  result.linear = solver->solve(b, y);
  if (!y.allFinite()) throw InputError(singular_message(method));

  const Eigen::VectorXd u = P * y;
  for (std::size_t j = 0; j < n_nodes; ++j) {
    const NodeRole r = bc.role[j];
    if (r == NodeRole::Free || r == NodeRole::Slide)
      result.x.col(static_cast<Eigen::Index>(j)) += u.segment(static_cast<Eigen::Index>(j) * d, d);
  }
  return result;
}

}  // namespace meshmorph::detail

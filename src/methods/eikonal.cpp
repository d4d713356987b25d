// SPDX-License-Identifier: MIT
#include "meshmorph/methods/eikonal.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "meshmorph/error.h"
#include "methods/detail/eikonal_residual.h"
#include "methods/detail/scalar_fe.h"

namespace meshmorph {
namespace detail {

void eikonal_residual(const ScalarAssembler& assembler, const Eigen::VectorXd& eps, double h, Eigen::VectorXd& R,
                      Eigen::SparseMatrix<double>& J) {
  assembler.assemble(
      [&](const ScalarCell& cell, Eigen::MatrixXd& Ke, Eigen::VectorXd& Fe) {
        const int n = cell.table->n_nodes();
        Eigen::VectorXd e(n);
        for (int a = 0; a < n; ++a) e[a] = eps[cell.nodes[a]];
        for (int q = 0; q < cell.table->n_points(); ++q) {
          const Eigen::MatrixXd& G = cell.G[static_cast<std::size_t>(q)];
          const auto N = cell.table->N.col(q);
          const Eigen::VectorXd grad = G.transpose() * e;
          const Eigen::VectorXd Gg = G * grad;  // ∇N_a·∇ε
          const double w = cell.w[q];
          Fe += w * (h * Gg + (grad.squaredNorm() - 1.0) * N);
          Ke += w * (h * G * G.transpose() + 2.0 * N * Gg.transpose());
        }
      },
      J, R);
}

}  // namespace detail

EikonalResult eikonal_distance(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& zero_nodes,
                               const EikonalOptions& options, const Eigen::VectorXd& start) {
  if (zero_nodes.empty()) throw InputError("eikonal: no node carries the zero boundary condition");
  const detail::ScalarAssembler assembler(mesh, topology, options.threads, "eikonal");
  const auto n = static_cast<Eigen::Index>(mesh.n_nodes());
  std::vector<std::uint8_t> fixed(mesh.n_nodes(), 1);  // nodes in no cell stay 0
  for (const CellBlock& block : mesh.cells)
    for (std::int32_t v : block.nodes) fixed[static_cast<std::size_t>(v)] = 0;
  for (std::int32_t v : zero_nodes) fixed[static_cast<std::size_t>(v)] = 1;
  detail::DirichletSolver solver(fixed);
  const double diameter = (mesh.x.rowwise().maxCoeff() - mesh.x.rowwise().minCoeff()).norm();

  EikonalResult result;
  result.h = options.h_factor * assembler.mean_size();
  result.distance = Eigen::VectorXd::Zero(n);
  Eigen::VectorXd& eps = result.distance;
  Eigen::SparseMatrix<double> J;
  Eigen::VectorXd R;
  auto residual_norm = [&](const Eigen::VectorXd& e, double hh) {
    Eigen::SparseMatrix<double> unused;
    Eigen::VectorXd r;
    detail::eikonal_residual(assembler, e, hh, r, unused);
    return solver.free_part(r).norm();
  };
  // Newton at fixed h until the step is below `tol`; false when it does not get there.
  auto newton = [&](double h, double tol) {
    ++result.stages;
    for (int k = 0; k < options.max_newton; ++k) {
      detail::eikonal_residual(assembler, eps, h, R, J);
      const double r0 = solver.free_part(R).norm();
      Eigen::VectorXd delta = Eigen::VectorXd::Zero(n);
      if (!solver.factorize(J)) return false;
      solver.solve(-R, delta);
      ++result.newton;
      // Backtracking on the residual norm; the full step is taken near the solution.
      double alpha = 1.0;
      Eigen::VectorXd trial = eps + delta;
      while (alpha > 1.0 / 64 && !(residual_norm(trial, h) < (1.0 - 1e-4 * alpha) * r0)) {
        alpha *= 0.5;
        trial = eps + alpha * delta;
      }
      eps = trial;
      if (!eps.allFinite()) return false;
      if (alpha * delta.lpNorm<Eigen::Infinity>() <= tol) return true;
    }
    return false;
  };
  const double step_tol = options.tolerance * diameter;

  if (start.size() == n) {
    eps = start;
    for (std::size_t i = 0; i < fixed.size(); ++i)
      if (fixed[i]) eps[static_cast<Eigen::Index>(i)] = 0.0;
    result.converged = newton(result.h, step_tol);
    if (result.converged) {
      result.message = "converged from the given start";
      return result;
    }
    eps.setZero();  // fall back to the continuation
  }

  // Start: −h₀ Δε = 1 (the linear part of the first stage), zero on the zero set.
  double h = std::max(diameter, result.h);
  detail::eikonal_residual(assembler, eps, h, R, J);  // at ε = 0: R = −∫N, J = h K
  if (!solver.factorize(J)) throw InputError("eikonal: the linear system is singular");
  solver.solve(-R, eps);
  for (;;) {
    // Intermediate stages only supply a starting point: a loose tolerance suffices there.
    if (!newton(h, h <= result.h ? step_tol : 1e-4 * diameter)) {
      result.converged = false;
      result.message = "eikonal: Newton did not converge in " + std::to_string(options.max_newton) + " steps at h = " +
                       std::to_string(h);
      return result;
    }
    if (h <= result.h) break;
    h = std::max(0.01 * h, result.h);
  }
  result.converged = true;
  result.message = "converged";
  return result;
}

}  // namespace meshmorph

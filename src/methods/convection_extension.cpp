// SPDX-License-Identifier: MIT
#include "methods/detail/convection_extension.h"

#include <cmath>
#include <limits>

namespace meshmorph::detail {

Eigen::SparseMatrix<double> convection_diffusion_matrix(const ScalarAssembler& assembler, const Eigen::VectorXd& diffusion_distance,
                                                        const Eigen::VectorXd& wind_potential, double alpha, double beta,
                                                        bool conservative) {
  Eigen::SparseMatrix<double> A;
  Eigen::VectorXd unused;
  assembler.assemble(
      [&](const ScalarCell& cell, Eigen::MatrixXd& Ke, Eigen::VectorXd&) {
        const int n = cell.table->n_nodes();
        Eigen::VectorXd e1(n), e2(n);
        for (int a = 0; a < n; ++a) {
          e1[a] = diffusion_distance[cell.nodes[a]];
          e2[a] = wind_potential[cell.nodes[a]];
        }
        for (int q = 0; q < cell.table->n_points(); ++q) {
          const Eigen::MatrixXd& G = cell.G[static_cast<std::size_t>(q)];
          const auto N = cell.table->N.col(q);
          const double eq = N.dot(e1);
          const double k = alpha * eq * eq;
          const Eigen::VectorXd b = beta * (G.transpose() * e2);
          const Eigen::VectorXd Gb = G * b;  // b·∇N_a
          // Streamline-upwind weight τ = h/(2|b|)·(coth Pe − 1/Pe), Pe = |b| h / (2k).
          const double speed = b.norm();
          double tau = 0.0;
          if (speed > 0.0) {
            const double pe = k > 0.0 ? speed * cell.size / (2.0 * k) : std::numeric_limits<double>::infinity();
            const double xi = pe < 1e-3 ? pe / 3.0 : (std::isinf(pe) ? 1.0 : 1.0 / std::tanh(pe) - 1.0 / pe);
            tau = cell.size / (2.0 * speed) * xi;
          }
          // ∫ k ∇v·∇w − v b·∇w (div(b v) integrated by parts; w vanishes on the Dirichlet
          // boundary) + Σ τ (b·∇w)(b·∇v).
          if (conservative) Ke += cell.w[q] * (k * G * G.transpose() - Gb * N.transpose() + tau * Gb * Gb.transpose());
          else Ke += cell.w[q] * (k * G * G.transpose() + N * Gb.transpose() + tau * Gb * Gb.transpose());
        }
      },
      A, unused);
  return A;
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#pragma once
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>
#include <gtest/gtest.h>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/quality/metric_registry.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph::test {

/// P1 stiffness on structured_mesh(simplex, 1, n) of dimension `dim`, with the boundary
/// nodes eliminated (so SPD): linear elasticity with Lamé λ, μ when `elasticity`, else the
/// scalar Laplacian times I_d (a block Laplacian). Unknowns interleaved, dof = dim·node + k.
inline Eigen::SparseMatrix<double> stiffness_matrix(int dim, int n, bool elasticity, double lambda = 1.0,
                                                    double mu = 1.0) {
  const Mesh mesh = structured_mesh(dim == 2 ? ElementType::Triangle : ElementType::Tetrahedron, 1, n);
  const auto nn = static_cast<int>(mesh.n_nodes());
  std::vector<int> reduced(static_cast<std::size_t>(nn), -1);
  int n_free = 0;
  for (int j = 0; j < nn; ++j) {
    const bool inside = (mesh.x.col(j).array() > 1e-12).all() && (mesh.x.col(j).array() < 1.0 - 1e-12).all();
    if (inside) reduced[j] = n_free++;
  }
  std::vector<Eigen::Triplet<double>> triplets;
  const CellBlock& cells = mesh.cells.front();
  const int m = dim + 1;
  for (std::size_t c = 0; c < cells.n_cells(); ++c) {
    const std::int32_t* v = cells.cell(c);
    Eigen::MatrixXd E(dim, dim);  // edge vectors; barycentric gradients G = E⁻ᵀ [−1 … ; I]
    for (int k = 0; k < dim; ++k) E.col(k) = mesh.x.col(v[k + 1]) - mesh.x.col(v[0]);
    const double volume = std::abs(E.determinant()) / (dim == 2 ? 2.0 : 6.0);
    Eigen::MatrixXd G(dim, m);
    const Eigen::MatrixXd Einv_t = E.inverse().transpose();
    G.col(0) = -Einv_t.rowwise().sum();
    G.rightCols(dim) = Einv_t;
    for (int a = 0; a < m; ++a)
      for (int b = 0; b < m; ++b) {
        if (reduced[v[a]] < 0 || reduced[v[b]] < 0) continue;
        for (int i = 0; i < dim; ++i)
          for (int j = 0; j < dim; ++j) {
            double k = i == j ? G.col(a).dot(G.col(b)) * (elasticity ? mu : 1.0) : 0.0;
            if (elasticity) k += lambda * G(i, a) * G(j, b) + mu * G(j, a) * G(i, b);
            if (k != 0.0 || i == j)
              triplets.emplace_back(dim * reduced[v[a]] + i, dim * reduced[v[b]] + j, volume * k);
          }
      }
  }
  Eigen::SparseMatrix<double> K(dim * n_free, dim * n_free);
  K.setFromTriplets(triplets.begin(), triplets.end());
  K.makeCompressed();
  return K;
}

/// The projected (SPD) Hessian of the morphing energy ∫η² on structured_mesh(simplex,
/// order, n) with the interior nodes moved at random by up to 10% of a cell size, boundary
/// nodes fixed: the matrix of a Newton step.
template <int d>
Eigen::SparseMatrix<double> energy_hessian(int order, int n) {
  const Mesh mesh = structured_mesh(d == 2 ? ElementType::Triangle : ElementType::Tetrahedron, order, n);
  const Topology topology = build_topology(mesh);
  const TargetField<d> targets = build_targets<d>(mesh, mesh.x, TargetKind::Input);
  const DofMap dofs = DofMap::fixing_boundary(mesh, topology);
  const EnergyAssembler<d> assembler(mesh, topology, targets, dofs);
  Eigen::MatrixXd x = mesh.x;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.1 / (n * order), 0.1 / (n * order));
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    if ((x.col(j).array() > 1e-12).all() && (x.col(j).array() < 1.0 - 1e-12).all())
      for (int k = 0; k < d; ++k) x(k, j) += u(rng);
  Assembly out;
  assembler.assemble(*make_metric<d>("distortion2"), x, AssemblyOptions{}, out);
  return out.hessian;
}

/// Matrices of one pattern as Newton steps give them: 3D elasticity A; B, A with 30 diagonal
/// entries changed by up to 20%; C, B with 24 rows' diagonal raised by 1e6 (a penalty's jump).
struct NewtonMatrices {
  Eigen::SparseMatrix<double> A, B, C;
};
inline NewtonMatrices newton_matrices() {
  NewtonMatrices m;
  m.A = stiffness_matrix(3, 8, true, 1.0, 1.0);
  m.B = m.A;
  for (Eigen::Index i = 0; i < 30; ++i) m.B.coeffRef(i, i) *= 1.0 + 0.1 * static_cast<double>(i % 3);
  m.C = m.B;
  for (Eigen::Index i = 0; i < 24; ++i) m.C.coeffRef(i, i) *= 1e6;
  return m;
}

/// A right-hand side with entries uniform in [−1, 1] (fixed seed).
inline Eigen::VectorXd random_vector(Eigen::Index n, unsigned seed = 3) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = u(rng);
  return v;
}

/// Solves with a factorized iterative solver to 1e-10, then again from that solution to
/// 1e-6, which must take no iteration; returns the second solve's figures.
inline LinearSolveStats solve_again_from_the_solution(LinearSolver& solver, const Eigen::VectorXd& b) {
  Eigen::VectorXd x;
  EXPECT_TRUE(solver.solve(b, x, 1e-10).ok);
  const LinearSolveStats again = solver.solve(b, x, 1e-6);
  EXPECT_TRUE(again.ok);
  EXPECT_EQ(again.iterations, 0);
  return again;
}

}  // namespace meshmorph::test

// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <petscksp.h>

#include "meshmorph/energy/dof_map.h"
#include "meshmorph/parallel/local_mesh.h"

namespace meshmorph::detail {

/// The Newton system of the distributed methods on one rank (collective calls throughout):
/// the Hessian over the global free DOFs as a PETSc MPI AIJ matrix of block size d, the
/// gradient as an MPI vector and the step as a ghosted one whose local form is the rank's free
/// DOFs in DofMap order (owned first, then the others: LocalMesh::global_free); conjugate
/// gradients with GAMG, with the rigid-body modes of the owned nodes as near-null space where
/// every free node has all d DOFs free. Each rank sets the rows of its owned DOFs alone, from
/// its owned and ghost cells, which hold every cell of an owned node: no rank adds into
/// another's rows, whose sums would then follow the order in which messages arrive.
class RankSystem {
 public:
  /// `dofs`: DofMap::from_mask(d, local.fixed). The matrix is preallocated for the rows of
  /// the owned DOFs from the owned and ghost cells.
  RankSystem(const LocalMesh& local, const DofMap& dofs);
  ~RankSystem();
  RankSystem(const RankSystem&) = delete;
  RankSystem& operator=(const RankSystem&) = delete;

  /// Sets the global gradient of slot 0 (current) or 1 (trial) from every rank's `local`
  /// gradient over its free DOFs (read at the owned ones); returns its 2-norm.
  double set_gradient(const Eigen::VectorXd& local, int slot);
  /// The trial gradient becomes the current one.
  void keep_trial_gradient() { std::swap(gradient_[0], gradient_[1]); }
  /// Sets the global matrix from every rank's `local` Hessian over its free DOFs (both
  /// triangles, the pattern of EnergyAssembler), read in the columns of the owned DOFs.
  void set_hessian(const Eigen::SparseMatrix<double>& local);
  /// Solves H p = −g (current gradient) by CG to ‖g + Hp‖ ≤ rtol‖g‖. On success `p` holds
  /// the rank's free DOFs of p (owned and ghost) and `slope` = gᵀp; returns false, with
  /// `why`, on negative curvature (`indefinite`), a failed set-up or no convergence.
  bool solve(double rtol, Eigen::VectorXd& p, double& slope, bool& indefinite, std::string& why);
  /// CG iterations of the last solve().
  int iterations() const { return iterations_; }

 private:
  Mat H_ = nullptr;
  Vec gradient_[2] = {nullptr, nullptr};
  Vec step_ = nullptr, rhs_ = nullptr;
  KSP ksp_ = nullptr;
  std::vector<PetscInt> rows_;  // global number of each local free DOF
  PetscInt n_owned_ = 0;
  int iterations_ = 0;
};

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#include "parallel/detail/rank_system.h"

#include <algorithm>

#include "meshmorph/solve/petsc_runtime.h"

namespace meshmorph::detail {
namespace {

// Whether every node with a free DOF has all d free, on every rank: the matrix then has
// block size d and GAMG gets the rigid-body modes.
bool whole_nodes(const DofMap& dofs) {
  int whole = 1;
  for (std::size_t j = 0; j < dofs.n_nodes() && whole; ++j) {
    const std::int32_t free = dofs.first(j + 1) - dofs.first(j);
    whole = free == 0 || free == dofs.dim();
  }
  MPI_Allreduce(MPI_IN_PLACE, &whole, 1, MPI_INT, MPI_LAND, PETSC_COMM_WORLD);
  return whole != 0;
}

// Nonzeros per owned row, in the diagonal (owned columns) and off-diagonal parts: the free
// DOFs of the nodes that share an owned or ghost cell with the row's node.
void count_row_entries(const LocalMesh& local, const DofMap& dofs, std::vector<PetscInt>& diagonal,
                       std::vector<PetscInt>& off) {
  const std::size_t owned = local.n_owned_nodes;
  std::vector<std::vector<std::int32_t>> near(owned);
  for (const std::vector<CellBlock>* blocks : {&local.mesh.cells, &local.ghosts})
    for (const CellBlock& block : *blocks) {
      const int n = block.n_nodes_per_cell();
      for (std::size_t c = 0; c < block.n_cells(); ++c)
        for (int a = 0; a < n; ++a) {
          const auto i = static_cast<std::size_t>(block.cell(c)[a]);
          if (i < owned) near[i].insert(near[i].end(), block.cell(c), block.cell(c) + n);
        }
    }
  for (std::size_t i = 0; i < owned; ++i) {
    std::vector<std::int32_t>& nodes = near[i];
    std::sort(nodes.begin(), nodes.end());
    nodes.erase(std::unique(nodes.begin(), nodes.end()), nodes.end());
    PetscInt in = 0, out = 0;
    for (const std::int32_t j : nodes) {
      const PetscInt free = dofs.first(static_cast<std::size_t>(j) + 1) - dofs.first(static_cast<std::size_t>(j));
      (static_cast<std::size_t>(j) < owned ? in : out) += free;
    }
    for (std::int32_t k = dofs.first(i); k < dofs.first(i + 1); ++k) {
      diagonal.push_back(in);
      off.push_back(out);
    }
  }
}

}  // namespace

RankSystem::RankSystem(const LocalMesh& local, const DofMap& dofs) {
  ensure_petsc();
  // GAMG's Galerkin products P^T A P on several ranks: PETSc's default adds the rows of other
  // ranks in the order their messages arrive, which changed the bits from run to run;
  // "allatonce" adds them in a fixed order (on one rank the product is sequential anyway).
  int size = 1;
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  PetscBool set = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, "-matptap_via", &set);
  if (size > 1 && !set) PetscOptionsSetValue(nullptr, "-matptap_via", "allatonce");
  const int d = local.mesh.dim;
  const int bs = whole_nodes(dofs) ? d : 1;
  const PetscInt n_owned = local.n_owned_free, n_global = local.n_global_free;
  rows_.assign(local.global_free.begin(), local.global_free.end());
  std::vector<PetscInt> ghosts;
  for (std::size_t k = static_cast<std::size_t>(n_owned); k < rows_.size(); k += static_cast<std::size_t>(bs))
    ghosts.push_back(rows_[k] / bs);
  n_owned_ = n_owned;
  check_petsc(VecCreateGhostBlock(PETSC_COMM_WORLD, bs, n_owned, n_global, static_cast<PetscInt>(ghosts.size()), ghosts.data(), &step_),
        "vector set-up");
  for (Vec* v : {&gradient_[0], &gradient_[1], &rhs_}) {
    check_petsc(VecCreateMPI(PETSC_COMM_WORLD, n_owned, n_global, v), "vector set-up");
    check_petsc(VecSetBlockSize(*v, bs), "vector set-up");
  }

  std::vector<PetscInt> diagonal, off;
  count_row_entries(local, dofs, diagonal, off);
  check_petsc(MatCreate(PETSC_COMM_WORLD, &H_), "matrix set-up");
  check_petsc(MatSetSizes(H_, n_owned, n_owned, n_global, n_global), "matrix set-up");
  check_petsc(MatSetType(H_, MATAIJ), "matrix set-up");
  check_petsc(MatSetBlockSize(H_, bs), "matrix set-up");
  check_petsc(MatSeqAIJSetPreallocation(H_, 0, diagonal.data()), "matrix preallocation");
  check_petsc(MatMPIAIJSetPreallocation(H_, 0, diagonal.data(), 0, off.data()), "matrix preallocation");
  check_petsc(MatSetOption(H_, MAT_SYMMETRIC, PETSC_TRUE), "matrix set-up");
  check_petsc(MatSetOption(H_, MAT_SYMMETRY_ETERNAL, PETSC_TRUE), "matrix set-up");
  check_petsc(MatSetOption(H_, MAT_NO_OFF_PROC_ENTRIES, PETSC_TRUE), "matrix set-up");
  if (bs == d) {
    Vec coordinates = nullptr;
    check_petsc(VecCreateMPI(PETSC_COMM_WORLD, n_owned, n_global, &coordinates), "near-null space");
    check_petsc(VecSetBlockSize(coordinates, bs), "near-null space");
    PetscScalar* c = nullptr;
    check_petsc(VecGetArray(coordinates, &c), "near-null space");
    for (std::size_t j = 0; j < local.n_owned_nodes; ++j)
      if (dofs.first(j + 1) > dofs.first(j))
        for (int k = 0; k < d; ++k) c[dofs.first(j) + k] = local.mesh.x(k, static_cast<Eigen::Index>(j));
    VecRestoreArray(coordinates, &c);
    MatNullSpace rigid = nullptr;
    const PetscErrorCode e = MatNullSpaceCreateRigidBody(coordinates, &rigid);
    VecDestroy(&coordinates);
    check_petsc(e, "near-null space");
    check_petsc(MatSetNearNullSpace(H_, rigid), "near-null space");
    MatNullSpaceDestroy(&rigid);
  }

  check_petsc(KSPCreate(PETSC_COMM_WORLD, &ksp_), "solver set-up");
  check_petsc(KSPSetType(ksp_, KSPCG), "solver set-up");
  check_petsc(KSPSetNormType(ksp_, KSP_NORM_UNPRECONDITIONED), "solver set-up");
  PC pc = nullptr;
  check_petsc(KSPGetPC(ksp_, &pc), "solver set-up");
  check_petsc(PCSetType(pc, PCGAMG), "solver set-up");
  check_petsc(PCSetOptionsPrefix(pc, gamg_options_prefix()), "solver set-up");
  check_petsc(PCSetFromOptions(pc), "solver set-up");
}

RankSystem::~RankSystem() {
  PetscBool finalized = PETSC_TRUE;
  if (PetscFinalized(&finalized) != 0 || finalized) return;
  KSPDestroy(&ksp_);
  MatDestroy(&H_);
  for (Vec* v : {&gradient_[0], &gradient_[1], &step_, &rhs_}) VecDestroy(v);
}

double RankSystem::set_gradient(const Eigen::VectorXd& local, int slot) {
  Vec v = gradient_[slot];
  PetscScalar* a = nullptr;
  check_petsc(VecGetArray(v, &a), "gradient");
  std::copy(local.data(), local.data() + n_owned_, a);
  VecRestoreArray(v, &a);
  PetscReal norm = 0.0;
  check_petsc(VecNorm(v, NORM_2, &norm), "gradient norm");
  return norm;
}

void RankSystem::set_hessian(const Eigen::SparseMatrix<double>& local) {
  std::vector<PetscInt> columns;
  const int* outer = local.outerIndexPtr();
  const int* inner = local.innerIndexPtr();
  const double* values = local.valuePtr();
  // Column j of the symmetric local Hessian is row j: one call per owned row.
  for (PetscInt j = 0; j < n_owned_; ++j) {
    columns.clear();
    for (int k = outer[j]; k < outer[j + 1]; ++k) columns.push_back(rows_[static_cast<std::size_t>(inner[k])]);
    check_petsc(MatSetValues(H_, 1, &rows_[static_cast<std::size_t>(j)], static_cast<PetscInt>(columns.size()), columns.data(),
                       values + outer[j], INSERT_VALUES),
          "matrix update");
  }
  check_petsc(MatAssemblyBegin(H_, MAT_FINAL_ASSEMBLY), "matrix assembly");
  check_petsc(MatAssemblyEnd(H_, MAT_FINAL_ASSEMBLY), "matrix assembly");
}

bool RankSystem::solve(double rtol, Eigen::VectorXd& p, double& slope, bool& indefinite, std::string& why) {
  indefinite = false;
  iterations_ = 0;
  check_petsc(VecCopy(gradient_[0], rhs_), "solve");
  check_petsc(VecScale(rhs_, -1.0), "solve");
  check_petsc(VecSet(step_, 0.0), "solve");
  check_petsc(KSPSetOperators(ksp_, H_, H_), "solve");
  check_petsc(KSPSetTolerances(ksp_, rtol, 0.0, 1e300, 2000), "solve");
  const PetscErrorCode e = KSPSolve(ksp_, rhs_, step_);
  PetscInt its = 0;
  KSPGetIterationNumber(ksp_, &its);
  iterations_ = static_cast<int>(its);
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  KSPGetConvergedReason(ksp_, &reason);
  if (e != 0 || reason <= 0) {
    indefinite = reason == KSP_DIVERGED_INDEFINITE_MAT || reason == KSP_DIVERGED_INDEFINITE_PC;
    why = e != 0 ? "the preconditioner's set-up failed" : std::string("CG stopped (") + KSPConvergedReasons[reason] + ")";
    return false;
  }
  check_petsc(VecGhostUpdateBegin(step_, INSERT_VALUES, SCATTER_FORWARD), "step exchange");
  check_petsc(VecGhostUpdateEnd(step_, INSERT_VALUES, SCATTER_FORWARD), "step exchange");
  Vec form = nullptr;
  check_petsc(VecGhostGetLocalForm(step_, &form), "step");
  const PetscScalar* a = nullptr;
  check_petsc(VecGetArrayRead(form, &a), "step");
  p = Eigen::Map<const Eigen::VectorXd>(a, static_cast<Eigen::Index>(rows_.size()));
  VecRestoreArrayRead(form, &a);
  VecGhostRestoreLocalForm(step_, &form);
  check_petsc(VecDot(gradient_[0], step_, &slope), "step");
  return true;
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include "meshmorph/app/option_reader.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph::detail {

/// The case file's "solver" option of the Newton-based methods (default "auto").
inline LinearSolverKind read_solver(OptionReader& r) {
  std::string solver = "auto";
  r.read("solver", solver, {"auto", "cholesky", "iterative", "minres-jacobi", "petsc-gamg", "petsc-hypre"});
  if (solver == "cholesky") return LinearSolverKind::Cholesky;
  if (solver == "iterative") return LinearSolverKind::Iterative;
  if (solver == "minres-jacobi") return LinearSolverKind::MinresJacobi;
  if (solver == "petsc-gamg") return LinearSolverKind::PetscGamg;
  if (solver == "petsc-hypre") return LinearSolverKind::PetscHypre;
  return LinearSolverKind::Auto;
}

}  // namespace meshmorph::detail

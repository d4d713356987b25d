// SPDX-License-Identifier: MIT
#include "solve/detail/petsc_solver.h"

#include <gtest/gtest.h>

#include "solve/linear_solver_fixtures.h"

namespace meshmorph {
namespace {

constexpr LinearSolverKind k_petsc_kinds[] = {LinearSolverKind::PetscGamg, LinearSolverKind::PetscHypre};

// The coordinates of the unknowns' nodes of test::stiffness_matrix(3, n, …) and
// test::energy_hessian<3>(1, n): the interior nodes of the structured mesh, in node order.
std::vector<double> interior_coordinates(int n) {
  const Mesh mesh = structured_mesh(ElementType::Tetrahedron, 1, n);
  std::vector<double> x;
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j)
    if ((mesh.x.col(j).array() > 1e-12).all() && (mesh.x.col(j).array() < 1.0 - 1e-12).all())
      x.insert(x.end(), mesh.x.col(j).data(), mesh.x.col(j).data() + 3);
  return x;
}

LinearSolverOptions petsc_options(LinearSolverKind kind, int n) {
  LinearSolverOptions o;
  o.kind = kind;
  o.dim = 3;
  o.block_size = 3;
  o.threads = 1;
  o.coordinates = interior_coordinates(n);
  return o;
}

Eigen::VectorXd cholmod_solution(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b) {
  LinearSolverOptions o;
  o.kind = LinearSolverKind::Cholesky;
  auto solver = make_linear_solver(o, static_cast<std::size_t>(A.rows()));
  EXPECT_TRUE(solver->factorize(A));
  Eigen::VectorXd x;
  EXPECT_TRUE(solver->solve(b, x).ok);
  return x;
}

double relative_residual(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  return (b - A * x).norm() / b.norm();
}

// Elasticity and the morphing energy's Hessian on a 3D tetrahedral mesh: the requested true
// residual, reported as it is, and CHOLMOD's solution; with or without the coordinates.
TEST(PetscSolver, SolvesElasticSystemsToTheRequestedResidualAndAgreesWithCholmod) {
  const int n = 10;
  const std::pair<const char*, Eigen::SparseMatrix<double>> cases[] = {
      {"elasticity", test::stiffness_matrix(3, n, true, 1.0, 1.0)}, {"hessian", test::energy_hessian<3>(1, n)}};
  for (const auto& [name, A] : cases) {
    const Eigen::VectorXd b = test::random_vector(A.rows());
    const Eigen::VectorXd exact = cholmod_solution(A, b);
    for (const LinearSolverKind kind : k_petsc_kinds)
      for (const bool coordinates : {true, false}) {
        LinearSolverOptions o = petsc_options(kind, n);
        if (!coordinates) o.coordinates.clear();
        auto solver = make_linear_solver(o, static_cast<std::size_t>(A.rows()));
        SCOPED_TRACE(std::string(name) + " " + solver->name() + (coordinates ? " with coordinates" : ""));
        ASSERT_TRUE(solver->factorize(A));
        for (const double rtol : {1e-4, 1e-10}) {
          Eigen::VectorXd x;
          const LinearSolveStats stats = solver->solve(b, x, rtol);
          ASSERT_TRUE(stats.ok) << stats.message;
          EXPECT_FALSE(stats.indefinite);
          EXPECT_GT(stats.iterations, 0);
          EXPECT_LT(stats.iterations, 60);
          const double res = relative_residual(A, b, x);
          EXPECT_LE(res, rtol);
          EXPECT_NEAR(stats.relative_residual, res, 1e-6 * rtol);
          if (rtol == 1e-10) {
            EXPECT_LE((x - exact).norm(), 1e-7 * exact.norm());
          }
        }
      }
  }
}

TEST(PetscSolver, NamesItsKind) {
  EXPECT_EQ(make_linear_solver(petsc_options(LinearSolverKind::PetscGamg, 3), 24)->name(), "petsc-gamg");
  EXPECT_EQ(make_linear_solver(petsc_options(LinearSolverKind::PetscHypre, 3), 24)->name(), "petsc-hypre");
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::PetscGamg, 3, 10), LinearSolverKind::PetscGamg);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::PetscHypre, 3, 10'000'000), LinearSolverKind::PetscHypre);
}

// Newton's matrices change from step to step with the same pattern, once with a penalty-like
// jump of a few rows by 1e6; then the pattern changes. Every solve reaches the tolerance.
TEST(PetscSolver, RefactorizesChangedValuesAndPatterns) {
  const auto [A, B, C] = test::newton_matrices();
  const Eigen::SparseMatrix<double> D = test::energy_hessian<3>(1, 9);  // another pattern
  for (const LinearSolverKind kind : k_petsc_kinds) {
    auto solver = make_linear_solver(petsc_options(kind, 8), static_cast<std::size_t>(A.rows()));
    SCOPED_TRACE(solver->name());
    for (const Eigen::SparseMatrix<double>* M : std::initializer_list<const Eigen::SparseMatrix<double>*>{&A, &B, &C, &C, &A, &D, &A}) {
      ASSERT_TRUE(solver->factorize(*M));
      const Eigen::VectorXd b = test::random_vector(M->rows());
      Eigen::VectorXd x;
      const LinearSolveStats s = solver->solve(b, x, 1e-10);
      ASSERT_TRUE(s.ok) << s.message;
      EXPECT_LE(relative_residual(*M, b, x), 1e-10);
      EXPECT_LE((x - cholmod_solution(*M, b)).norm(), 1e-6 * x.norm());
    }
  }
}

// The old set-up preconditions CG on a new matrix of its pattern; without one, or for
// another pattern, solve_previous() says so.
TEST(PetscSolver, SolvePreviousUsesTheOldSetUpForANewMatrixOfTheSamePattern) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 8, true, 1.0, 1.0);
  const Eigen::SparseMatrix<double> B = 1.5 * A;
  const Eigen::VectorXd b = test::random_vector(A.rows());
  for (const LinearSolverKind kind : k_petsc_kinds) {
    auto solver = make_linear_solver(petsc_options(kind, 8), static_cast<std::size_t>(A.rows()));
    SCOPED_TRACE(solver->name());
    EXPECT_FALSE(solver->cheap_previous());
    Eigen::VectorXd x;
    EXPECT_FALSE(solver->solve_previous(B, b, x, 1e-10).ok);
    ASSERT_TRUE(solver->factorize(A));
    const LinearSolveStats s = solver->solve_previous(B, b, x, 1e-10);
    ASSERT_TRUE(s.ok) << s.message;
    EXPECT_LE(relative_residual(B, b, x), 1e-10);
    const Eigen::SparseMatrix<double> C = test::stiffness_matrix(3, 7, true, 1.0, 1.0);
    EXPECT_FALSE(solver->solve_previous(C, test::random_vector(C.rows()), x, 1e-10).ok);
  }
}

// From the solution as initial guess no iteration is needed; a zero right-hand side gives 0.
TEST(PetscSolver, StartsFromTheGivenInitialGuess) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 8, true, 1.0, 1.0);
  const Eigen::VectorXd b = test::random_vector(A.rows());
  for (const LinearSolverKind kind : k_petsc_kinds) {
    auto solver = make_linear_solver(petsc_options(kind, 8), static_cast<std::size_t>(A.rows()));
    ASSERT_TRUE(solver->factorize(A));
    test::solve_again_from_the_solution(*solver, b);
    Eigen::VectorXd zero = Eigen::VectorXd::Ones(A.rows());
    EXPECT_TRUE(solver->solve(Eigen::VectorXd::Zero(A.rows()), zero).ok);
    EXPECT_EQ(zero.norm(), 0.0);
  }
}

// A − σI with σ inside A's spectrum (positive diagonal) is not positive definite: the set-up
// or CG reports it, and the object still solves an SPD matrix afterwards.
TEST(PetscSolver, ReportsAnIndefiniteMatrix) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 8, true, 1.0, 1.0);
  Eigen::SparseMatrix<double> I(A.rows(), A.cols());
  I.setIdentity();
  Eigen::SparseMatrix<double> S = A - 0.5 * A.diagonal().mean() * I;
  S.makeCompressed();
  ASSERT_GT(S.diagonal().minCoeff(), 0.0);
  const Eigen::VectorXd b = test::random_vector(A.rows());
  for (const LinearSolverKind kind : k_petsc_kinds) {
    auto solver = make_linear_solver(petsc_options(kind, 8), static_cast<std::size_t>(A.rows()));
    SCOPED_TRACE(solver->name());
    if (solver->factorize(S)) {
      Eigen::VectorXd x;
      const LinearSolveStats s = solver->solve(b, x, 1e-10);
      EXPECT_FALSE(s.ok);
      EXPECT_FALSE(s.message.empty());
    }
    ASSERT_TRUE(solver->factorize(A));
    Eigen::VectorXd x;
    EXPECT_TRUE(solver->solve(b, x, 1e-10).ok);
  }
}

// Two solver objects on the same system give the same bits and the same iteration counts.
TEST(PetscSolver, IsDeterministic) {
  const Eigen::SparseMatrix<double> A = test::energy_hessian<3>(1, 9);
  const Eigen::VectorXd b = test::random_vector(A.rows());
  for (const LinearSolverKind kind : k_petsc_kinds) {
    Eigen::VectorXd x[2];
    int iterations[2];
    for (int k = 0; k < 2; ++k) {
      auto solver = make_linear_solver(petsc_options(kind, 9), static_cast<std::size_t>(A.rows()));
      ASSERT_TRUE(solver->factorize(A));
      const LinearSolveStats s = solver->solve(b, x[k], 1e-8);
      ASSERT_TRUE(s.ok) << s.message;
      iterations[k] = s.iterations;
    }
    EXPECT_EQ(iterations[0], iterations[1]);
    EXPECT_EQ((x[0] - x[1]).cwiseAbs().maxCoeff(), 0.0);
  }
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/solve/linear_solver.h"

#include <Eigen/SparseCholesky>
#include <gtest/gtest.h>

#include "meshmorph/energy/coarse_space.h"
#include "solve/detail/cg_amg_solver.h"
#include "solve/detail/cholmod_header.h"
#include "solve/detail/cholmod_solver.h"
#include "solve/linear_solver_fixtures.h"

namespace meshmorph {
namespace {

double relative_residual(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, const Eigen::VectorXd& x) {
  return (b - A * x).norm() / b.norm();
}

LinearSolverOptions options_for(LinearSolverKind kind, int dim) {
  LinearSolverOptions o;
  o.kind = kind;
  o.dim = dim;
  o.block_size = dim;
  o.threads = 1;
  return o;
}

// The iterative backend with a small coarsest level, so that these small test matrices get
// a hierarchy of several levels.
std::unique_ptr<LinearSolver> multilevel_solver(int dim, int coarse_size = 60) {
  const LinearSolverOptions o = options_for(LinearSolverKind::Iterative, dim);
  detail::AmgOptions amg = detail::amg_options(o);
  amg.coarse_size = coarse_size;
  return std::make_unique<detail::CgAmgSolver>(o, amg);
}

struct Case {
  const char* name;
  int dim;
  Eigen::SparseMatrix<double> A;
};

std::vector<Case> spd_cases() {
  std::vector<Case> cases;
  cases.push_back({"laplace-2d", 2, test::stiffness_matrix(2, 24, false)});
  cases.push_back({"elasticity-2d", 2, test::stiffness_matrix(2, 24, true, 10.0, 1.0)});
  cases.push_back({"laplace-3d", 3, test::stiffness_matrix(3, 8, false)});
  cases.push_back({"elasticity-3d", 3, test::stiffness_matrix(3, 8, true, 1.0, 1.0)});
  cases.push_back({"hessian-2d-p2", 2, test::energy_hessian<2>(2, 10)});
  cases.push_back({"hessian-3d-p1", 3, test::energy_hessian<3>(1, 8)});
  return cases;
}

TEST(LinearSolver, BothBackendsSolveSpdSystemsToTheRequestedResidual) {
  for (const Case& c : spd_cases()) {
    SCOPED_TRACE(c.name);
    const Eigen::VectorXd b = test::random_vector(c.A.rows());
    const auto n = static_cast<std::size_t>(c.A.rows());
    std::vector<std::unique_ptr<LinearSolver>> solvers;
    solvers.push_back(make_linear_solver(options_for(LinearSolverKind::Cholesky, c.dim), n));
    solvers.push_back(make_linear_solver(options_for(LinearSolverKind::Iterative, c.dim), n));
    solvers.push_back(multilevel_solver(c.dim));
    for (const auto& solver : solvers) {
      SCOPED_TRACE(solver->name());
      ASSERT_TRUE(solver->factorize(c.A));
      const bool direct = solver->name() == "cholmod";
      for (double rtol : {1e-4, 1e-10}) {
        Eigen::VectorXd x;
        const LinearSolveStats stats = solver->solve(b, x, rtol);
        EXPECT_TRUE(stats.ok) << stats.message;
        const double res = relative_residual(c.A, b, x);
        EXPECT_LE(res, direct ? 1e-12 : rtol);
        if (!direct) {
          EXPECT_NEAR(stats.relative_residual, res, 1e-3 * rtol);
          EXPECT_GT(stats.iterations, 0);
          EXPECT_LT(stats.iterations, 40);
        }
      }
    }
  }
}

TEST(LinearSolver, IterativeSolveFromTheSolutionTakesNoIteration) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(2, 16, true);
  const Eigen::VectorXd b = test::random_vector(A.rows());
  auto solver = multilevel_solver(2);
  ASSERT_TRUE(solver->factorize(A));
  EXPECT_LE(test::solve_again_from_the_solution(*solver, b).relative_residual, 1e-10);
}

TEST(LinearSolver, SolvePreviousUsesTheOldSetUpForANewMatrixOfTheSamePattern) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 8, true, 1.0, 1.0);
  const Eigen::SparseMatrix<double> B = 1.5 * A;  // same pattern, other values
  const Eigen::VectorXd b = test::random_vector(A.rows());
  std::vector<std::unique_ptr<LinearSolver>> solvers;
  solvers.push_back(make_linear_solver(options_for(LinearSolverKind::Cholesky, 3), static_cast<std::size_t>(A.rows())));
  solvers.push_back(multilevel_solver(3));
  for (const auto& solver : solvers) {
    SCOPED_TRACE(solver->name());
    Eigen::VectorXd x;
    EXPECT_FALSE(solver->solve_previous(B, b, x, 1e-10).ok);  // nothing to reuse yet
    ASSERT_TRUE(solver->factorize(A));
    const LinearSolveStats s = solver->solve_previous(B, b, x, 1e-10);
    ASSERT_TRUE(s.ok) << s.message;
    EXPECT_LE(relative_residual(B, b, x), 1e-10);  // CG on the new matrix, the old set-up preconditioning
    const Eigen::SparseMatrix<double> C = test::stiffness_matrix(3, 7, true, 1.0, 1.0);  // other pattern
    EXPECT_FALSE(solver->solve_previous(C, test::random_vector(C.rows()), x, 1e-10).ok);
  }
}

// A Newton solve may stop once ½ rᵀM⁻¹r, standing in for the decrease ½ rᵀA⁻¹r its residual
// leaves undone, is small: long before the relative residual, and leaving about that undone.
TEST(LinearSolver, SolvesStopOnceTheDecreaseLeftInTheResidualIsSmall) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 8, true, 1.0, 1.0);
  const Eigen::SparseMatrix<double> B = 1.2 * A;
  const Eigen::VectorXd b = test::random_vector(A.rows());
  const Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> exact(B);
  const double full = 0.5 * b.dot(exact.solve(b));  // the decrease of the exact solution
  std::vector<std::unique_ptr<LinearSolver>> solvers;
  solvers.push_back(make_linear_solver(options_for(LinearSolverKind::Cholesky, 3), static_cast<std::size_t>(A.rows())));
  solvers.push_back(multilevel_solver(3));
  for (const auto& solver : solvers) {
    SCOPED_TRACE(solver->name());
    ASSERT_TRUE(solver->factorize(A));
    for (double fraction : {1e-4, 1e-8}) {
      const double decrease = fraction * full;
      Eigen::VectorXd tight, loose;
      const LinearSolveStats t = solver->solve_previous(B, b, tight, 1e-12);
      const LinearSolveStats l = solver->solve_previous(B, b, loose, 1e-12, decrease);
      ASSERT_TRUE(t.ok) << t.message;
      ASSERT_TRUE(l.ok) << l.message;
      EXPECT_GE(l.iterations, 1);
      EXPECT_LT(l.iterations, t.iterations);
      const Eigen::VectorXd r = b - B * loose;
      const double left = 0.5 * r.dot(exact.solve(r));
      EXPECT_LE(left, 4.0 * decrease);
      EXPECT_NEAR(0.5 * b.dot(loose) + left, full, 1e-9 * full);
    }
  }
}

TEST(LinearSolver, IterativeSolvesStayAccurateWhenTheHierarchyIsReused) {
  // Newton's matrices change from step to step with the same pattern: the solver keeps the
  // coarse levels and must still reach the tolerance, also for a penalty-like jump of a few
  // rows by 1e6 (which makes it rebuild once CG slows down).
  const auto [A, B, C] = test::newton_matrices();
  auto solver = multilevel_solver(3);
  const Eigen::VectorXd b = test::random_vector(A.rows());
  for (const Eigen::SparseMatrix<double>* M : std::vector<const Eigen::SparseMatrix<double>*>{&A, &B, &C, &C, &A}) {
    ASSERT_TRUE(solver->factorize(*M));
    Eigen::VectorXd x;
    const LinearSolveStats s = solver->solve(b, x, 1e-10);
    ASSERT_TRUE(s.ok) << s.message;
    EXPECT_LE(relative_residual(*M, b, x), 1e-10);
    EXPECT_LT(s.iterations, 200);
  }
}

// Mesh independence of smoothed aggregation: from n = 8 to n = 16 cells per side in 3D
// (8x the unknowns, one more level) the CG iteration count at most doubles.
TEST(LinearSolver, IterativeIterationsStayBoundedUnderRefinement) {
  for (int kind = 0; kind < 3; ++kind) {
    SCOPED_TRACE(kind);
    int iterations[2] = {0, 0};
    int levels[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      const int n = 8 << k;
      const Eigen::SparseMatrix<double> A =
          kind == 2 ? test::energy_hessian<3>(1, n) : test::stiffness_matrix(3, n, kind == 1);
      const Eigen::VectorXd b = test::random_vector(A.rows());
      const LinearSolverOptions o = options_for(LinearSolverKind::Iterative, 3);
      detail::AmgOptions amg = detail::amg_options(o);
      amg.coarse_size = 200;
      detail::CgAmgSolver solver(o, amg);
      ASSERT_TRUE(solver.factorize(A));
      Eigen::VectorXd x;
      const LinearSolveStats stats = solver.solve(b, x, 1e-8);
      ASSERT_TRUE(stats.ok) << stats.message;
      EXPECT_LE(relative_residual(A, b, x), 1e-8);
      iterations[k] = stats.iterations;
      levels[k] = solver.hierarchy().n_levels();
    }
    EXPECT_GT(levels[1], levels[0]);
    EXPECT_GE(levels[0], 2);
    EXPECT_LE(iterations[1], 2 * iterations[0]) << iterations[0] << " → " << iterations[1];
    EXPECT_LE(iterations[1], 30);
  }
}

// High-order Hessians with the vertex hats as the first coarse level: that level is the
// linear mesh's (d unknowns per kept vertex), CG converges in iterations that stay bounded
// as the mesh is refined, and a reused hierarchy still solves a changed matrix.
template <int d>
void vertex_hats_precondition(int order, int n, int (&iterations)[2], int k) {
  const Mesh mesh = structured_mesh(d == 2 ? ElementType::Triangle : ElementType::Tetrahedron, order, n);
  const DofMap dofs = DofMap::fixing_boundary(mesh, build_topology(mesh));
  const Eigen::SparseMatrix<double> R = vertex_hats<d>(mesh, dofs);
  const Eigen::SparseMatrix<double> A = test::energy_hessian<d>(order, n);  // the same mesh and DofMap
  ASSERT_EQ(A.rows(), R.rows());
  const Eigen::VectorXd b = test::random_vector(A.rows());
  const LinearSolverOptions o = options_for(LinearSolverKind::Iterative, d);
  detail::AmgOptions amg = detail::amg_options(o);
  amg.coarse_size = 60;
  detail::CgAmgSolver solver(o, amg);
  solver.set_coarse_space(R);
  ASSERT_TRUE(solver.factorize(A));
  ASSERT_GE(solver.hierarchy().n_levels(), 2);
  EXPECT_EQ(solver.hierarchy().rows(1), R.cols());
  Eigen::VectorXd x;
  const LinearSolveStats stats = solver.solve(b, x, 1e-8);
  ASSERT_TRUE(stats.ok) << stats.message;
  EXPECT_LE(relative_residual(A, b, x), 1e-8);
  iterations[k] = stats.iterations;
  Eigen::SparseMatrix<double> A2 = A;
  A2.diagonal() *= 1.5;
  Eigen::VectorXd x2;
  const LinearSolveStats again = solver.solve_previous(A2, b, x2, 1e-8);
  ASSERT_TRUE(again.ok) << again.message;
  EXPECT_LE(relative_residual(A2, b, x2), 1e-8);
}

TEST(LinearSolver, VertexHatsAreTheFirstCoarseLevelOfHighOrderSystems) {
  for (int order : {2, 3}) {
    SCOPED_TRACE(order);
    int it2[2] = {0, 0}, it3[2] = {0, 0};
    for (int k = 0; k < 2; ++k) {
      vertex_hats_precondition<2>(order, 6 << k, it2, k);
      vertex_hats_precondition<3>(order, 3 << k, it3, k);
    }
    // Measured: P2 8 → 9 (2D) and 9 → 10 (3D), P3 17 → 21 and 16 → 26 (3D: one level more).
    EXPECT_LE(it2[1], 2 * it2[0]);
    EXPECT_LE(it3[1], 2 * it3[0]);
    EXPECT_LE(std::max(it2[1], it3[1]), 40);
  }
}

TEST(LinearSolver, CholeskyReusesItsAnalysisWhileThePatternIsUnchanged) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 6, true);
  const Eigen::VectorXd b = test::random_vector(A.rows());
  detail::CholmodSolver solver;
  ASSERT_TRUE(solver.factorize(A));
  EXPECT_EQ(solver.n_analyses(), 1);
  // New values on the same pattern: same analysis, the solution of the new matrix.
  Eigen::SparseMatrix<double> B = A;
  for (int k = 0; k < B.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(B, k); it; ++it)
      if (it.row() == it.col()) it.valueRef() *= 3.0;
  ASSERT_TRUE(solver.factorize(B));
  EXPECT_EQ(solver.n_analyses(), 1);
  Eigen::VectorXd x;
  ASSERT_TRUE(solver.solve(b, x).ok);
  EXPECT_LE(relative_residual(B, b, x), 1e-12);
  // Another pattern: analysed again.
  const Eigen::SparseMatrix<double> C = test::stiffness_matrix(3, 6, false);
  ASSERT_TRUE(solver.factorize(C));
  EXPECT_EQ(solver.n_analyses(), 2);
  ASSERT_TRUE(solver.solve(test::random_vector(C.rows()), x).ok);
  EXPECT_LE(relative_residual(C, test::random_vector(C.rows()), x), 1e-12);
}

// CHOLMOD's own analysis of A, with its default amalgamation: the number of supernodes.
int default_supernodes(const Eigen::SparseMatrix<double>& A) {
  cholmod_common c;
  cholmod_start(&c);
  c.supernodal = CHOLMOD_SUPERNODAL;
  cholmod_sparse S = detail::cholmod_header(detail::view_of(A));
  cholmod_factor* L = cholmod_analyze(&S, &c);
  const int n_super = L && L->is_super ? static_cast<int>(L->nsuper) : -1;
  if (L) cholmod_free_factor(&L, &c);
  cholmod_finish(&c);
  return n_super;
}

// Narrow supernodes (2D Hessians) are merged further than CHOLMOD's default; wide ones (3D)
// keep it. Either way the factor solves to rounding, directly and as solve_previous's
// preconditioner.
TEST(LinearSolver, CholeskyMergesNarrowSupernodesOnly) {
  const Eigen::SparseMatrix<double> A2 = test::stiffness_matrix(2, 40, true, 10.0, 1.0);
  const Eigen::SparseMatrix<double> A3 = test::stiffness_matrix(3, 12, true, 1.0, 1.0);
  const int default2 = default_supernodes(A2), default3 = default_supernodes(A3);
  ASSERT_LT(A2.rows(), 15 * default2) << "the 2D case should have narrow supernodes by default";
  ASSERT_GE(A3.rows(), 15 * default3) << "the 3D case should have wide supernodes by default";
  for (const auto* A : {&A2, &A3}) {
    detail::CholmodSolver solver;
    ASSERT_TRUE(solver.factorize(*A));
    const Eigen::VectorXd b = test::random_vector(A->rows());
    Eigen::VectorXd x;
    ASSERT_TRUE(solver.solve(b, x).ok);
    EXPECT_LE(relative_residual(*A, b, x), 1e-12);
    x.setZero();
    const LinearSolveStats s = solver.solve_previous(*A, b, x, 1e-10);
    ASSERT_TRUE(s.ok) << s.message;
    EXPECT_LE(relative_residual(*A, b, x), 1e-10);
    if (A == &A2) {
      EXPECT_LE(solver.n_supernodes(), default2 * 3 / 4);
    } else {
      EXPECT_EQ(solver.n_supernodes(), default3);
    }
  }
}

// A − σI with σ between the smallest and the largest eigenvalue of A: indefinite, with a
// positive diagonal.
Eigen::SparseMatrix<double> shifted(const Eigen::SparseMatrix<double>& A, double sigma) {
  Eigen::SparseMatrix<double> I(A.rows(), A.cols());
  I.setIdentity();
  Eigen::SparseMatrix<double> S = A - sigma * I;
  S.makeCompressed();
  return S;
}

// Paper 003's baseline: Jacobi-preconditioned MINRES reaches the requested true residual on
// every SPD case, from zero and from a given initial guess, and reports a matrix with a
// non-positive diagonal entry at factorize().
TEST(LinearSolver, MinresJacobiSolvesSpdSystemsToTheRequestedResidual) {
  for (const Case& c : spd_cases()) {
    SCOPED_TRACE(c.name);
    const Eigen::VectorXd b = test::random_vector(c.A.rows());
    LinearSolverOptions o = options_for(LinearSolverKind::MinresJacobi, c.dim);
    o.max_iterations = 20000;
    auto solver = make_linear_solver(o, static_cast<std::size_t>(c.A.rows()));
    ASSERT_EQ(solver->name(), "minres-jacobi");
    ASSERT_TRUE(solver->factorize(c.A));
    int iterations_loose = 0;
    for (double rtol : {1e-4, 1e-10}) {
      Eigen::VectorXd x;
      const LinearSolveStats stats = solver->solve(b, x, rtol);
      EXPECT_TRUE(stats.ok) << stats.message;
      const double res = relative_residual(c.A, b, x);
      EXPECT_LE(res, rtol);
      EXPECT_NEAR(stats.relative_residual, res, 1e-6 * rtol);
      EXPECT_GT(stats.iterations, iterations_loose);
      iterations_loose = stats.iterations;
    }
    // From the exact solution of a perturbed right-hand side: few iterations.
    Eigen::VectorXd x;
    ASSERT_TRUE(solver->solve(b, x, 1e-12).ok);
    const Eigen::VectorXd b2 = b + 1e-6 * test::random_vector(c.A.rows(), 7);
    const LinearSolveStats warm = solver->solve(b2, x, 1e-4);
    EXPECT_TRUE(warm.ok);
    EXPECT_LE(relative_residual(c.A, b2, x), 1e-4);
    EXPECT_LT(warm.iterations, iterations_loose / 2);
  }
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(2, 12, true);
  auto solver = make_linear_solver(options_for(LinearSolverKind::MinresJacobi, 2), static_cast<std::size_t>(A.rows()));
  EXPECT_FALSE(solver->factorize(shifted(A, 2.0 * A.diagonal().maxCoeff())));
  Eigen::VectorXd x;
  EXPECT_FALSE(solver->solve(test::random_vector(A.rows()), x).ok);
}

// With too few iterations allowed the solve says so instead of returning a poor direction.
TEST(LinearSolver, MinresJacobiReportsAnUnreachedTolerance) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 8, true, 1.0, 1.0);
  LinearSolverOptions o = options_for(LinearSolverKind::MinresJacobi, 3);
  o.max_iterations = 5;
  auto solver = make_linear_solver(o, static_cast<std::size_t>(A.rows()));
  ASSERT_TRUE(solver->factorize(A));
  Eigen::VectorXd x;
  const LinearSolveStats stats = solver->solve(test::random_vector(A.rows()), x, 1e-10);
  EXPECT_FALSE(stats.ok);
  EXPECT_EQ(stats.iterations, 5);
  EXPECT_NE(stats.message.find("did not reach"), std::string::npos) << stats.message;
}

TEST(LinearSolver, CholeskyReportsAnIndefiniteMatrixAndStaysUsable) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(2, 12, true);
  const double mean_diagonal = A.diagonal().mean();
  detail::CholmodSolver solver;
  EXPECT_FALSE(solver.factorize(shifted(A, 0.5 * mean_diagonal)));
  Eigen::VectorXd x;
  EXPECT_FALSE(solver.solve(test::random_vector(A.rows()), x).ok);
  ASSERT_TRUE(solver.factorize(A));
  EXPECT_EQ(solver.n_analyses(), 1);
  const Eigen::VectorXd b = test::random_vector(A.rows());
  ASSERT_TRUE(solver.solve(b, x).ok);
  EXPECT_LE(relative_residual(A, b, x), 1e-12);
}

TEST(LinearSolver, IterativeReportsAnIndefiniteMatrix) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(2, 24, true);
  const Eigen::VectorXd b = test::random_vector(A.rows());
  // Indefinite everywhere (σ = half the mean diagonal) and, separately, through one pair
  // of unknowns only (a_ij = 3√(a_ii a_jj): e_i − e_j has negative curvature).
  Eigen::SparseMatrix<double> local = A;
  const int i = 40, j = 41;
  local.coeffRef(i, j) = local.coeffRef(j, i) = 3.0 * std::sqrt(A.coeff(i, i) * A.coeff(j, j));
  local.makeCompressed();
  for (const auto& M : {shifted(A, 0.5 * A.diagonal().mean()), local}) {
    auto solver = multilevel_solver(2);
    Eigen::VectorXd x;
    if (solver->factorize(M)) {
      const LinearSolveStats stats = solver->solve(b, x, 1e-10);
      EXPECT_FALSE(stats.ok);
      EXPECT_NE(stats.message.find("not positive definite"), std::string::npos) << stats.message;
    } else {
      EXPECT_FALSE(solver->solve(b, x).ok);
    }
  }
}

// CG's own check: the hierarchy is built for A, then the values change in place to
// A − σI (same pattern); CG meets pᵀ(A − σI)p ≤ 0 and stops.
TEST(LinearSolver, IterativeStopsAtNegativeCurvature) {
  const Eigen::SparseMatrix<double> A = test::stiffness_matrix(3, 10, true);
  const Eigen::SparseMatrix<double> S = shifted(A, 0.5 * A.diagonal().mean());
  ASSERT_EQ(S.nonZeros(), A.nonZeros());
  Eigen::SparseMatrix<double> M = A;
  auto solver = multilevel_solver(3);
  ASSERT_TRUE(solver->factorize(M));
  std::copy(S.valuePtr(), S.valuePtr() + S.nonZeros(), M.valuePtr());
  Eigen::VectorXd x;
  const LinearSolveStats stats = solver->solve(test::random_vector(A.rows()), x, 1e-10);
  EXPECT_FALSE(stats.ok);
  EXPECT_EQ(stats.message, "matrix not positive definite");
  EXPECT_GT(stats.iterations, 0);
}

TEST(LinearSolver, AutoPicksCholeskyIn2DAndForSmall3DSystems) {
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 2, 5'000'000), LinearSolverKind::Cholesky);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 3, 3'000), LinearSolverKind::Cholesky);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 3, 20'000), LinearSolverKind::Cholesky);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 3, 40'000), LinearSolverKind::Iterative);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Iterative, 2, 10), LinearSolverKind::Iterative);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Cholesky, 3, 10'000'000), LinearSolverKind::Cholesky);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::MinresJacobi, 3, 10), LinearSolverKind::MinresJacobi);
  LinearSolverOptions o;
  o.dim = 3;
  EXPECT_EQ(make_linear_solver(o, 1000)->name(), "cholmod");
  EXPECT_EQ(make_linear_solver(o, 1'000'000)->name(), "cg-amg");
}

TEST(LinearSolver, AutoKeepsCholeskyLongerForHighOrderCells) {
  // P1 and P2 tetrahedra (4, 10 nodes): CG-AMG past 30k unknowns.
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 3, 40'000, 4), LinearSolverKind::Iterative);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 3, 40'000, 10), LinearSolverKind::Iterative);
  // P3 tetrahedra (20), P2 hexahedra (27): Cholesky up to 300k, CG-AMG beyond.
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 3, 115'000, 20), LinearSolverKind::Cholesky);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 3, 250'000, 27), LinearSolverKind::Cholesky);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Auto, 3, 400'000, 27), LinearSolverKind::Iterative);
  EXPECT_EQ(resolve_linear_solver(LinearSolverKind::Iterative, 3, 50'000, 27), LinearSolverKind::Iterative);
  LinearSolverOptions o;
  o.dim = 3;
  o.cell_nodes = 64;
  EXPECT_EQ(make_linear_solver(o, 200'000)->name(), "cholmod");
}

}  // namespace
}  // namespace meshmorph

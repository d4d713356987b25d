// SPDX-License-Identifier: MIT
#include "meshmorph/solve/newton.h"

#include <cmath>
#include <limits>

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

namespace meshmorph {
namespace {

// A dense LLᵀ behind the LinearSolver interface, so these tests depend on Newton alone.
class DenseSolver final : public LinearSolver {
 public:
  bool factorize(const Eigen::SparseMatrix<double>& A) override {
    llt_.compute(Eigen::MatrixXd(A));
    ++factorizations;
    return llt_.info() == Eigen::Success;
  }
  LinearSolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double rtol, double /*decrease*/) override {
    x = llt_.solve(b);
    LinearSolveStats s;
    s.ok = true;
    if (loose_factor != 1.0) {  // an iterative solver whose loose solutions are poor steps
      s.iterations = 1;
      if (rtol > 1e-6)
        x *= loose_factor;
      else
        ++tight_solves;
    }
    return s;
  }
  // As the real backends: A solved to rtol, preconditioned by the old factor (here by
  // iterative refinement), or not at all within a few corrections.
  LinearSolveStats solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                  double rtol, double /*decrease*/) override {
    LinearSolveStats s;
    if (llt_.info() != Eigen::Success || llt_.rows() != A.rows()) return s;
    ++reuses;
    if (x.size() != b.size()) x.setZero(b.size());
    for (Eigen::VectorXd r = b - A * x; s.iterations < 12; r = b - A * x) {
      if (r.norm() <= rtol * b.norm()) {
        s.ok = true;
        break;
      }
      x += llt_.solve(r);
      ++s.iterations;
    }
    return s;
  }
  bool cheap_previous() const override { return true; }
  std::string name() const override { return "dense"; }
  int factorizations = 0, reuses = 0;
  double loose_factor = 1.0;
  int tight_solves = 0;

 private:
  Eigen::LLT<Eigen::MatrixXd> llt_;
};

// f(x) = Σ_i (x_i² − 1)² / 4 + ½ s ‖x − c‖², a non-convex function whose Hessian x_i²·3 − 1 + s
// is indefinite near 0; +∞ for x_0 ≤ barrier (a stand-in for an inverted element).
class Quartic final : public NewtonProblem {
 public:
  Quartic(Eigen::VectorXd x0, double s, Eigen::VectorXd c, double barrier)
      : x(std::move(x0)), s_(s), c_(std::move(c)), barrier_(barrier) {}
  double f(const Eigen::VectorXd& y) const {
    if (y[0] <= barrier_) return std::numeric_limits<double>::infinity();
    return offset + offset * noise * std::sin(1e7 * y.sum()) + 0.25 * (y.array().square() - 1.0).square().sum() +
           0.5 * s_ * (y - c_).squaredNorm();
  }
  void evaluate(HessianMode mode, Assembly& out) override {
    ++evaluations;
    if (mode == HessianMode::Exact) ++exact_evaluations;
    out.value = f(x);
    out.gradient = gradient();
    Eigen::VectorXd diag = (3.0 * x.array().square() - 1.0 + s_).matrix();
    if (mode == HessianMode::Projected) diag = diag.cwiseMax(0.0);
    diag *= hessian_scale;
    out.hessian.resize(x.size(), x.size());
    out.hessian.setIdentity();
    for (Eigen::Index i = 0; i < x.size(); ++i) out.hessian.coeffRef(i, i) = diag[i];
  }
  bool evaluate_gradient(Assembly& out) override {
    if (!gradient_alone) return false;
    ++gradient_evaluations;
    out.value = f(x);
    out.gradient = gradient();
    return true;
  }
  Eigen::VectorXd gradient() const { return (x.array().cube() - x.array()).matrix() + s_ * (x - c_); }
  // ½ gᵀH⁻¹g with the exact Hessian at x.
  double decrement() const {
    const Eigen::ArrayXd h = 3.0 * x.array().square() - 1.0 + s_;
    return 0.5 * (gradient().array().square() / h).sum();
  }
  double trial_value(const Eigen::VectorXd& p, double alpha) override { return f(x + alpha * p); }
  void accept(const Eigen::VectorXd& p, double alpha) override {
    EXPECT_TRUE(std::isfinite(f(x + alpha * p)));
    x += alpha * p;
  }
  Eigen::VectorXd x;
  int evaluations = 0, exact_evaluations = 0, gradient_evaluations = 0;
  bool gradient_alone = false;  // evaluate_gradient() answers
  // A constant that the energy carries (a penalised, weighted energy's large part) and the
  // relative round-off of its evaluation, as a deterministic pseudo-noise.
  double offset = 0.0, noise = 0.0;
  // A Hessian off by this factor (a stand-in for a solve that lost digits): linear convergence.
  double hessian_scale = 1.0;

 private:
  double s_;
  Eigen::VectorXd c_;
  double barrier_;
};

// s = 2 outweighs the quartic's negative curvature: strongly convex, no barrier in reach.
Quartic convex_quartic() {
  Eigen::VectorXd x0(3), c(3);
  x0 << 2.0, -1.5, 0.7;
  c << 1.5, -1.2, 1.1;
  return Quartic(x0, 2.0, c, -10.0);
}

TEST(Newton, ConvergesQuadraticallyOnAStronglyConvexProblem) {
  Quartic q = convex_quartic();
  DenseSolver solver;
  NewtonOptions o;
  o.decrement_tolerance = 1e-28;
  const NewtonStats s = newton(q, solver, o);
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_LT(q.gradient().norm(), 1e-13);
  EXPECT_LE(s.iterations, 8);  // quadratic convergence: a handful of steps
}

// Where the energy is 1e6 and evaluated to a few ulps, no line search can measure a decrease
// below ~1e-9. With steps that converge only linearly Newton would cut them on round-off
// until the line search gave up; it stops there, converged.
TEST(Newton, StopsWhereTheEnergyCannotResolveTheDecrement) {
  Quartic q = convex_quartic();
  q.offset = 1e6;
  q.noise = 4.0 * std::numeric_limits<double>::epsilon();
  q.hessian_scale = 3.0;
  DenseSolver solver;
  NewtonOptions o;
  o.decrement_tolerance = 1e-28;
  const NewtonStats s = newton(q, solver, o);
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_LE(s.decrement, 16.0 * std::numeric_limits<double>::epsilon() * (q.offset + 1.0));
  EXPECT_LT(q.gradient().norm(), 1e-3);
}

TEST(Newton, StepsAndConfirmsConvergenceWithThePreviousFactorization) {
  Quartic q = convex_quartic();
  DenseSolver solver;
  NewtonOptions o;
  o.decrement_tolerance = 1e-20;
  NewtonMemory memory;
  const NewtonStats first = newton(q, solver, o, &memory);
  ASSERT_TRUE(first.converged) << first.message;
  // Without the reuse every step and the last iterate's test cost a factorization each; with
  // it the old factor preconditions some steps and the test.
  EXPECT_LT(solver.factorizations, first.iterations);
  EXPECT_GT(solver.reuses, 0);
  EXPECT_TRUE(memory.reusable);
  // A second call on the solved problem: no factorization, no step.
  const int factorizations = solver.factorizations;
  const NewtonStats second = newton(q, solver, o, &memory);
  EXPECT_TRUE(second.converged);
  EXPECT_EQ(second.iterations, 0);
  EXPECT_EQ(solver.factorizations, factorizations);
  EXPECT_EQ(second.linear_solves, 1);
  // The estimate never replaces the test: the gradient is still at the tolerance's level.
  EXPECT_LT(q.gradient().norm(), 1e-9);
}

// After a full step the test is first taken from the gradient alone and the factorization of
// the iterate before the step: the iteration ends at the same iterate as with the full test,
// without the Hessian there, and the decrement there is within the tolerance.
TEST(Newton, TestsAfterAFullStepFromTheGradientAndTheEarlierFactorization) {
  Quartic full = convex_quartic(), cheap = convex_quartic();
  cheap.gradient_alone = true;
  NewtonOptions o;
  o.decrement_tolerance = 1e-20;
  DenseSolver s1, s2;
  const NewtonStats a = newton(full, s1, o), b = newton(cheap, s2, o);
  ASSERT_TRUE(a.converged && b.converged) << a.message << b.message;
  EXPECT_EQ(cheap.x, full.x);
  EXPECT_EQ(b.iterations, a.iterations);
  EXPECT_EQ(cheap.gradient_evaluations, 1);
  EXPECT_EQ(cheap.evaluations, full.evaluations - 1);
  EXPECT_LE(cheap.decrement(), o.decrement_tolerance);
  EXPECT_LE(b.decrement, o.decrement_tolerance / 32.0);
}

// A Hessian off by a factor 3 gives steps of a third of Newton's, all taken in full: the
// decrement falls by only (2/3)² per step. The test from the gradient is tried after the
// first step, where it fails, and then only where the quadratic model predicts a pass.
TEST(Newton, StopsTestingFromTheGradientWhereItFails) {
  Quartic q = convex_quartic();
  q.gradient_alone = true;
  q.hessian_scale = 3.0;
  DenseSolver solver;
  NewtonOptions o;
  o.decrement_tolerance = 1e-12;
  NewtonMemory memory;
  const NewtonStats s = newton(q, solver, o, &memory);
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_GT(s.iterations, 10);
  EXPECT_GE(q.gradient_evaluations, 1);
  EXPECT_LE(q.gradient_evaluations, 2);
  EXPECT_LE(q.decrement() / q.hessian_scale, o.decrement_tolerance);  // in Newton's own Hessian
  EXPECT_TRUE(memory.test_from_gradient);
}

// A problem changed by less than the decrement test sees (its minimiser shifted by ~5e-7)
// takes no step by default; min_iterations = 1 takes the step that answers the change, and
// that Newton step lands on the new minimiser.
TEST(Newton, MinIterationsTakesTheStepBelowTheTest) {
  Eigen::VectorXd x0(3), c(3);
  x0 << 1.2, -0.9, 1.05;
  c = x0;
  Quartic solved(x0, 2.0, c, -10.0);
  DenseSolver solver;
  NewtonOptions o;
  o.decrement_tolerance = 1e-24;  // to the energy's resolution
  ASSERT_TRUE(newton(solved, solver, o).converged);
  const Eigen::VectorXd minimiser = solved.x;
  Eigen::VectorXd nudged = c;
  nudged[1] += 1e-6;  // a gradient of 2e-6: a decrement of ~5e-13
  o.decrement_tolerance = 1e-12;
  for (int min_iterations : {0, 1}) {
    Quartic q(minimiser, 2.0, nudged, -10.0);
    o.min_iterations = min_iterations;
    const NewtonStats s = newton(q, solver, o);
    ASSERT_TRUE(s.converged) << s.message;
    EXPECT_EQ(s.iterations, min_iterations);
    if (min_iterations == 0) {
      EXPECT_EQ(q.x, minimiser);
      EXPECT_GT(q.gradient().norm(), 1e-6);
    } else {
      EXPECT_LT(q.gradient().norm(), 1e-10);
    }
  }
}

TEST(Newton, SolvesOnWhenAnInexactStepIsCutShort) {
  // Loose solves return 30 times the Newton step: Armijo cuts it to α = 1/16 and, taken as
  // it is, Newton would converge linearly (error ×0.875 per step). Solved on to linear_rtol,
  // every step is the Newton step.
  Quartic q = convex_quartic();
  DenseSolver solver;
  solver.loose_factor = 30.0;
  NewtonOptions o;
  o.forcing = 1e-2;
  o.decrement_tolerance = 1e-28;
  const NewtonStats s = newton(q, solver, o);
  ASSERT_TRUE(s.converged) << s.message;
  EXPECT_LT(q.gradient().norm(), 1e-13);
  EXPECT_LE(s.iterations, 8);
  EXPECT_GT(solver.tight_solves, 0);
}

TEST(Newton, FallsBackToTheProjectedHessianWhereTheExactOneIsIndefinite) {
  // Start near 0, where 3x² − 1 + s < 0: the exact Hessian is not positive definite.
  Eigen::VectorXd x0(2), c(2);
  x0 << 0.05, -0.02;
  c << 0.0, 0.0;
  Quartic q(x0, 0.5, c, -10.0);
  DenseSolver solver;
  NewtonOptions o;
  o.decrement_tolerance = 1e-24;
  const NewtonStats s = newton(q, solver, o);
  ASSERT_TRUE(s.converged) << s.message;
  // Minima of (x² − 1)²/4 + x²/4: x² = 1/2.
  EXPECT_NEAR(std::abs(q.x[0]), std::sqrt(0.5), 1e-10);
  EXPECT_NEAR(std::abs(q.x[1]), std::sqrt(0.5), 1e-10);
  EXPECT_GT(s.linear_solves, s.iterations);  // some exact attempts were rejected
  // Projected steps first, the exact Hessian after a full step.
  EXPECT_GT(q.exact_evaluations, 0);
  EXPECT_LT(q.exact_evaluations, q.evaluations);
}

// As CG-AMG: a set-up takes any matrix, and only the solve finds out, by negative curvature,
// that it is not positive definite. With `reuse`, solve_previous() solves a new matrix with
// the old set-up, as the real backend does.
class SetUpThenSolve final : public LinearSolver {
 public:
  explicit SetUpThenSolve(bool reuse) : reuse_(reuse) {}
  bool factorize(const Eigen::SparseMatrix<double>& A) override {
    A_ = A;
    ++setups;
    return true;
  }
  LinearSolveStats solve(const Eigen::VectorXd& b, Eigen::VectorXd& x, double /*rtol*/, double /*decrease*/) override {
    return solve_with(A_, b, x);
  }
  LinearSolveStats solve_previous(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b, Eigen::VectorXd& x,
                                  double /*rtol*/, double /*decrease*/) override {
    if (!reuse_ || A_.rows() != A.rows()) return {};
    return solve_with(A, b, x);
  }
  std::string name() const override { return "set-up-then-solve"; }
  int setups = 0;

 private:
  static LinearSolveStats solve_with(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b,
                                     Eigen::VectorXd& x) {
    LinearSolveStats s;
    s.iterations = 1;
    const Eigen::LLT<Eigen::MatrixXd> llt{Eigen::MatrixXd(A)};
    if (llt.info() != Eigen::Success) {
      s.indefinite = true;
      return s;
    }
    x = llt.solve(b);
    s.ok = true;
    return s;
  }
  bool reuse_;
  Eigen::SparseMatrix<double> A_;
};

TEST(Newton, TriesLargerShiftsWithTheSetUpOfTheIndefiniteMatrix) {
  // x_1 near 0 keeps the exact Hessian indefinite after the first full projected step, so
  // that shifts are tried; once CG has found negative curvature with a set-up, the next
  // shift is tried with the same set-up, and a new one is made only for a matrix that CG
  // solves.
  Eigen::VectorXd x0(2), c(2);
  x0 << 1.5, 0.02;
  c << 1.0, 0.0;
  const auto run = [&](bool reuse, int& setups) {
    Quartic q(x0, 0.5, c, -10.0);
    SetUpThenSolve solver(reuse);
    NewtonOptions o;
    o.decrement_tolerance = 1e-24;
    const NewtonStats s = newton(q, solver, o);
    EXPECT_TRUE(s.converged) << s.message;
    setups = solver.setups;
    return q.x;
  };
  int with = 0, without = 0;
  const Eigen::VectorXd a = run(true, with), b = run(false, without);
  EXPECT_LT(with, without);
  EXPECT_LT((a - b).norm(), 1e-12);
}

TEST(Newton, NeverAcceptsAPointBeyondTheBarrier) {
  // The unconstrained minimum in x_0 is near 1.2, but the barrier x_0 > 0.9 … is not active
  // there; start just above a barrier that the full step would cross.
  Eigen::VectorXd x0(1), c(1);
  x0 << 3.0;
  c << -3.0;
  Quartic q(x0, 1.0, c, 0.5);  // the minimum of f lies below 0.5: the barrier is active
  DenseSolver solver;
  NewtonOptions o;
  o.max_iterations = 60;
  const NewtonStats s = newton(q, solver, o);
  EXPECT_GT(q.x[0], 0.5);  // accept() checks every accepted point is finite
  EXPECT_TRUE(std::isfinite(s.value));
}

TEST(Newton, ReportsANonFiniteStart) {
  Eigen::VectorXd x0(1), c(1);
  x0 << 0.0;
  c << 0.0;
  Quartic q(x0, 1.0, c, 0.5);
  DenseSolver solver;
  const NewtonStats s = newton(q, solver, {});
  EXPECT_FALSE(s.converged);
  EXPECT_NE(s.message.find("not finite"), std::string::npos);
}

}  // namespace
}  // namespace meshmorph

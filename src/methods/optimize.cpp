// SPDX-License-Identifier: MIT
#include "meshmorph/methods/optimize.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/error.h"
#include "meshmorph/log.h"
#include "meshmorph/solve/newton.h"
#include "methods/detail/fit_problem.h"
#include "methods/detail/newton_solver.h"

namespace meshmorph {
namespace {

// TMOP optimization is fitting without a level-set term: FitProblem with no fitted nodes is
// F = Σ_E ∫ μ with the same line-search rules.
template <int d>
OptimizeResult optimize_dim(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& fixed,
                            const std::vector<FitTerm>& slides, const OptimizeOptions& options, Eigen::MatrixXd& x) {
  FitOptions fo;
  fo.metric = options.metric;
  fo.target = options.target;
  fo.quadrature = options.quadrature;
  fo.quadrature_degree = options.quadrature_degree > 0 ? options.quadrature_degree : optimize_quadrature_degree(mesh);
  fo.growth = options.growth;
  fo.det_floor = options.det_floor;
  const std::size_t n_free =
      fixed.size() - static_cast<std::size_t>(std::count_if(fixed.begin(), fixed.end(), [](std::uint8_t f) { return f != 0; }));
  fo.threads = optimize_threads(options.threads, n_free);
  OptimizeSolver kind = options.solver;
  if (kind == OptimizeSolver::Auto) kind = d == 3 ? OptimizeSolver::MatrixFree : OptimizeSolver::Cholesky;
  const std::vector<FitTerm> no_terms;
  OptimizeResult result;
  FitProblem<d> P(mesh, topology, no_terms, fixed, fo, x, slides, kind == OptimizeSolver::MatrixFree);
  result.min_det0 = result.min_det = P.min_det();
  MESHMORPH_CHECK(result.min_det0 > 0.0, "optimize: the input mesh must be valid");
  result.energy0 = result.energy = P.energy();
  P.remember_current();
  const double g0 = P.current_gradient_norm();
  result.history.push_back({0, 0.0, result.energy0, g0, result.min_det0});

  bool converged = P.n_free() == 0 || g0 == 0.0;
  bool at_floor = false;  // ended on options.det_floor
  std::string why;
  if (!converged) {
    NewtonOptions no;
    no.exact_first = true;
    no.max_iterations = options.max_newton;
    // Rounding level of F (μ = |T|²/(2τ) − 1 cancels to rounding where T is ideal, so the
    // error scales with the measure, not with F): below it no step can be told from noise.
    no.decrement_tolerance = 1e-15 * (std::abs(result.energy0) + P.target_measure());
    bool reached = false;
    // With a det floor, F's minimiser may lie beyond it: the steps then shrink against the
    // floor (the line search rejects what crosses it) and the iterate sits on it, the best
    // mesh the floor allows. Ended there once a step is cut below 1e-3.
    const double floor = options.det_floor * result.min_det0;
    const auto on_floor = [&] { return floor > 0.0 && P.accepted_min_det() <= floor * (1.0 + 1e-3); };
    no.on_step = [&](int step, double alpha) {
      const double g = P.current_gradient_norm();
      result.history.push_back({step, alpha, P.accepted_energy(), g, P.accepted_min_det()});
      log_progress(format("optimize: Newton %d: F %.10g, |grad F| %.3g, alpha %.3g", step, result.history.back().energy, g, alpha));
      reached = g <= options.rtol * g0;
      at_floor = !reached && alpha < 1e-3 && on_floor();
      return !reached && !at_floor;
    };
    NewtonStats s;
    if (kind == OptimizeSolver::MatrixFree) {
      result.solver = "matrix-free";
      KrylovNewtonOptions ko;
      ko.threads = fo.threads;
      s = newton_matrix_free(P, no, ko);
      result.linear = s.krylov_iterations;
    } else {
      LinearSolverOptions lo;
      // Measured on fichq3_rs3_o2 (95k DOFs, P2 hexahedra, ~375 Hessian entries per row;
      // loaded 2-core machine): CHOLMOD 47 s and 1.0 GB for the run, CG-AMG 625 s and 2.3 GB,
      // 83% of it in the Galerkin products of the smoothed prolongator, whose A·P has the
      // pattern of A² on high-order Hessians: assembled Hessians take CHOLMOD unless asked.
      lo.kind = kind == OptimizeSolver::Iterative    ? LinearSolverKind::Iterative
                : kind == OptimizeSolver::PetscGamg  ? LinearSolverKind::PetscGamg
                : kind == OptimizeSolver::PetscHypre ? LinearSolverKind::PetscHypre
                                                     : LinearSolverKind::Cholesky;
      lo.block_size = d;
      lo.dim = d;
      lo.threads = fo.threads;
      lo.coordinates = detail::free_node_coordinates<d>(mesh, P.dofs());
      const std::unique_ptr<LinearSolver> solver = make_linear_solver(lo, P.n_free());
      result.solver = solver->name();
      s = newton(P, *solver, no, nullptr);
      result.linear = s.linear_solves;
    }
    result.newton = s.iterations;
    at_floor = at_floor || (!reached && !s.converged && on_floor());
    converged = reached || s.converged || at_floor;
    if (!converged) why = s.message;
  }
  x = P.state();
  result.energy = P.energy();
  result.min_det = P.min_det();
  const std::array<double, 3> mu = P.metric_range();
  result.mu_min = mu[0];
  result.mu_mean = mu[1];
  result.mu_max = mu[2];
  result.quadrature_degree = fo.quadrature_degree;
  result.converged = converged;
  const double g = result.history.back().gradient_norm;
  result.message = converged ? format("optimized: F %.6g -> %.6g, |grad F| reduced by %.2g in %lld Newton steps", result.energy0,
                                      result.energy, g0 > 0.0 ? g / g0 : 0.0, result.newton) +
                                   (at_floor ? format("; min det A on the det floor (%.3g of its initial value)",
                                                      options.det_floor)
                                             : std::string())
                             : format("stopped after %lld Newton steps at |grad F| / |grad F0| = %.2g: ", result.newton,
                                      g / g0) + why;
  return result;
}

}  // namespace

// More points than metric_quadrature_degree where the μ barrier must see the dips of det A
// between them, which otherwise stalled the line search on MFEM's curved meshes: in 2D 4p + 5
// (2p + 4 Lobatto points per direction; blade P4, jagged_mid22 P2), cheap at m² points; in 3D
// 2p + 2 when a simplex block has p ≥ 3 (escher_rs3_o3, P3 tetrahedra: degree 8); otherwise
// 0, each block's metric_quadrature_degree.
int optimize_quadrature_degree(const Mesh& mesh) {
  int order = 1;
  bool cubic_simplices = false;
  for (const CellBlock& b : mesh.cells) {
    order = std::max(order, b.order);
    cubic_simplices = cubic_simplices || (is_simplex(b.type) && b.order >= 3);
  }
  if (mesh.dim == 2) return 4 * order + 5;
  return cubic_simplices ? 2 * order + 2 : 0;
}

int optimize_threads(int threads, std::size_t n_dofs) { return threads > 0 ? threads : n_dofs < 30000 ? 1 : 0; }

OptimizeResult optimize_mesh(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& fixed,
                             const std::vector<FitTerm>& slides, const OptimizeOptions& options, Eigen::MatrixXd& x) {
  MESHMORPH_CHECK(fixed.size() == static_cast<std::size_t>(mesh.dim) * mesh.n_nodes(), "optimize: one fixed flag per DOF");
  return mesh.dim == 2 ? optimize_dim<2>(mesh, topology, fixed, slides, options, x)
                       : optimize_dim<3>(mesh, topology, fixed, slides, options, x);
}

}  // namespace meshmorph

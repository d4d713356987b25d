// SPDX-License-Identifier: MIT
#include "meshmorph/methods/fit.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/error.h"
#include "meshmorph/log.h"
#include "meshmorph/solve/newton.h"
#include "methods/detail/fit_problem.h"
#include "methods/detail/newton_solver.h"

namespace meshmorph {
namespace {

template <int d>
FitResult fit_dim(const Mesh& mesh, const Topology& topology, const std::vector<FitTerm>& terms,
                  const std::vector<std::uint8_t>& fixed, const FitOptions& options, Eigen::MatrixXd& x) {
  FitResult result;
  FitProblem<d> P(mesh, topology, terms, fixed, options, x);
  result.fit_error0 = result.fit_error = P.fit_error();
  result.min_det0 = result.min_det = P.min_det();
  MESHMORPH_CHECK(result.min_det0 > 0.0, "fit: the input mesh must be valid");
  double& weight = P.penalty().weight;  // w_σ
  weight = options.weight0 > 0.0 ? options.weight0 : 0.5 * options.penalty0 * P.metric_stiffness();
  result.history.push_back({0, weight, 0.0, result.fit_error, result.min_det});
  if (P.n_free() == 0 || result.fit_error <= options.eps_sigma) {
    result.converged = result.fit_error <= options.eps_sigma;
    result.message = result.converged ? "fitted" : "no node is free to move";
    return result;
  }

  const std::unique_ptr<LinearSolver> solver = detail::make_newton_solver<d>(options.solver, options.threads, mesh, P.dofs());
  NewtonMemory memory;

  // Algorithm 1 with eq. 13. N_σ bounds the consecutive weight increases (§3.4: "the maximum
  // number of consecutive Newton iterations through which w_σ is adapted"; the listing's
  // counter is reset the other way round, which would stop a run that fits well).
  int steps = 0, raises = 0;
  double error = result.fit_error;
  bool done = false;
  const auto raise = [&] {
    weight *= options.alpha_sigma;
    ++result.weight_updates;
    ++raises;
  };
  NewtonOptions no;
  no.exact_first = true;
  no.on_step = [&](int, double alpha) {
    ++steps;
    const double e = P.fit_error();
    result.history.push_back({steps, weight, alpha, e, P.min_det()});
    log_progress(format("fit: Newton %d: max |sigma| %.3g, w %.3g, alpha %.3g", steps, e, weight, alpha));
    if (options.adaptive && (error - e) < options.eps_dsigma * e) {
      raise();
      P.remember_current();
    } else {
      raises = 0;
    }
    error = e;
    done = error <= options.eps_sigma || raises >= options.n_sigma || steps >= options.max_newton;
    return !done;
  };
  while (!done) {
    P.remember_current();
    no.max_iterations = options.max_newton - steps;
    // The penalized problem at this w_σ solved to rounding: with a fixed weight that is the
    // answer, with an adaptive one the weight rises below.
    no.decrement_tolerance = 1e-14 * std::max(P.energy(), 1e-300);
    const NewtonStats s = newton(P, *solver, no, &memory);
    result.linear += s.linear_solves;
    if (s.stopped || done) break;
    if (!options.adaptive) {
      if (!s.converged) result.message = "the Newton solver stopped: " + s.message;
      break;
    }
    raise();  // converged (or stuck) at this weight without reaching ε_σ
    error = P.fit_error();
    done = raises >= options.n_sigma;
  }
  result.newton = steps;
  x = P.state();
  result.fit_error = P.fit_error();
  result.min_det = P.min_det();
  const auto [inverted, flat] = P.invalid_cells(x);
  result.inverted = inverted;
  result.flat = flat;
  result.converged = result.fit_error <= options.eps_sigma;
  if (result.converged) result.message = "fitted: max |sigma| " + format("%.3g", result.fit_error);
  else if (result.message.empty())
    result.message = format("max |sigma| %.3g above eps_sigma %.3g after %d Newton steps (w %.3g)", result.fit_error,
                            options.eps_sigma, steps, weight);
  return result;
}

}  // namespace

FitResult fit_to_level_sets(const Mesh& mesh, const Topology& topology, const std::vector<FitTerm>& terms,
                            const std::vector<std::uint8_t>& fixed, const FitOptions& options, Eigen::MatrixXd& x) {
  MESHMORPH_CHECK(fixed.size() == static_cast<std::size_t>(mesh.dim) * mesh.n_nodes(), "fit: one fixed flag per DOF");
  return mesh.dim == 2 ? fit_dim<2>(mesh, topology, terms, fixed, options, x) : fit_dim<3>(mesh, topology, terms, fixed, options, x);
}

}  // namespace meshmorph

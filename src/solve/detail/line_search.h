// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>

#include <Eigen/Core>

#include "meshmorph/solve/newton.h"
#include "meshmorph/timings.h"

namespace meshmorph::detail {

/// Step length α and energy there of the backtracking Armijo search along p from an iterate of
/// energy `value` and gradient g (c = options.armijo, α halved by options.backtrack): never
/// past a non-finite energy or an inadmissible point. α < options.min_step: none found.
struct LineSearch {
  double alpha = 1.0, value = 0.0;
};

inline LineSearch line_search(NewtonProblem& problem, double value, const Eigen::VectorXd& g, const Eigen::VectorXd& p,
                              const NewtonOptions& options) {
  const PhaseTimer timer(Phase::LineSearch);
  LineSearch s;
  const auto admissible = [&] {
    const PhaseTimer validity(Phase::Validity);
    return problem.admissible(p, s.alpha);
  };
  const double slope = g.dot(p);
  s.value = problem.trial_value(p, s.alpha);
  while (!(std::isfinite(s.value) && s.value <= value + options.armijo * s.alpha * slope && admissible())) {
    s.alpha *= options.backtrack;
    if (s.alpha < options.min_step) break;
    s.value = problem.trial_value(p, s.alpha);
  }
  return s;
}

/// problem.evaluate(mode, a), timed as assembly.
inline void evaluate(NewtonProblem& problem, HessianMode mode, Assembly& a) {
  const PhaseTimer timer(Phase::Assembly);
  problem.evaluate(mode, a);
}

/// The checks at the top of every Newton iteration, after the evaluation `a`: true (with
/// stats set) when the loop ends there, at a non-finite energy or with no free DOF.
inline bool ends_at(const Assembly& a, NewtonStats& stats) {
  stats.value = a.value;
  if (!std::isfinite(a.value)) {
    stats.message = "the energy is not finite at the starting point (an inverted element)";
    return true;
  }
  if (a.gradient.size() == 0) {
    stats.converged = true;
    return true;
  }
  return false;
}

}  // namespace meshmorph::detail

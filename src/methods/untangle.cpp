// SPDX-License-Identifier: MIT
#include "meshmorph/methods/untangle.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "meshmorph/error.h"
#include "meshmorph/log.h"
#include "meshmorph/solve/newton.h"
#include "methods/detail/newton_solver.h"
#include "methods/detail/untangle_problem.h"

namespace meshmorph {

struct Untangler::Impl {
  virtual ~Impl() = default;
  virtual UntangleResult solve(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step) = 0;
};

namespace {

// Decrement tolerances: for the intermediate δ of the continuation relative to F (Newton at
// fixed δ stops once it predicts a decrease below 1% of F: on paper 001's tests, 1e-4 took
// 2–3x the Newton steps for the same meshes); for the last solve per cell (F ≥ 1 per cell
// once valid).
constexpr double kLooseDecrement = 1e-2;
constexpr double kTightDecrement = 1e-10;
// δ below this fraction of its initial value with cells still inverted: give up.
constexpr double kSmallestDelta = 1e-14;
// Rounds of finer sampling where the Bernstein bounds find folds between the points.
constexpr int kFoldRounds = 8;

template <int d>
class UntangleImpl final : public Untangler::Impl {
 public:
  UntangleImpl(const Mesh& input, const Topology& topology, const BoundaryTargets& bc, UntangleOptions options,
               const std::vector<FitTerm>& surfaces)
      : options_(options), bc_(&bc), problem_(input, topology, bc, options.reference, options.n, options.threads, surfaces) {
    solver_ = detail::make_newton_solver<d>(options.solver, options.threads, input, problem_.dofs());
  }

  UntangleResult solve(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step) override {
    UntangleResult result;
    UntangleProblem<d>& P = problem_;
    // The case's tangle: the prescribed nodes at their targets, the others where they are.
    Eigen::MatrixXd placed = x;
    place(target, placed);
    P.set_state(placed);
    result.initial_inverted = P.measure().inverted;
    if (const std::size_t stuck = P.stuck_inverted(); stuck > 0) {
      result.message = std::to_string(stuck) +
                       " inverted cells have no free node (all on fixed or prescribed boundary): the boundary folds over"
                       " itself and no interior motion can untangle it";
      x = placed;
      return result;
    }
    // The differential predictor moves the free nodes along with the boundary (eq. 23).
    if (options_.predictor) {
      P.set_state(x);
      P.set_delta(0.0);
      Eigen::MatrixXd increment;
      if (P.measure().inverted == 0 && P.predict(target, *solver_, increment)) {
        ++result.linear;
        placed = x + increment;
        place(target, placed);
      }
      memory_.reusable = false;
    }
    P.set_state(placed);

    typename UntangleProblem<d>::Measures m = P.measure();
    double delta = 0.0, delta0 = 0.0;
    int rounds = 0, steps = 0;
    std::size_t folded = 0, sampled = 0;
    // δ of eq. 24 (h*_min = h(V_min)/δ) where a point finds a cell inverted, else 0; the
    // smoothing at δ = 0 keeps the mesh valid by the Bernstein bounds once it is.
    const auto start = [&] {
      delta = m.inverted > 0 ? options_.h_min * std::min(m.v_min, 0.0) / (options_.h_min * options_.h_min - 1.0) + options_.eps_delta
                             : 0.0;
      delta0 = delta;
      P.set_delta(delta);
      P.set_gamma(delta > 0.0 ? options_.gamma_untangle : options_.gamma_smooth);
      P.set_certify(options_.certify && delta == 0.0 && folded == 0);
    };
    // Valid at every point, smoothed, and still folded by the Bernstein bounds between the
    // points: the folds' pieces are sampled too and the untangling goes on (true).
    const auto resample = [&] {
      if (folded == 0 || rounds >= kFoldRounds || steps >= options_.max_newton) return false;
      ++rounds;
      sampled += P.sample_folds(true);
      memory_.reusable = false;
      m = P.measure();
      log_progress(format("untangle: step %d: the Bernstein bounds find det A <= 0 between the points of %zu cells:"
                          " sampled there too (%zu inverted at the points)", step, folded, m.inverted));
      start();
      return true;
    };
    if (options_.certify && m.inverted == 0) folded = P.sample_folds(false);
    start();
    record(result, step, 0, delta, 0.0, m);

    bool stop_rule = false, became_valid = false;
    double q_previous = m.q_min;
    NewtonOptions no;
    no.exact_first = true;
    no.on_step = [&](int, double alpha) {
      ++steps;
      const double delta_used = P.delta();
      m = P.measure();
      record(result, step, steps, delta_used, alpha, m);
      if (delta_used > 0.0) {
        if (m.inverted == 0) {  // valid: on with the unregularized functional
          became_valid = true;
          q_previous = m.q_min;
          return false;
        }
        if (options_.delta_rule == DeltaRule::Paper && alpha == 1.0) lower_delta(result, P.last_step());
      } else {
        if (m.inverted == 0 && std::abs(m.q_min - q_previous) < options_.eps_q * m.q_min) {
          stop_rule = true;
          return false;
        }
        q_previous = m.q_min;
      }
      return steps < options_.max_newton;
    };

    const double cells = static_cast<double>(P.n_cells());
    for (;;) {
      const bool smoothing = P.delta() == 0.0;
      no.decrement_tolerance = !smoothing && options_.delta_rule == DeltaRule::Continuation
                                   ? kLooseDecrement * P.energy()
                                   : kTightDecrement * cells;
      no.max_iterations = options_.max_newton - steps;
      became_valid = false;
      const NewtonStats s = newton(P, *solver_, no, &memory_);
      result.linear += s.linear_solves;
      if (smoothing) {
        folded = options_.certify && m.inverted == 0 ? P.sample_folds(false) : 0;
        if (resample()) continue;
        result.converged = m.inverted == 0 && folded == 0;
        const std::string valid = !options_.certify ? std::string("valid")
                                  : sampled > 0   ? format("valid by the Bernstein bounds (%zu cells sampled at folds between their points)", sampled)
                                                  : std::string("valid by the Bernstein bounds");
        if (stop_rule) result.message = valid + "; q_min changed by less than eps_q";
        else if (s.converged) result.message = valid + "; the functional is at its minimum";
        else if (steps >= options_.max_newton) result.message = valid + "; smoothing stopped at max_newton Newton steps";
        else result.message = valid + "; smoothing stopped: " + s.message;
        if (m.inverted > 0) result.message = "tangled again while smoothing";
        else if (folded > 0)
          result.message = format("valid at every point, but the Bernstein bounds find det A <= 0 between the points of %zu"
                                  " cells (after %d rounds of sampling at folds)", folded, rounds);
        break;
      }
      if (became_valid) {
        folded = options_.certify ? P.sample_folds(false) : 0;
        log_progress(format("untangle: step %d: valid after %d Newton steps (q_min %.3f); smoothing", step, steps, m.q_min));
        P.set_delta(0.0);
        P.set_gamma(options_.gamma_smooth);
        P.set_certify(options_.certify && folded == 0);
        continue;
      }
      if (steps >= options_.max_newton) {
        result.message = format("still tangled after max_newton = %d Newton steps (delta %.3g)", options_.max_newton,
                                P.delta());
        break;
      }
      // Converged at this δ (or no further progress): lower it (eq. 13–14 with Δx = 0).
      lower_delta(result, Eigen::VectorXd());
      if (P.delta() < kSmallestDelta * delta0) {
        result.message = format("delta fell to %.3g with the mesh still tangled: no valid mesh was found", P.delta());
        break;
      }
    }
    result.newton = steps;
    result.min_quality = m.q_min;
    x = P.state();
    return result;
  }

 private:
  void place(const Eigen::MatrixXd& target, Eigen::MatrixXd& x) const {
    for (std::size_t i = 0; i < bc_->n_nodes(); ++i)
      if (bc_->role[i] == NodeRole::Prescribed) x.col(static_cast<Eigen::Index>(i)) = target.col(static_cast<Eigen::Index>(i));
  }

  // δ ← max(δ − α|Δδ|, βδ) (eq. 14).
  void lower_delta(UntangleResult& result, const Eigen::VectorXd& dx) {
    const double delta = problem_.delta();
    const double step = std::abs(problem_.delta_increment(dx));
    const double next = std::max(delta - options_.alpha * step, options_.beta * delta);
    problem_.set_delta(next);
    ++result.delta_updates;
    // A progress line each update: Newton may take no step at a δ, and a run of such updates
    // is otherwise silent.
    log_progress(format("untangle: delta %.4g -> %.4g", delta, next));
  }

  static void record(UntangleResult& result, int step, int newton, double delta, double alpha,
                     const typename UntangleProblem<d>::Measures& m) {
    result.history.push_back({step, newton, delta, alpha, m.q_min, m.inverted});
    log_progress(format("untangle: step %d, Newton %d: delta %.3g, alpha %.3g, q_min %.4f, %zu inverted", step, newton,
                        delta, alpha, m.q_min, m.inverted));
  }

  UntangleOptions options_;
  const BoundaryTargets* bc_;
  UntangleProblem<d> problem_;
  std::unique_ptr<LinearSolver> solver_;
  NewtonMemory memory_;
};

}  // namespace

Untangler::Untangler(const Mesh& input, const Topology& topology, const BoundaryTargets& bc, UntangleOptions options,
                     const std::vector<FitTerm>& surfaces) {
  MESHMORPH_CHECK(bc.n_nodes() == input.n_nodes(), "Untangler: the boundary targets do not fit the mesh");
  if (input.dim == 2)
    impl_ = std::make_unique<UntangleImpl<2>>(input, topology, bc, options, surfaces);
  else
    impl_ = std::make_unique<UntangleImpl<3>>(input, topology, bc, options, surfaces);
}

Untangler::~Untangler() = default;

UntangleResult Untangler::solve(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step) {
  return impl_->solve(target, x, step);
}

}  // namespace meshmorph

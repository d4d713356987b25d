// SPDX-License-Identifier: MIT
#include "meshmorph/methods/morph.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "meshmorph/energy/boundary_penalty.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/log.h"
#include "meshmorph/mesh/node_order.h"
#include "meshmorph/methods/untangle.h"
#include "meshmorph/quality/metric_registry.h"
#include "meshmorph/solve/newton.h"
#include "methods/detail/morph_problem.h"
#include "methods/detail/newton_solver.h"

namespace meshmorph {

struct Morpher::Impl {
  virtual ~Impl() = default;
  virtual MorphResult solve(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step) = 0;
};

namespace {

template <int d>
class MorphImpl final : public Morpher::Impl {
 public:
  MorphImpl(const Mesh& input, const Topology& topology, const BoundaryTargets& bc, MorphOptions options)
      : options_(options), input_(&input), topology_(&topology), bc_(&bc), problem_(input, topology, bc, options.threads) {
    solver_ = detail::make_newton_solver<d>(options.solver, options.threads, input, problem_.dofs());
    if (options.guard == MorphOptions::Guard::Ring || (options.guard == MorphOptions::Guard::Auto && d == 2))
      problem_.widen_guard();
  }

  MorphResult solve(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step) override {
    MorphResult result;
    MorphProblem<d>& P = problem_;
    BoundaryPenalty<d>& penalty = P.penalty();
    P.set_state(x);
    penalty.set_target(P.gather_targets(target));
    if (penalty.size() == 0) {
      result.converged = true;
      result.message = "no node has a prescribed motion";
      return result;
    }
    if (const std::size_t stuck = P.stuck_inverted(target); stuck > 0) {
      result.message = std::to_string(stuck) +
                       " cells have only fixed and prescribed nodes and the motion inverts them: no motion of the"
                       " other nodes can make them valid";
      return result;
    }
    const double tol_max = options_.tolerance * P.length_scale();
    // δ and μ are relative to the weights' scale (docs/morph.md): δ to the energy of the
    // identity map with the current weights, μ to the mean weight beside the constrained
    // nodes. Scaling every ω by s then leaves the iterates unchanged, and the weights' growth
    // (Algorithm 2: ×β per update, e^27 for a cell of quality 0.1) neither pushes the boundary
    // back nor tightens δ.
    const double delta_star = options_.gradient_tolerance;
    if (!started_) {
      mu0_ = options_.penalty0 * P.distortion_stiffness() / penalty.mean_diagonal();
      m_ = options_.m0;
      started_ = true;
    }
    const auto set_mu = [&] { penalty.mu = mu0_ * m_ / options_.m0 * P.boundary_weight(); };
    // A multigrid set-up made before μ grew by m_factor preconditions the new Hessian poorly
    // (CG took 92 iterations for the first solve at μ = 3.9e8 on the 50.7k shell): the next
    // subproblem makes its own. A direct factor is tried first as ever (a few cheap iterations).
    const auto raise_mu = [&] {
      m_ *= options_.m_factor;
      set_mu();
      if (!solver_->cheap_previous()) newton_memory_.reusable = false;
    };
    set_mu();
    // ε₀, δ₀ restart with each step (relative to how far this step has to go); μ, m, λ and
    // the weights carry over (paper 000 §5.5).
    const double c_start = penalty.constraint_norm(P.state());
    double eps = options_.eps0 * c_start;
    double delta = std::max(options_.delta0, delta_star);

    bool stalled = false;
    bool short_of_boundary = false;  // the last AL iteration ended short of the boundary
    NewtonOptions no;
    no.max_iterations = options_.max_newton;
    no.exact_first = options_.exact_first;
    // Shifts of 1e-4 |diag H| dwarf the soft modes beside cells weighted 1e12 or squeezed to
    // 1%: full steps crawled there (docs/morph.md). fit's P3 meshes took up to 2.8× the
    // Newton steps with this floor, so only morph lowers it.
    no.min_shift = 1e-10;
    for (int outer = 1; outer <= options_.max_outer; ++outer) {
      // Inexact Newton on the intermediate subproblems: two digits per Krylov solve cost a
      // quarter of the iterations of eight and (measured on the §5.2 shells) neither more
      // Newton steps nor another AL iteration; a premature decrement test only leaves the
      // rest to the next subproblem. The last ones, at δ*, decide the result: tight solves.
      const bool final_delta = delta <= delta_star * (1 + 1e-12);
      no.forcing = final_delta ? 0.0 : 1e-2;
      bool newton_ok = true;
      std::string newton_message;
      const long long newton_before = result.newton;
      // Algorithm 2 with inexact re-solves (docs/morph.md, "The weight loop"): the first solve
      // of an AL iteration meets δ; after each weight update Newton takes at most
      // `weight_steps` steps before the next one, and the loop ends with a solve that meets δ
      // once the weights stop changing or after `max_weight_updates` updates.
      bool settled = !options_.adaptive_weights;
      double growth = options_.beta;  // the bound on a weight's growth per update (eq. 11's β)
      for (int update = 0;; ++update) {
        const bool last = settled || update >= options_.max_weight_updates;
        no.decrement_tolerance = delta * P.reference_energy();
        // Near the boundary a new λ or μ changes the gradient by less than the decrement test
        // sees (μ·e with e ~ ε*): without a step the iteration finds the same error and
        // raises μ for nothing.
        no.min_iterations = update == 0 && short_of_boundary ? 1 : 0;
        no.on_step = nullptr;
        if (!last && update > 0 && options_.weight_steps > 0)
          no.on_step = [k = options_.weight_steps](int steps, double) { return steps < k; };
        const NewtonStats s = newton(P, *solver_, no, &newton_memory_);
        result.linear += s.linear_solves;
        result.krylov += s.krylov_iterations;
        result.newton += s.iterations;
        if (s.iterations > 0) ++result.nonlinear;
        newton_ok = s.converged;
        newton_message = s.message;
        // Algorithm 2's loop condition: the gradient is below δ with the weights just updated,
        // i.e. Newton had nothing to do after an update.
        if (last || !(s.converged || s.stopped) || (update > 0 && s.iterations == 0)) break;
        // Adaptive growth (docs/morph.md, "Weight growth"): where Newton absorbed the last
        // update in one step, the next may grow the weights by the square of the last bound,
        // up to β⁴; where it needed all `weight_steps`, the bound goes back by a square root.
        if (options_.adaptive_growth && update > 0) {
          if (s.converged && s.iterations <= 1)
            growth = std::min(growth * growth, std::pow(options_.beta, 4));
          else if (s.stopped)
            growth = std::max(options_.beta, std::sqrt(growth));
        }
        if (P.update_weights(options_.alpha, growth, options_.max_weight))
          set_mu();
        else if (s.converged)
          break;
        else
          settled = true;  // a cut-short solve: one more, to δ
      }
      ++result.outer;
      const double c = penalty.constraint_norm(P.state());
      const double emax = penalty.max_error(P.state());
      MorphIteration row;
      row.step = step;
      row.outer = outer;
      row.constraint_norm = c;
      row.boundary_error_max = emax;
      row.min_quality = P.min_quality();
      row.mu = penalty.mu;
      row.nonlinear = result.nonlinear;
      row.newton = result.newton;
      row.linear = result.linear;
      result.history.push_back(row);
      log_progress("morph: step " + std::to_string(step) + ", AL iteration " + std::to_string(outer) +
                   format(": boundary error %.3g (max %.3g), min quality %.3f, mu %.3g", c, emax, row.min_quality, penalty.mu));
      if (emax <= tol_max && newton_ok && final_delta) {
        result.converged = true;
        break;
      }
      // Stalled: twelve orders of penalty (six failed iterations) and the constraint no longer
      // halves; past this the Newton systems lose their digits to the penalty's condition.
      if (outer > 1 && c > 0.5 * result.history[result.history.size() - 2].constraint_norm && m_ > 1e12 * options_.m0) {
        result.message = newton_ok ? format("the augmented Lagrangian stalled (boundary error %.3g, mu %.3g)", c, penalty.mu)
                                   : "the nonlinear solver stalled (" + newton_message + ")";
        stalled = true;
        break;
      }
      short_of_boundary = emax > tol_max;
      if (c <= eps) {  // Algorithm 1, lines 10–15 (ε, δ as in Conn–Gould–Toint, DESIGN §6)
        penalty.update_multipliers(P.state());
        eps /= std::pow(m_, 0.9);
        // Once the boundary is reached only δ* is left to meet: no intermediate δ on the way
        // (with μ still at μ₀, δ/m would take nine AL iterations from δ₀ to δ*). The same
        // where this subproblem took no Newton step: its iterate met δ_k as it was, and δ/m
        // per iteration left the multiplier updates with nothing to move (bl_circle_p3: three
        // AL iterations in a row without a step).
        delta = emax <= tol_max || result.newton == newton_before ? delta_star : std::max(delta / m_, delta_star);
        // A multiplier update converges at the rate ~κ/(κ + μ) (κ: the mesh's stiffness beside
        // the boundary, which the weights raise), and μ only grows on the other branch when an
        // update falls short of ε_k: raised with every update that leaves the boundary short,
        // μ reaches the boundary in 5 iterations where the printed rule took 7–12
        // (docs/morph.md, "Raising μ after multiplier updates").
        if (outer > 1 && emax > tol_max && c > options_.min_decrease * result.history[result.history.size() - 2].constraint_norm) {
          raise_mu();
        }
      } else {  // lines 16–21
        raise_mu();
        eps = options_.eps0 * c_start * std::pow(options_.m0 / m_, 0.1);
        delta = std::max(options_.delta0 * (options_.m0 / m_), delta_star);
      }
    }
    if (!result.converged && result.message.empty())
      result.message = "the boundary was not reached within " + std::to_string(options_.max_outer) +
                       " augmented-Lagrangian iterations (max error " +
                       format("%.3g, tolerance %.3g)", result.history.back().boundary_error_max, tol_max);
    x = P.state();
    result.guarded_cells = P.guarded_cells();
    if (stalled && options_.finish_by_untangle) finish_by_untangle(target, x, step, result);
    return result;
  }

 private:
  // DESIGN §6: on extreme squeezes the distortion's barrier holds the last cells against the
  // penalty and the augmented Lagrangian stalls short of the boundary, though valid meshes
  // exist there. Paper 001 finds one from the stalled iterate with the prescribed nodes on
  // their targets (the slide nodes are on their planes already): its regularized volume lets
  // the cells that this placing inverts come back.
  void finish_by_untangle(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step, MorphResult& result) {
    // From a value: clang before 16 takes a nested struct with member initializers for one
    // without a default constructor inside std::optional.
    MorphResult::Finish& f = result.finish.emplace(MorphResult::Finish{});
    f.stall = result.message;
    f.boundary_error_max = result.history.back().boundary_error_max;
    // The stalled λ and μ (≥ 1e12 μ₀) would start the next step of a series at the condition
    // that stalled this one: it starts afresh from μ₀ and λ = 0; the weights carry over.
    started_ = false;
    problem_.penalty().multipliers().setZero();
    if (!untangler_) {
      UntangleOptions uo;
      uo.predictor = false;
      uo.solver = options_.solver;
      uo.threads = options_.threads;
      try {
        untangler_ = std::make_unique<Untangler>(*input_, *topology_, *bc_, uo);
      } catch (const InputError& e) {
        f.message = std::string("not run: ") + e.what();
        result.message += "; no untangle pass (" + f.message + ")";
        return;
      }
    }
    Eigen::MatrixXd y = x;  // its slide nodes are on their planes (MorphProblem)
    log_progress("morph: step " + std::to_string(step) + ": " + result.message + "; untangle pass from there");
    const UntangleResult u = untangler_->solve(target, y, step);
    f.initial_inverted = u.initial_inverted;
    f.newton = u.newton;
    f.linear = u.linear;
    f.valid = u.converged;
    f.message = u.message;
    result.newton += u.newton;
    result.linear += u.linear;
    if (!u.converged) {
      result.message += "; the untangle pass did not find a valid mesh either (" + u.message + ")";
      return;
    }
    // Untangling judges cells at its samples; the result must pass the Bernstein bounds too.
    Mesh moved = *input_;
    moved.x = y;
    if (const std::size_t bad = count_invalid_cells(moved); bad > 0) {
      f.valid = false;
      result.message += "; the untangle pass left " + std::to_string(bad) + " cells inverted between their samples";
      return;
    }
    x = y;
    result.converged = true;
    result.message = format("boundary reached by an untangle pass (paper 001) after the augmented Lagrangian stalled"
                            " %.3g from it", f.boundary_error_max);
  }

  MorphOptions options_;
  const Mesh* input_;
  const Topology* topology_;
  const BoundaryTargets* bc_;
  MorphProblem<d> problem_;
  std::unique_ptr<LinearSolver> solver_;
  std::unique_ptr<Untangler> untangler_;  // the finishing pass, made when first needed
  NewtonMemory newton_memory_;  // shift and factorization carried from one subproblem to the next
  bool started_ = false;
  double mu0_ = 1.0, m_ = 10.0;
};

}  // namespace

// The run's nodes in locality_order(): the Newton systems of a mesh numbered as its
// generator left it spend much of their time waiting for scattered vector entries.
struct Morpher::Renumbered {
  Renumbered(const Mesh& input, const Topology& input_topology, const BoundaryTargets& input_bc)
      : order(locality_order(input_topology)), mesh(renumber_nodes(input, order)), topology(build_topology(mesh)) {
    bc.role.resize(order.size());
    bc.target = in_order(input_bc.target);
    bc.normal = in_order(input_bc.normal);
    for (std::size_t k = 0; k < order.size(); ++k) bc.role[k] = input_bc.role[order[k]];
  }
  Eigen::MatrixXd in_order(const Eigen::MatrixXd& x) const {
    Eigen::MatrixXd y(x.rows(), x.cols());
    for (std::size_t k = 0; k < order.size(); ++k) y.col(static_cast<Eigen::Index>(k)) = x.col(order[k]);
    return y;
  }
  void back(const Eigen::MatrixXd& y, Eigen::MatrixXd& x) const {
    for (std::size_t k = 0; k < order.size(); ++k) x.col(order[k]) = y.col(static_cast<Eigen::Index>(k));
  }

  std::vector<std::int32_t> order;
  Mesh mesh;
  Topology topology;
  BoundaryTargets bc;
};

Morpher::Morpher(const Mesh& input, const Topology& topology, const BoundaryTargets& bc, MorphOptions options) {
  MESHMORPH_CHECK(bc.n_nodes() == input.n_nodes(), "Morpher: the boundary targets do not fit the mesh");
  const Mesh* mesh = &input;
  const Topology* topo = &topology;
  const BoundaryTargets* targets = &bc;
  if (options.renumber) {
    renumbered_ = std::make_unique<Renumbered>(input, topology, bc);
    mesh = &renumbered_->mesh;
    topo = &renumbered_->topology;
    targets = &renumbered_->bc;
  }
  if (input.dim == 2)
    impl_ = std::make_unique<MorphImpl<2>>(*mesh, *topo, *targets, options);
  else
    impl_ = std::make_unique<MorphImpl<3>>(*mesh, *topo, *targets, options);
}

Morpher::~Morpher() = default;

MorphResult Morpher::solve(const Eigen::MatrixXd& target, Eigen::MatrixXd& x, int step) {
  if (!renumbered_) return impl_->solve(target, x, step);
  Eigen::MatrixXd y = renumbered_->in_order(x);
  const MorphResult result = impl_->solve(renumbered_->in_order(target), y, step);
  renumbered_->back(y, x);
  return result;
}

}  // namespace meshmorph

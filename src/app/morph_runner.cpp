// SPDX-License-Identifier: MIT
// MorphRunner: the augmented Lagrangian of paper 000 or a baseline on a case, for the command
// line and the Python module alike.
#include <string>
#include <utility>

#include "app/detail/method_output.h"
#include "meshmorph/app/morph_case.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/validity.h"

namespace meshmorph {

// What the solves of one run have added up to so far.
struct MorphRunner::Progress {
  IterationCounts counts;
  std::size_t guarded = 0;
  nlohmann::ordered_json finishes = nlohmann::ordered_json::array();
};

MorphRunner::MorphRunner(const CaseFile& c, Mesh mesh, int threads) : where_(c.file.string()), input_(std::move(mesh)) {
  reject_unused_keys(c, "morph", {"interface", "trim"});
  check_case_against_mesh(c, input_);
  settings_ = read_morph_settings(c, threads);
  if (c.order && below_order(input_, *c.order)) input_ = elevate_order(input_, *c.order);
  // One topology for the orientation check and the run (a million-node shell builds one in
  // about 20 s); cells listed mirrored back change their facets' numbers: built again.
  topology_ = build_topology(input_);
  if (orient_cells(c, input_, topology_) > 0) topology_ = build_topology(input_);
  if (const std::size_t bad = count_invalid_cells(input_); bad > 0)
    throw InputError(detail::inverted_input(c, bad) + ": morph needs a valid input mesh (untangle recovers one)");
  motion_ = std::make_unique<BoundaryMotion>(c.boundary, c.file.string(), input_, topology_);
  if (settings_.method == "morph") morpher_ = std::make_unique<Morpher>(input_, topology_, motion_->targets(), settings_.morph);
  // A renumbering Morpher holds its own topology, and nothing else here reads this one again:
  // on a million-node shell it holds about 600 MB.
  if (morpher_ && settings_.morph.renumber) topology_ = Topology();
  x_ = input_.x;
  steps_ = c.steps;
}

MorphRunner::~MorphRunner() = default;

bool MorphRunner::advance(const Eigen::MatrixXd& target, int step, bool label, Progress& p, MorphOutput& out) {
  Report& report = out.report;
  const std::string prefix = label ? "step " + std::to_string(step) + ": " : std::string();
  if (morpher_) {
    const MorphResult r = morpher_->solve(target, x_, step);
    p.counts.outer += r.outer;
    p.counts.nonlinear += r.nonlinear;
    p.counts.newton += r.newton;
    p.counts.linear += r.linear;
    out.krylov += r.krylov;
    p.guarded = r.guarded_cells;
    for (HistoryRow& row : morph_history(r)) report.history.push_back(std::move(row));
    if (r.finish) {
      p.finishes.push_back(untangle_pass(*r.finish, step));
      if (r.converged) report.message = prefix + r.message;
    }
    if (!r.converged) report.message = prefix + r.message;
    return r.converged;
  }
  // A baseline: one linear solve on the mesh the last increment left (the incremental
  // Laplacian / elasticity of the mesh-motion literature).
  Mesh current = input_;
  current.x = x_;
  BoundaryTargets bc = motion_->targets();
  bc.target = target;
  const BaselineResult r = settings_.method == "laplace" ? laplace_morph(current, topology_, bc, settings_.baseline)
                                                         : elastic_morph(current, topology_, bc, settings_.baseline);
  p.counts.nonlinear += 1;
  p.counts.linear += r.linear_solves;
  x_ = r.x;
  if (!r.linear.ok) report.message = prefix + "the linear solver did not converge: " + r.linear.message;
  return r.linear.ok;
}

MorphOutput MorphRunner::finish(MorphOutput out, const Progress& p, const BoundaryTargets& bc) const {
  Report& report = out.report;
  report.method = morpher_ ? "morph" : "morph/" + settings_.method;
  report.iterations = p.counts;
  out.moved = input_;
  out.moved.x = x_;
  out.quality = detail::fill_result(report, out.moved, &input_, bc);
  if (report.converged && report.message.empty()) report.message = "boundary reached, mesh valid";
  if (morpher_) {
    out.extra["guarded_cells"] = p.guarded;
    out.extra["untangle_passes"] = p.finishes;
  }
  return out;
}

// The augmented Lagrangian hands back valid meshes only: a result that fails the report's
// checks (cells inverted between the samples that the method judged them at, a boundary
// that passes through itself) is replaced by the mesh its last solve started from, or, where
// that fails them too (an earlier step of a series that overlapped), by the input.
MorphOutput MorphRunner::keep_valid(MorphOutput out, const Eigen::MatrixXd& before, const Progress& p,
                                    const BoundaryTargets& bc) {
  if (!morpher_ || out.report.valid) return out;
  const std::string why = out.report.message;
  const Eigen::MatrixXd* input = &input_.x;
  for (const Eigen::MatrixXd* x : {&before, input}) {
    x_ = *x;
    out = finish(std::move(out), p, bc);
    if (out.report.valid || x == input) {
      out.report.message = why + (x == &before ? "; the mesh returned is the one the last solve started from"
                                               : "; the mesh returned is the input");
      return out;
    }
  }
  return out;
}

MorphOutput MorphRunner::run(const StepSink& on_step) {
  MorphOutput out;
  Progress p;
  out.report.converged = true;
  Eigen::MatrixXd before;  // x_ where the last solve started (steps_ ≥ 1)
  for (int s = 1; s <= steps_; ++s) {
    ++solves_;
    before = x_;
    if (!advance(motion_->at(static_cast<double>(s) / steps_), s, steps_ > 1, p, out)) {
      out.report.converged = false;
      break;
    }
    if (s == steps_) break;
    Mesh mesh = input_;
    mesh.x = x_;
    // The next increment of a baseline needs valid cells: one that inverted some ends here.
    if (!morpher_)
      if (const std::size_t bad = count_invalid_cells(mesh); bad > 0) {
        out.report.converged = false;
        out.report.message = "step " + std::to_string(s) + ": " + std::to_string(bad) + " inverted elements";
        break;
      }
    if (on_step) on_step(s, mesh);
  }
  return keep_valid(finish(std::move(out), p, motion_->targets()), before, p, motion_->targets());
}

MorphOutput MorphRunner::solve(const Eigen::MatrixXd& target) {
  MorphOutput out;
  Progress p;
  const Eigen::MatrixXd before = x_;
  out.report.converged = advance(target, ++solves_, false, p, out);
  // The boundary error against this solve's targets, not the case's motion at its end.
  const BoundaryTargets bc = detail::with_targets(motion_->targets(), target);
  return keep_valid(finish(std::move(out), p, bc), before, p, bc);
}

}  // namespace meshmorph

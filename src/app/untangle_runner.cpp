// SPDX-License-Identifier: MIT
// UntangleRunner: simultaneous untangling and smoothing (paper 001) on a case, for the
// command line and the Python module alike.
#include <string>
#include <utility>

#include "app/detail/method_output.h"
#include "meshmorph/app/untangle_case.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/validity.h"

namespace meshmorph {
namespace {

void count(IterationCounts& counts, const UntangleResult& r) {
  counts.outer += r.delta_updates;
  counts.nonlinear += 1;
  counts.newton += r.newton;
  counts.linear += r.linear;
}

}  // namespace

UntangleRunner::UntangleRunner(const CaseFile& c, Mesh mesh, int threads) : where_(c.file.string()), input_(std::move(mesh)) {
  reject_unused_keys(c, "untangle", {"interface", "trim"});
  check_case_against_mesh(c, input_);
  std::optional<UntangleReference> reference;
  options_ = read_untangle_options(c.options, where_, threads, reference);
  if (c.order && below_order(input_, *c.order)) input_ = elevate_order(input_, *c.order);
  orient_cells(c, input_);
  input_inverted_ = count_invalid_cells(input_);
  resolve_untangle_reference(options_, reference, input_inverted_, where_);
  topology_ = build_topology(input_);
  motion_ = std::make_unique<BoundaryMotion>(c.boundary, c.file.string(), input_, topology_);
  try {
    untangler_ = std::make_unique<Untangler>(input_, topology_, motion_->targets(), options_);
  } catch (const InputError& e) {
    throw InputError(where_ + ": " + e.what());
  }
  x_ = input_.x;
  steps_ = c.steps;
}

UntangleRunner::~UntangleRunner() = default;

RunOutput UntangleRunner::finish(RunOutput out, const BoundaryTargets& bc) const {
  out.report.method = "untangle";
  out.moved = input_;
  out.moved.x = x_;
  out.quality = detail::fill_result(out.report, out.moved, input_inverted_ == 0 ? &input_ : nullptr, bc);
  out.extra["predictor"] = options_.predictor;
  out.extra["reference"] = options_.reference == UntangleReference::Input ? "input" : "regular";
  return out;
}

RunOutput UntangleRunner::run(const StepSink& on_step) {
  RunOutput out;
  IterationCounts counts;
  std::size_t initial_inverted = 0;
  double min_edge_quality = 0.0;
  out.report.converged = true;
  for (int s = 1; s <= steps_; ++s) {
    const UntangleResult r = untangler_->solve(motion_->at(static_cast<double>(s) / steps_), x_, ++solves_);
    if (s == 1) initial_inverted = r.initial_inverted;
    count(counts, r);
    min_edge_quality = r.min_quality;
    for (HistoryRow& row : untangle_history(r)) out.report.history.push_back(std::move(row));
    out.report.message = (steps_ > 1 ? "step " + std::to_string(s) + ": " : std::string()) + r.message;
    if (!r.converged) {
      out.report.converged = false;
      break;
    }
    if (s < steps_ && on_step) {
      Mesh mesh = input_;
      mesh.x = x_;
      on_step(s, mesh);
    }
  }
  out.report.iterations = counts;
  out.extra["initial_inverted_elements"] = initial_inverted;
  out.extra["min_edge_quality"] = min_edge_quality;
  out.extra["steps"] = steps_;
  return finish(std::move(out), motion_->targets());
}

RunOutput UntangleRunner::solve(const Eigen::MatrixXd& target) {
  RunOutput out;
  const UntangleResult r = untangler_->solve(target, x_, ++solves_);
  IterationCounts counts;
  count(counts, r);
  out.report.iterations = counts;
  out.report.history = untangle_history(r);
  out.report.converged = r.converged;
  out.report.message = r.message;
  out.extra["initial_inverted_elements"] = r.initial_inverted;
  out.extra["min_edge_quality"] = r.min_quality;
  // The boundary error against this solve's targets, not the case's motion at its end.
  return finish(std::move(out), detail::with_targets(motion_->targets(), target));
}

}  // namespace meshmorph

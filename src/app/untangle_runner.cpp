// SPDX-License-Identifier: MIT
// UntangleRunner: simultaneous untangling and smoothing (paper 001) on a case, for the
// command line and the Python module alike.
#include <algorithm>
#include <string>
#include <utility>

#include "app/detail/method_output.h"
#include "meshmorph/app/untangle_case.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/log.h"

namespace meshmorph {
namespace {

constexpr int kLocalNewton = 60;

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
  options_ = read_untangle_options(c.options, where_, threads, reference, boundary_);
  if (boundary_.mode.empty()) boundary_.mode = c.boundary.empty() ? "auto" : "fixed";
  if (c.order && below_order(input_, *c.order)) input_ = elevate_order(input_, *c.order);
  orient_cells(c, input_);
  input_invalid_ = invalid_cells(input_);
  input_inverted_ = static_cast<std::size_t>(std::count(input_invalid_.begin(), input_invalid_.end(), std::uint8_t{1}));
  resolve_untangle_reference(options_, reference, input_inverted_, where_);
  topology_ = build_topology(input_);
  motion_ = std::make_unique<BoundaryMotion>(c.boundary, c.file.string(), input_, topology_);
  steps_ = c.steps;
  bc_ = motion_->targets();
  if (boundary_.mode == "fixed") {
    start(false);
    return;
  }
  // The input's own facets carry the boundary nodes no entry names, and in "slide" each
  // `project` group moves along its level set.
  may_slide_.assign(input_.n_nodes(), 0);
  for (std::int32_t node : boundary_nodes(input_, topology_)) may_slide_[static_cast<std::size_t>(node)] = 1;
  for (const BoundaryCondition& b : c.boundary)
    for (std::int32_t node : input_.group_nodes(*input_.find_group(b.group))) may_slide_[static_cast<std::size_t>(node)] = 0;
  if (boundary_.mode == "slide") {
    LevelSetOptions lso;
    lso.source = where_;
    lso.length_scale = (input_.x.rowwise().maxCoeff() - input_.x.rowwise().minCoeff()).norm();
    for (const BoundaryCondition& b : c.boundary)
      if (const auto* project = std::get_if<ProjectMotion>(&b.motion))
        surfaces_.push_back({LevelSetFunction(project->target, input_.dim, lso), input_.group_nodes(*input_.find_group(b.group))});
    boundary_why_ = "asked for";
    start(true);
    return;
  }
  // auto: the boundary slides where inverted cells have only interior nodes free.
  Mesh placed = input_;
  placed.x = motion_->at(1.0);
  const bool unmoved = placed.x == input_.x;
  const std::size_t bound = boundary_bound_inverted(placed, motion_->targets(), unmoved ? &input_invalid_ : nullptr);
  boundary_why_ = bound > 0 ? std::to_string(bound) + " inverted cells have all their corners on the boundary"
                            : "the interior untangles the mesh";
  local_ = bound > 0 && steps_ == 1 && motion_->targets().nodes_with(NodeRole::Prescribed).empty();
  // A patch repair builds its own untangler; the whole mesh's only where the patches fail.
  if (local_) x_ = input_.x;
  else start(bound > 0);
}

UntangleRunner::~UntangleRunner() = default;

void UntangleRunner::start(bool slide) {
  sliding_ = slide;
  untangler_.reset();
  if (slide && !facet_surfaces_) {
    facet_surfaces_ = true;
    for (FitTerm& t : untangle_surfaces(input_, topology_, topology_.boundary_facets, may_slide_, boundary_.feature_angle))
      surfaces_.push_back(std::move(t));
    for (const FitTerm& t : surfaces_)
      for (std::int32_t node : t.nodes) bc_.role[static_cast<std::size_t>(node)] = NodeRole::Free;
  }
  try {
    untangler_ = slide ? std::make_unique<Untangler>(input_, topology_, bc_, options_, surfaces_)
                       : std::make_unique<Untangler>(input_, topology_, motion_->targets(), options_);
  } catch (const InputError& e) {
    throw InputError(where_ + ": " + e.what());
  }
  x_ = input_.x;
  solves_ = 0;
}

RunOutput UntangleRunner::finish(RunOutput out, const BoundaryTargets& bc) const {
  out.report.method = "untangle";
  out.moved = input_;
  out.moved.x = x_;
  out.quality = detail::fill_result(out.report, out.moved, input_inverted_ == 0 ? &input_ : nullptr, bc);
  // A valid mesh where the input or the placed boundary tangled it is better than the input
  // even where the run stopped short (written, DESIGN §3.1).
  const bool was_tangled = input_inverted_ > 0 || out.extra.value("initial_inverted_elements", std::size_t{0}) > 0;
  out.extra["improved"] = out.report.valid && was_tangled;
  out.extra["predictor"] = options_.predictor;
  out.extra["reference"] = local_                                          ? "input where valid"
                           : options_.reference == UntangleReference::Input ? "input"
                                                                            : "regular";
  out.extra["boundary"] = sliding_ ? "slide" : "fixed";
  out.extra["boundary_choice"] = boundary_.mode + (boundary_why_.empty() ? std::string() : ": " + boundary_why_);
  // Distance of the sliding nodes from the surfaces they slide on (0 with the boundary fixed).
  out.extra["boundary_deviation_max"] = sliding_ ? fit_error(surfaces_, x_) : 0.0;
  return out;
}

RunOutput UntangleRunner::run_local() {
  RunOutput out;
  sliding_ = true;
  // A patch either repairs in tens of Newton steps or slides its boundary astray: a short
  // budget, then the whole mesh.
  UntangleOptions o = options_;
  o.max_newton = std::min(o.max_newton, kLocalNewton);
  for (const int layers : {1, 2}) {
    out = RunOutput();
    x_ = input_.x;
    const LocalUntangle l = untangle_locally(input_, topology_, may_slide_, boundary_.feature_angle, layers, o, x_, &input_invalid_);
    IterationCounts counts;
    count(counts, l.result);
    out.report.iterations = counts;
    out.report.history = untangle_history(l.result);
    out.report.converged = l.result.converged;
    out.report.message = l.result.message + "; repaired in a patch of " + std::to_string(l.cells) + " cells";
    out.extra["initial_inverted_elements"] = l.result.initial_inverted;
    out.extra["min_edge_quality"] = l.result.min_quality;
    out.extra["steps"] = 1;
    out.extra["patch_cells"] = l.cells;
    out = finish(std::move(out), bc_);
    out.extra["boundary_deviation_max"] = l.deviation;
    if (out.report.converged) break;
  }
  return out;
}

RunOutput UntangleRunner::run(const StepSink& on_step) {
  if (local_) {
    RunOutput out = run_local();
    if (out.report.converged) return out;
    log_progress("untangle: the patches around the inverted cells stay tangled (" + out.report.message +
                 "): the whole mesh with its boundary fixed");
    local_ = false;
    boundary_why_ = "the patches around the inverted cells stayed tangled with the boundary sliding";
    start(false);
  }
  RunOutput out = run_steps(on_step);
  const bool any_slides = std::find(may_slide_.begin(), may_slide_.end(), 1) != may_slide_.end();
  if (out.report.converged || sliding_ || boundary_.mode != "auto" || !any_slides) return out;
  log_progress("untangle: the mesh stays tangled with the boundary fixed (" + out.report.message +
               "): starting over with the boundary sliding along itself");
  boundary_why_ = "the mesh stayed tangled with the boundary fixed";
  start(true);
  return run_steps(on_step);
}

RunOutput UntangleRunner::run_steps(const StepSink& on_step) {
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
  return finish(std::move(out), bc_);
}

RunOutput UntangleRunner::solve(const Eigen::MatrixXd& target) {
  if (!untangler_) {  // one solve at a time: the whole mesh, its boundary fixed
    local_ = false;
    start(false);
  }
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
  return finish(std::move(out), detail::with_targets(bc_, target));
}

}  // namespace meshmorph

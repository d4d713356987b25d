// SPDX-License-Identifier: MIT
#include "meshmorph/app/optimize_case.h"

#include <algorithm>
#include <utility>

#include "app/detail/method_output.h"
#include "meshmorph/app/option_reader.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/log.h"
#include "meshmorph/quality/metric_registry.h"
#include "meshmorph/threads.h"

namespace meshmorph {
namespace {

// The case's boundary entries as optimize takes them. Throws for motions it has no use for.
std::vector<OptimizeEntry> optimize_entries(const CaseFile& c, const Mesh& mesh) {
  std::vector<OptimizeEntry> entries;
  for (const BoundaryCondition& b : c.boundary) {
    OptimizeEntry e;
    e.nodes = mesh.group_nodes(*mesh.find_group(b.group));
    e.key_path = b.key_path;
    if (const auto* project = std::get_if<ProjectMotion>(&b.motion)) {
      e.kind = OptimizeEntry::Kind::Project;
      e.level_set = project->target;
    } else if (std::holds_alternative<SlideMotion>(b.motion)) {
      e.kind = OptimizeEntry::Kind::Slide;
    } else if (!std::holds_alternative<FixedMotion>(b.motion)) {
      throw InputError(c.file.string() + ": " + b.key_path + ": optimize takes \"fixed\", \"slide\" and \"project\" entries");
    }
    entries.push_back(std::move(e));
  }
  return entries;
}

}  // namespace

OptimizeSettings read_optimize_settings(const CaseFile& c, const OptimizeFlags& flags, int dim, int threads) {
  OptimizeSettings s;
  OptimizeOptions& o = s.options;
  OptionReader r(c.options, c.file.string());
  std::string target = "ideal", solver = "auto", quadrature = "lobatto";
  r.read("metric", o.metric);
  r.read("quadrature", quadrature, {"lobatto", "gauss"});
  r.read("quadrature_degree", o.quadrature_degree, 0, 30);
  o.quadrature = quadrature == "gauss" ? QuadratureFamily::Gauss : QuadratureFamily::Lobatto;
  r.read("target", target, {"ideal", "input", "ideal_unit"});
  r.read("boundary", s.boundary, {"fixed", "slide", "slide-planes"});
  r.read("feature_angle", s.feature_angle, 0.0, 180.0);
  r.read("max_newton", o.max_newton, 1, 100000);
  r.read("rtol", o.rtol, 0.0, 1.0);
  r.read("growth", o.growth, 1.0, 1e6);
  r.read("det_floor", o.det_floor, 0.0, 1.0);
  r.read("solver", solver, {"auto", "cholesky", "iterative", "matrix-free", "petsc-gamg", "petsc-hypre"});
  r.finish();
  if (!flags.metric.empty()) o.metric = flags.metric;
  if (!flags.target.empty()) target = flags.target;
  if (!flags.boundary.empty()) s.boundary = flags.boundary;
  if (!flags.solver.empty()) solver = flags.solver;
  o.target = target_kind(target);
  o.solver = solver == "cholesky"      ? OptimizeSolver::Cholesky
             : solver == "iterative"   ? OptimizeSolver::Iterative
             : solver == "matrix-free" ? OptimizeSolver::MatrixFree
             : solver == "petsc-gamg"  ? OptimizeSolver::PetscGamg
             : solver == "petsc-hypre" ? OptimizeSolver::PetscHypre
                                       : OptimizeSolver::Auto;
  o.threads = threads;
  if (!o.metric.empty()) {
    const std::vector<std::string> names = metric_names(dim);
    if (std::find(names.begin(), names.end(), o.metric) == names.end())
      throw InputError(c.file.string() + ": options.metric: \"" + o.metric + "\" is not a " + std::to_string(dim) +
                       "D metric (mu2 in 2D, mu303 in 3D, mu77, mu80, distortion, distortion2)");
  }
  return s;
}

OptimizeRunner::OptimizeRunner(const CaseFile& c, Mesh mesh, int threads, const OptimizeFlags& flags)
    : where_(c.file.string()), input_(std::move(mesh)) {
  reject_unused_keys(c, "optimize", {"interface", "trim", "steps", "output_each_step", "dt"});
  check_case_against_mesh(c, input_);
  threads_ = optimize_threads(threads, static_cast<std::size_t>(input_.dim) * input_.n_nodes());
  const ScopedThreads scoped(threads_);
  settings_ = read_optimize_settings(c, flags, input_.dim, threads_);
  if (c.order && below_order(input_, *c.order)) input_ = elevate_order(input_, *c.order);
  orient_cells(c, input_);
  topology_ = build_topology(input_);
  initial_inverted_ = count_invalid_cells(input_);
  if (initial_inverted_ > 0 && settings_.options.target == TargetKind::Input)
    throw InputError(where_ + ": target \"input\" needs a valid input mesh, and " + std::to_string(initial_inverted_) +
                     " cells of it are inverted (\"ideal\" untangles it first)");
  Mesh start = input_;
  if (initial_inverted_ > 0) {
    log_progress("optimize: " + std::to_string(initial_inverted_) + " inverted cells: untangling first");
    start.x = untangled_start(input_, topology_, threads_, where_, untangle_newton_);
  }
  const BoundaryTreatment treatment = settings_.boundary == "slide"          ? BoundaryTreatment::Slide
                                      : settings_.boundary == "slide-planes" ? BoundaryTreatment::SlidePlanes
                                                                             : BoundaryTreatment::Fixed;
  constraints_ = optimize_constraints(start, topology_, optimize_entries(c, input_), treatment, settings_.feature_angle, where_);
  start_ = std::move(start.x);
}

RunOutput OptimizeRunner::run() const {
  const ScopedThreads scoped(threads_);
  const OptimizeOptions& options = settings_.options;
  Mesh start = input_;
  start.x = start_;
  Eigen::MatrixXd x = start_;
  const OptimizeResult r = optimize_mesh(start, topology_, constraints_.fixed, constraints_.slides, options, x);
  return output(r, x);
}

RunOutput OptimizeRunner::output(const OptimizeResult& r, const Eigen::MatrixXd& x) const {
  const ScopedThreads scoped(threads_);
  const OptimizeOptions& options = settings_.options;
  RunOutput out;
  Report& report = out.report;
  report.method = "optimize";
  report.converged = r.converged;
  report.message = r.message;
  report.iterations = IterationCounts{initial_inverted_ > 0 ? 1 : 0, 1, r.newton + untangle_newton_, r.linear};
  for (const OptimizeIteration& h : r.history)
    report.history.push_back({{"newton", h.newton}, {"alpha", h.alpha}, {"energy", h.energy},
                              {"gradient_norm", h.gradient_norm}, {"min_det", h.min_det}});
  out.moved = input_;
  out.moved.x = x;
  BoundaryTargets none;
  none.role.assign(input_.n_nodes(), NodeRole::Free);
  out.quality = detail::fill_result(report, out.moved, initial_inverted_ == 0 ? &input_ : nullptr, none);
  report.boundary_error_max = fit_error(constraints_.slides, x);
  report.boundary_error_l2.reset();

  const int d = input_.dim;
  nlohmann::ordered_json& extra = out.extra;
  extra["metric"] = options.metric.empty() ? std::string(default_shape_metric(d)) : options.metric;
  extra["target"] = target_name(options.target);
  extra["boundary"] = settings_.boundary;
  int degree = r.quadrature_degree;
  if (degree == 0)
    for (const CellBlock& b : input_.cells) degree = std::max(degree, metric_quadrature_degree(b.type, b.order));
  extra["quadrature"] = std::string(options.quadrature == QuadratureFamily::Lobatto ? "Gauss-Lobatto" : "Gauss") +
                        " products on tensor cells and prisms, symmetric rules on simplices, degree " +
                        std::to_string(degree);
  extra["initial_inverted_elements"] = initial_inverted_;
  extra["untangle_newton"] = untangle_newton_;
  extra["slide_nodes"] = constraints_.slide_nodes;
  extra["solver"] = r.solver;
  extra["energy_initial"] = r.energy0;
  extra["energy_final"] = r.energy;
  extra["min_det_initial"] = r.min_det0;
  extra["min_det_final"] = r.min_det;
  extra["mu_min"] = r.mu_min;
  extra["mu_mean"] = r.mu_mean;
  extra["mu_max"] = r.mu_max;
  // Valid with F below the input's (or untangled): better than the input even where Newton
  // stopped short, so written (DESIGN §3.1).
  extra["improved"] = report.valid && (initial_inverted_ > 0 || r.energy < r.energy0);
  return out;
}

}  // namespace meshmorph

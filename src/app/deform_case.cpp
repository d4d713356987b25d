// SPDX-License-Identifier: MIT
#include "meshmorph/app/deform_case.h"

#include <algorithm>
#include <string>
#include <utility>

#include "app/detail/method_output.h"
#include "meshmorph/app/option_reader.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/validity.h"

namespace meshmorph {

DeformOptions read_deform_options(const CaseFile& c, int threads) {
  DeformOptions o;
  OptionReader r(c.options, c.file.string());
  std::string method = "eikonal", density = "uniform", diffusion = "design", solver = "auto";
  r.read("method", method, {"eikonal", "laplace"});
  o.method = method == "laplace" ? DeformMethod::Laplace : DeformMethod::Eikonal;
  r.read("cvt", o.cvt);
  r.read("density", density, {"uniform", "input"});
  o.cvt_options.density = density == "input" ? CvtDensity::Input : CvtDensity::Uniform;
  r.read("cvt_tolerance", o.cvt_options.tolerance, 0.0, 1.0);
  r.read("cvt_max_iterations", o.cvt_options.max_iterations, 0, 10000000);
  r.read("feature_angle", o.cvt_options.feature_angle, 0.0, 180.0);
  r.read("alpha", o.alpha, 1e-12, 1e12);
  r.read("beta", o.beta, 0.0, 1e12);
  r.read("diffusion", diffusion, {"design", "far_field"});
  o.diffusion = diffusion == "far_field" ? DiffusionDistance::FarField : DiffusionDistance::Design;
  std::string convection = "advective";
  r.read("convection", convection, {"conservative", "advective"});
  o.conservative = convection == "conservative";
  r.read("eikonal_h", o.eikonal.h_factor, 1e-6, 1e6);
  r.read("max_newton", o.eikonal.max_newton, 1, 10000);
  r.read("solver", solver, {"auto", "cholesky", "iterative"});
  o.solver = solver == "cholesky" ? LinearSolverKind::Cholesky : solver == "iterative" ? LinearSolverKind::Iterative : LinearSolverKind::Auto;
  r.finish();
  o.threads = threads;
  return o;
}

namespace {

// The case's keys checked against `mesh`, then the mesh raised to the case's order, its cells
// oriented alike.
Mesh elevated(const CaseFile& c, Mesh mesh) {
  reject_unused_keys(c, "deform", {"interface", "trim"});
  check_case_against_mesh(c, mesh);
  if (c.order && below_order(mesh, *c.order)) mesh = elevate_order(mesh, *c.order);
  orient_cells(c, mesh);
  return mesh;
}

}  // namespace

DeformRunner::DeformRunner(const CaseFile& c, Mesh mesh, int threads)
    : where_(c.file.string()), input_(elevated(c, std::move(mesh))), exact_(input_.n_nodes()) {
  options_ = read_deform_options(c, threads);
  if (const std::size_t bad = count_invalid_cells(input_); bad > 0)
    throw InputError(where_ + ": " + std::to_string(bad) + " cells of the input mesh are inverted; "
                     "deform starts from a valid mesh (meshmorph untangle repairs it)");
  topology_ = build_topology(input_);
  motion_ = std::make_unique<BoundaryMotion>(c.boundary, c.file.string(), input_, topology_);
  const BoundaryTargets& bc = motion_->targets();
  // The exact target of nodes moved by `project`: the last step snaps them onto it.
  LevelSetOptions lo;
  lo.source = where_;
  lo.length_scale = (input_.x.rowwise().maxCoeff() - input_.x.rowwise().minCoeff()).norm();
  for (const BoundaryCondition& entry : c.boundary)
    if (const auto* m = std::get_if<ProjectMotion>(&entry.motion)) {
      std::vector<std::int32_t> nodes = input_.group_nodes(*input_.find_group(entry.group));
      std::erase_if(nodes, [&](std::int32_t v) { return bc.role[static_cast<std::size_t>(v)] != NodeRole::Prescribed; });
      exact_.add(LevelSetFunction(m->target, input_.dim, lo), nodes);
    }
  on_design_.assign(input_.n_nodes(), 0);
  for (std::size_t i = 0; i < input_.n_nodes(); ++i) on_design_[i] = bc.role[i] == NodeRole::Prescribed;
  if (std::find(on_design_.begin(), on_design_.end(), 1) == on_design_.end())
    throw InputError(where_ + ": boundary: no group moves; deform needs a design group with a motion "
                     "(translate, rotate, scale, project or displace)");
  surface_ = design_surface(input_, topology_, on_design_);
  steps_ = c.steps;
}

DeformRunner::~DeformRunner() = default;

DeformOutput DeformRunner::run(const StepSink& on_step) const {
  DeformOutput out;
  Report& report = out.report;
  const BoundaryTargets& bc = motion_->targets();
  report.method = "deform";
  report.converged = true;
  IterationCounts counts;
  Mesh moved = input_;
  int cvt_iterations = 0;
  EikonalDistances distances;
  bool cvt_converged = true;
  std::size_t cvt_pinned = 0, straightened = 0;
  for (int s = 1; s <= steps_; ++s) {
    BoundaryTargets step = bc;
    step.target = motion_->at(static_cast<double>(s) / steps_);
    const SurfaceProjection projection = [&](std::int32_t node, const Eigen::VectorXd& x) -> std::optional<Eigen::VectorXd> {
      if (s < steps_) return std::nullopt;
      return exact_.project(node, x);
    };
    DeformResult r;
    try {
      r = deform(moved, topology_, step, input_.x, options_, projection, distances);
    } catch (const InputError& e) {
      throw InputError(where_ + ": " + e.what());
    }
    counts.outer += 1;
    counts.nonlinear += options_.method == DeformMethod::Eikonal ? 2 : 0;
    counts.newton += r.newton;
    counts.linear += r.linear_solves;
    cvt_iterations += r.cvt.iterations;
    cvt_converged = cvt_converged && (!options_.cvt || r.cvt.converged);
    cvt_pinned = r.cvt.pinned;
    straightened += r.straightened_cells;
    moved.x = r.x;
    distances = r.distances;
    const std::size_t inverted = count_invalid_cells(moved);
    report.history.push_back({{"step", s}, {"cvt_iterations", r.cvt.iterations}, {"spacing_ratio_before", r.cvt.spacing_ratio_before},
                              {"spacing_ratio_after", spacing_ratio(surface_, moved.x)}, {"newton", r.newton},
                              {"straightened", static_cast<double>(r.straightened_cells)},
                              {"inverted", static_cast<double>(inverted)}});
    report.message = (steps_ > 1 ? "step " + std::to_string(s) + ": " : std::string()) + r.message;
    if (!r.converged || inverted > 0) {
      report.converged = false;
      if (inverted > 0) report.message += " left inverted cells";
      break;
    }
    if (s < steps_ && on_step) on_step(s, moved);
  }
  report.iterations = counts;
  out.quality = detail::fill_result(report, moved, &input_, bc);
  std::tie(report.boundary_error_max, report.boundary_error_l2) = design_errors(surface_, bc.target, exact_, on_design_, moved.x);
  out.design_nodes = static_cast<std::size_t>(std::count(on_design_.begin(), on_design_.end(), 1));
  out.extra["deform_method"] = options_.method == DeformMethod::Laplace ? "laplace" : "eikonal";
  out.extra["cvt"] = options_.cvt;
  out.extra["steps"] = steps_;
  out.extra["cvt_iterations"] = cvt_iterations;
  out.extra["cvt_converged"] = cvt_converged;
  out.extra["cvt_pinned_nodes"] = cvt_pinned;
  out.extra["straightened_cells"] = straightened;
  out.extra["spacing_ratio_input"] = spacing_ratio(surface_, input_.x);
  out.extra["spacing_ratio_unrepaired"] = spacing_ratio(surface_, bc.target);
  out.extra["spacing_ratio"] = spacing_ratio(surface_, moved.x);
  out.moved = std::move(moved);
  return out;
}

}  // namespace meshmorph

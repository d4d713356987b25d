// SPDX-License-Identifier: MIT
// `meshmorph deform CASE.json`: CVT surface repair and Eikonal convection volume deformation
// (paper 004).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "app/detail/method_output.h"
#include "meshmorph/app/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/commands.h"
#include "meshmorph/app/option_reader.h"
#include "meshmorph/app/report.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/geometry/level_set_function.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/methods/deform.h"

namespace meshmorph {
namespace {

struct DeformArgs {
  std::string case_file;
  std::string output;
  std::string report;
};

// The options of docs/deform.md.
DeformOptions read_options(const CaseFile& c, int threads) {
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

// The exact target of nodes moved by `project` (the last step snaps them onto it).
struct Projections {
  std::vector<LevelSetFunction> level_sets;
  std::vector<int> owner;  // per node: index into level_sets, or −1
};

Projections projections(const CaseFile& c, const Mesh& mesh, const BoundaryTargets& bc) {
  Projections p;
  p.owner.assign(mesh.n_nodes(), -1);
  LevelSetOptions lo;
  lo.source = c.file.string();
  lo.length_scale = (mesh.x.rowwise().maxCoeff() - mesh.x.rowwise().minCoeff()).norm();
  for (const BoundaryCondition& entry : c.boundary) {
    const auto* m = std::get_if<ProjectMotion>(&entry.motion);
    if (!m) continue;
    p.level_sets.emplace_back(m->target, mesh.dim, lo);
    for (std::int32_t v : mesh.group_nodes(*mesh.find_group(entry.group)))
      if (bc.role[static_cast<std::size_t>(v)] == NodeRole::Prescribed && p.owner[static_cast<std::size_t>(v)] < 0)
        p.owner[static_cast<std::size_t>(v)] = static_cast<int>(p.level_sets.size()) - 1;
  }
  return p;
}

Outcome run_deform(const DeformArgs& a, int threads, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const CaseFile c = read_case_file(a.case_file);
  reject_unused_keys(c, "deform", {"interface", "trim"});
  Mesh input = read_mesh(c.mesh);
  check_case_against_mesh(c, input);
  const DeformOptions options = read_options(c, threads);
  if (c.order && below_order(input, *c.order)) input = elevate_order(input, *c.order);
  const std::size_t input_inverted = count_invalid_cells(input);
  if (input_inverted > 0)
    throw InputError(a.case_file + ": " + std::to_string(input_inverted) + " cells of the input mesh are inverted; "
                     "deform starts from a valid mesh (meshmorph untangle repairs it)");
  std::optional<std::filesystem::path> output = a.output.empty() ? c.output : std::optional(std::filesystem::path(a.output));
  std::optional<std::filesystem::path> report_path = a.report.empty() ? c.report : std::optional(std::filesystem::path(a.report));

  const Topology topology = build_topology(input);
  const BoundaryMotion motion(c, input, topology);
  const BoundaryTargets& bc = motion.targets();
  const Projections exact = projections(c, input, bc);
  detail::check_outputs(&c, output, report_path);
  std::vector<std::uint8_t> on_design(input.n_nodes(), 0);
  for (std::size_t i = 0; i < input.n_nodes(); ++i) on_design[i] = bc.role[i] == NodeRole::Prescribed;
  if (std::find(on_design.begin(), on_design.end(), 1) == on_design.end())
    throw InputError(a.case_file + ": boundary: no group moves; deform needs a design group with a motion "
                     "(translate, rotate, scale, project or displace)");
  const DesignSurface surface = design_surface(input, topology, on_design);

  Report report;
  int step_files = 0;  // output_each_step files written
  report.method = "deform";
  report.case_file = a.case_file;
  report.converged = true;
  IterationCounts counts;
  Mesh moved = input;
  int cvt_iterations = 0;
  EikonalDistances distances;
  bool cvt_converged = true;
  std::size_t cvt_pinned = 0, straightened = 0;
  for (int s = 1; s <= c.steps; ++s) {
    BoundaryTargets step = bc;
    step.target = motion.at(static_cast<double>(s) / c.steps);
    const SurfaceProjection projection = [&](std::int32_t node, const Eigen::VectorXd& x) -> std::optional<Eigen::VectorXd> {
      const int k = exact.owner[static_cast<std::size_t>(node)];
      if (k < 0 || s < c.steps) return std::nullopt;
      return exact.level_sets[static_cast<std::size_t>(k)].closest_point(x);
    };
    DeformResult r;
    try {
      r = deform(moved, topology, step, input.x, options, projection, distances);
    } catch (const InputError& e) {
      throw InputError(a.case_file + ": " + e.what());
    }
    counts.outer += 1;
    counts.nonlinear += options.method == DeformMethod::Eikonal ? 2 : 0;
    counts.newton += r.newton;
    counts.linear += r.linear_solves;
    cvt_iterations += r.cvt.iterations;
    cvt_converged = cvt_converged && (!options.cvt || r.cvt.converged);
    cvt_pinned = r.cvt.pinned;
    straightened += r.straightened_cells;
    moved.x = r.x;
    distances = r.distances;
    const std::size_t inverted = count_invalid_cells(moved);
    report.history.push_back({{"step", s}, {"cvt_iterations", r.cvt.iterations}, {"spacing_ratio_before", r.cvt.spacing_ratio_before},
                              {"spacing_ratio_after", spacing_ratio(surface, moved.x)}, {"newton", r.newton},
                              {"straightened", static_cast<double>(r.straightened_cells)},
                              {"inverted", static_cast<double>(inverted)}});
    report.message = (c.steps > 1 ? "step " + std::to_string(s) + ": " : std::string()) + r.message;
    if (!r.converged || inverted > 0) {
      report.converged = false;
      if (inverted > 0) report.message += " left inverted cells";
      break;
    }
    if (c.output_each_step && output && s < c.steps) detail::write_step_mesh(*output, s, moved, step_files);
  }
  report.iterations = counts;
  const QualityReport q = detail::fill_result(report, moved, &input, bc);
  // The design nodes slide tangentially on purpose: the boundary error is their distance
  // from the target surface (exact where `project` gives one, else the moved facets).
  double err_max = 0.0, err_sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < input.n_nodes(); ++i) {
    if (!on_design[i]) continue;
    const Eigen::VectorXd x = moved.x.col(static_cast<Eigen::Index>(i));
    double e = distance_to_surface(surface, bc.target, x);
    if (const int k = exact.owner[i]; k >= 0)
      if (const auto p = exact.level_sets[static_cast<std::size_t>(k)].closest_point(x)) e = (*p - x).norm();
    err_max = std::max(err_max, e);
    err_sum += e * e;
    ++count;
  }
  report.boundary_error_max = err_max;
  report.boundary_error_l2 = std::sqrt(err_sum / static_cast<double>(count));
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  detail::write_result_mesh(report, moved, q, output);

  nlohmann::ordered_json extra = nlohmann::ordered_json::object();
  extra["deform_method"] = options.method == DeformMethod::Laplace ? "laplace" : "eikonal";
  extra["cvt"] = options.cvt;
  extra["steps"] = c.steps;
  extra["cvt_iterations"] = cvt_iterations;
  extra["cvt_converged"] = cvt_converged;
  extra["cvt_pinned_nodes"] = cvt_pinned;
  extra["straightened_cells"] = straightened;
  extra["spacing_ratio_input"] = spacing_ratio(surface, input.x);
  extra["spacing_ratio_unrepaired"] = spacing_ratio(surface, bc.target);
  extra["spacing_ratio"] = spacing_ratio(surface, moved.x);
  if (report_path) write_report(*report_path, report, extra);

  char line[200];
  out << "deform   " << a.case_file << " (" << extra["deform_method"].get<std::string>() << (options.cvt ? " + CVT" : "")
      << ")\n"
      << "mesh     " << input.dim << "D, " << input.n_nodes() << " nodes, " << input.n_cells() << " cells, order "
      << input.order() << "; " << count << " design nodes\n";
  std::snprintf(line, sizeof line, "work     %d step%s, %d CVT iterations, %lld Newton steps, %lld linear solves\n", c.steps,
                c.steps > 1 ? "s" : "", cvt_iterations, counts.newton, counts.linear);
  out << line;
  std::snprintf(line, sizeof line, "surface  spacing ratio %.3f at input, %.3f unrepaired, %.3f now\n",
                extra["spacing_ratio_input"].get<double>(), extra["spacing_ratio_unrepaired"].get<double>(),
                extra["spacing_ratio"].get<double>());
  out << line;
  std::snprintf(line, sizeof line, "quality  min %.4f, mean %.4f, min shape %.4f; inverted %zu\n", q.min_quality, q.mean_quality,
                q.min_shape_quality, q.inverted_elements);
  out << line;
  return detail::print_result(out, report, output, step_files);
}

}  // namespace

void add_deform_command(CLI::App& app, Command& run, const int& threads) {
  auto args = std::make_shared<DeformArgs>();
  CLI::App* cmd = app.add_subcommand("deform", "CVT surface repair and Eikonal convection deformation (paper 004)");
  cmd->add_option("CASE", args->case_file, "Case file (JSON, docs/case-file.md, docs/deform.md)")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh (overrides the case's \"output\")")->type_name("OUT");
  cmd->add_option("--report", args->report, "Report JSON (overrides the case's \"report\")")->type_name("FILE");
  cmd->callback([args, &run, &threads] {
    run = [args, &threads](std::ostream& out) { return run_deform(*args, threads, out); };
  });
}

}  // namespace meshmorph

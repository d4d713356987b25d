// SPDX-License-Identifier: MIT
// `meshmorph optimize MESH | CASE.json`: TMOP mesh optimization with a fixed or sliding boundary.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <omp.h>
#include <Eigen/Eigenvalues>

#include "app/detail/method_output.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/commands.h"
#include "meshmorph/app/option_reader.h"
#include "meshmorph/app/report.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/log.h"
#include "meshmorph/methods/optimize.h"
#include "meshmorph/methods/untangle.h"
#include "meshmorph/quality/metric_registry.h"

namespace meshmorph {
namespace {

struct OptimizeArgs {
  std::string input;  // a mesh or a case file (.json)
  std::string output, report, metric, target, boundary, solver;
};

struct OptimizeSettings {
  OptimizeOptions options;
  std::string boundary = "fixed";  // what happens to boundary nodes that no case entry names
  double feature_angle = 30.0;     // degrees: sliding patches split where the normals turn more
};

// The options of docs/optimize.md; the command line overrides the case file.
OptimizeSettings read_settings(const nlohmann::json& json, const std::string& file, const OptimizeArgs& a, int threads) {
  OptimizeSettings s;
  OptimizeOptions& o = s.options;
  OptionReader r(json, file);
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
  r.read("solver", solver, {"auto", "cholesky", "iterative", "matrix-free"});
  r.finish();
  if (!a.metric.empty()) o.metric = a.metric;
  if (!a.target.empty()) target = a.target;
  if (!a.boundary.empty()) s.boundary = a.boundary;
  if (!a.solver.empty()) solver = a.solver;
  o.target = target_kind(target);
  o.solver = solver == "cholesky"      ? OptimizeSolver::Cholesky
             : solver == "iterative"   ? OptimizeSolver::Iterative
             : solver == "matrix-free" ? OptimizeSolver::MatrixFree
                                       : OptimizeSolver::Auto;
  o.threads = threads;
  return s;
}

// Untangles a tangled input with its boundary fixed (paper 001, regular reference): TMOP needs
// a valid start. Throws InputError when untangling does not reach a valid mesh.
Eigen::MatrixXd untangled(const Mesh& mesh, const Topology& topology, const std::string& input, int threads,
                          long long& newton) {
  const BoundaryTargets bc = detail::fixed_boundary(mesh, topology);
  UntangleOptions uo;
  uo.reference = UntangleReference::Regular;
  uo.threads = threads;
  // In 3D CG-AMG: the start needs only be valid, and CHOLMOD's factor of a high-order 3D
  // Hessian would be the run's peak (untangle3d: 158 MB, against 84 MB with CG-AMG).
  if (mesh.dim == 3) uo.solver = LinearSolverKind::Iterative;
  Untangler untangler(mesh, topology, bc, uo);
  Eigen::MatrixXd x = mesh.x;
  const UntangleResult r = untangler.solve(mesh.x, x);
  newton = r.newton;
  Mesh moved = mesh;
  moved.x = x;
  if (count_invalid_cells(moved) > 0)
    throw InputError(input + ": the mesh is tangled and untangling with its boundary fixed failed: " + r.message);
  return x;
}

// The slide constraints of a case: `project` entries slide on their level set (their nodes
// are first moved onto it, e.g. the new nodes of an elevated mesh; that must leave `mesh`
// valid), `slide` entries on the plane of their group, or when its nodes are not on one
// plane, on the smooth patches of its boundary facets (boundary_slides).
std::vector<FitTerm> case_slides(const CaseFile& c, Mesh& mesh, const Topology& topology, double feature_angle,
                                 std::vector<std::uint8_t>& fixed) {
  const int d = mesh.dim;
  const double size = (mesh.x.rowwise().maxCoeff() - mesh.x.rowwise().minCoeff()).norm();
  LevelSetOptions lso;
  lso.source = c.file.string();
  lso.length_scale = size;
  std::vector<FitTerm> slides;
  for (const BoundaryCondition& b : c.boundary) {
    std::vector<std::int32_t> nodes = mesh.group_nodes(*mesh.find_group(b.group));
    const std::string where = c.file.string() + ": " + b.key_path;
    if (const auto* project = std::get_if<ProjectMotion>(&b.motion)) {
      LevelSetFunction sigma(project->target, d, lso);
      double moved = 0.0;
      for (std::int32_t node : nodes) {
        const std::optional<Eigen::VectorXd> p = sigma.closest_point(mesh.x.col(node));
        if (!p)
          throw InputError(where + ".project: node " +
                           std::to_string(mesh.node_tags.empty() ? node + 1 : mesh.node_tags[static_cast<std::size_t>(node)]) +
                           " has no closest point on the level set");
        moved = std::max(moved, (*p - mesh.x.col(node)).norm());
        mesh.x.col(node) = *p;
      }
      if (const std::size_t bad = count_invalid_cells(mesh); bad > 0)
        throw InputError(where + ".project: moving the group's nodes onto the level set (by up to " + std::to_string(moved) +
                         ") inverts " + std::to_string(bad) + " cells; fit them onto it first");
      slides.push_back({std::move(sigma), std::move(nodes)});
    } else if (std::holds_alternative<SlideMotion>(b.motion)) {
      // The group's plane: through its centroid, normal to its least-spread direction.
      const Eigen::MatrixXd X = mesh.x(Eigen::all, nodes);
      const Eigen::VectorXd centre = X.rowwise().mean();
      const Eigen::MatrixXd Y = X.colwise() - centre;
      const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(Y * Y.transpose());
      const Eigen::VectorXd normal = eig.eigenvectors().col(0);
      if ((normal.transpose() * Y).cwiseAbs().maxCoeff() > 1e-10 * size) {
        // Curved: the boundary facets whose nodes are all in the group.
        std::vector<std::uint8_t> in(mesh.n_nodes(), 0);
        for (std::int32_t node : nodes) in[static_cast<std::size_t>(node)] = 1;
        std::vector<std::int32_t> facets;
        for (std::int32_t f : topology.boundary_facets) {
          const CellFacet cf = topology.facets[static_cast<std::size_t>(f)][0];
          const auto [blk, cell] = topology.locate(cf.cell);
          const std::vector<std::int32_t> fn = facet_nodes(mesh.cells[blk], cell, cf.local);
          if (std::all_of(fn.begin(), fn.end(), [&](std::int32_t n) { return in[static_cast<std::size_t>(n)] != 0; }))
            facets.push_back(f);
        }
        if (facets.empty()) throw InputError(where + ".slide: the group's nodes are not on one plane and hold no boundary facet");
        for (FitTerm& t : boundary_slides(mesh, topology, facets, feature_angle, true, fixed)) slides.push_back(std::move(t));
        continue;
      }
      slides.push_back({LevelSetFunction(LevelSet{PlaneLevelSet{centre, normal}, b.key_path}, d, lso), std::move(nodes)});
    } else if (std::holds_alternative<FixedMotion>(b.motion)) {
      continue;  // below, so that `fixed` wins over a slide entry whatever the order
    } else {
      throw InputError(where + ": optimize takes \"fixed\", \"slide\" and \"project\" entries");
    }
    for (std::int32_t node : slides.back().nodes) std::fill_n(fixed.begin() + d * node, d, 0);
  }
  for (const BoundaryCondition& b : c.boundary)
    if (std::holds_alternative<FixedMotion>(b.motion))
      for (std::int32_t node : mesh.group_nodes(*mesh.find_group(b.group))) std::fill_n(fixed.begin() + d * node, d, 1);
  return slides;
}

// A node on d or more surfaces (a corner) cannot slide: fixed and dropped from every entry.
void fix_corners(std::vector<FitTerm>& slides, int d, std::size_t n_nodes, std::vector<std::uint8_t>& fixed) {
  std::vector<int> count(n_nodes, 0);
  for (const FitTerm& t : slides)
    for (std::int32_t node : t.nodes) ++count[static_cast<std::size_t>(node)];
  for (FitTerm& t : slides)
    std::erase_if(t.nodes, [&](std::int32_t node) {
      const bool corner = count[static_cast<std::size_t>(node)] >= d || fixed[static_cast<std::size_t>(d * node)];
      if (corner) std::fill_n(fixed.begin() + d * node, d, 1);
      return corner;
    });
}

Outcome run_optimize(const OptimizeArgs& a, int threads, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const bool is_case = std::filesystem::path(a.input).extension() == ".json";
  std::optional<CaseFile> c;
  Mesh mesh;
  if (is_case) {
    c = read_case_file(a.input);
    reject_unused_keys(*c, "optimize", {"interface", "trim", "steps", "output_each_step"});
    mesh = read_mesh(c->mesh);
    check_case_against_mesh(*c, mesh);
  } else {
    mesh = read_mesh(a.input);
  }
  // Every element loop of the run (untangling, quality, validity) on the threads optimize
  // picks for this size: one for small meshes.
  threads = optimize_threads(threads, static_cast<std::size_t>(mesh.dim) * mesh.n_nodes());
  if (threads > 0) omp_set_num_threads(threads);
  const OptimizeSettings settings = read_settings(c ? c->options : nlohmann::json::object(), a.input, a, threads);
  const OptimizeOptions& options = settings.options;
  const int d = mesh.dim;
  if (!options.metric.empty()) {
    const std::vector<std::string> names = metric_names(d);
    if (std::find(names.begin(), names.end(), options.metric) == names.end())
      throw InputError(a.input + ": options.metric: \"" + options.metric + "\" is not a " + std::to_string(d) +
                       "D metric (mu2 in 2D, mu303 in 3D, mu77, mu80, distortion, distortion2)");
  }
  if (c && c->order && below_order(mesh, *c->order)) mesh = elevate_order(mesh, *c->order);

  std::optional<std::filesystem::path> output, report_path;
  if (!a.output.empty()) output = a.output;
  else if (c) output = c->output;
  else {  // a bare mesh: next to it, never over it
    const std::filesystem::path in(a.input);
    output = in.parent_path() / (in.stem().string() + "_optimized" + in.extension().string());
  }
  if (!a.report.empty()) report_path = a.report;
  else if (c) report_path = c->report;

  const Topology topology = build_topology(mesh);
  const std::size_t initial_inverted = count_invalid_cells(mesh);
  if (initial_inverted > 0 && options.target == TargetKind::Input)
    throw InputError(a.input + ": target \"input\" needs a valid input mesh, and " + std::to_string(initial_inverted) +
                     " cells of it are inverted (\"ideal\" untangles it first)");
  long long untangle_newton = 0;
  Mesh start_mesh = mesh;
  if (initial_inverted > 0) {
    log_progress("optimize: " + std::to_string(initial_inverted) + " inverted cells: untangling first");
    start_mesh.x = untangled(mesh, topology, a.input, threads, untangle_newton);
  }

  // Unknowns: interior nodes free; the boundary as the case's entries and `boundary` say.
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(d) * mesh.n_nodes(), 0);
  std::vector<FitTerm> slides;
  if (settings.boundary != "fixed") {
    slides = boundary_slides(start_mesh, topology, topology.boundary_facets, settings.feature_angle,
                             settings.boundary == "slide", fixed);
  } else {
    for (std::int32_t node : boundary_nodes(mesh, topology)) std::fill_n(fixed.begin() + d * node, d, 1);
  }
  if (c) {
    std::vector<FitTerm> more = case_slides(*c, start_mesh, topology, settings.feature_angle, fixed);  // may move nodes onto level sets
    // A node that a case entry names follows that entry, not the automatic planes.
    std::vector<std::uint8_t> named(mesh.n_nodes(), 0);
    for (const BoundaryCondition& b : c->boundary)
      for (std::int32_t node : mesh.group_nodes(*mesh.find_group(b.group))) named[static_cast<std::size_t>(node)] = 1;
    for (FitTerm& t : slides) std::erase_if(t.nodes, [&](std::int32_t node) { return named[static_cast<std::size_t>(node)] != 0; });
    for (FitTerm& t : more) slides.push_back(std::move(t));
  }
  fix_corners(slides, d, mesh.n_nodes(), fixed);
  std::erase_if(slides, [](const FitTerm& t) { return t.nodes.empty(); });
  std::size_t slide_nodes = 0;
  {
    std::vector<std::uint8_t> seen(mesh.n_nodes(), 0);
    for (const FitTerm& t : slides)
      for (std::int32_t node : t.nodes) slide_nodes += seen[static_cast<std::size_t>(node)]++ == 0 ? 1 : 0;
  }

  detail::check_outputs(c ? &*c : nullptr, output, report_path);  // every input is read by now
  Eigen::MatrixXd x = start_mesh.x;
  const OptimizeResult r = optimize_mesh(start_mesh, topology, fixed, slides, options, x);

  Report report;
  report.method = "optimize";
  if (c) report.case_file = a.input;
  report.converged = r.converged;
  report.message = r.message;
  report.iterations = IterationCounts{initial_inverted > 0 ? 1 : 0, 1, r.newton + untangle_newton, r.linear};
  for (const OptimizeIteration& h : r.history)
    report.history.push_back({{"newton", h.newton}, {"alpha", h.alpha}, {"energy", h.energy},
                              {"gradient_norm", h.gradient_norm}, {"min_det", h.min_det}});
  Mesh moved = mesh;
  moved.x = x;
  BoundaryTargets none;
  none.role.assign(mesh.n_nodes(), NodeRole::Free);
  const QualityReport q = detail::fill_result(report, moved, initial_inverted == 0 ? &mesh : nullptr, none);
  double slide_error = 0.0;  // max |σ| of the slide nodes: their distance from their surfaces
  for (const FitTerm& t : slides)
    for (std::int32_t node : t.nodes) slide_error = std::max(slide_error, std::abs(t.sigma.value(x.col(node))));
  report.boundary_error_max = slide_error;
  report.boundary_error_l2.reset();
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  detail::write_result_mesh(report, moved, q, output);

  nlohmann::ordered_json extra = nlohmann::ordered_json::object();
  extra["metric"] = options.metric.empty() ? (d == 2 ? "mu2" : "mu303") : options.metric;
  extra["target"] = target_name(options.target);
  extra["boundary"] = settings.boundary;
  int degree = r.quadrature_degree;
  if (degree == 0)
    for (const CellBlock& b : mesh.cells) degree = std::max(degree, metric_quadrature_degree(b.type, b.order));
  extra["quadrature"] = std::string(options.quadrature == QuadratureFamily::Lobatto ? "Gauss-Lobatto" : "Gauss") +
                        " products on tensor cells, symmetric rules on simplices, degree " + std::to_string(degree);
  extra["initial_inverted_elements"] = initial_inverted;
  extra["untangle_newton"] = untangle_newton;
  extra["slide_nodes"] = slide_nodes;
  extra["solver"] = r.solver;
  extra["energy_initial"] = r.energy0;
  extra["energy_final"] = r.energy;
  extra["min_det_initial"] = r.min_det0;
  extra["min_det_final"] = r.min_det;
  extra["mu_min"] = r.mu_min;
  extra["mu_mean"] = r.mu_mean;
  extra["mu_max"] = r.mu_max;
  if (report_path) write_report(*report_path, report, extra);

  char line[240];
  out << "optimize " << a.input << " (" << extra["metric"].get<std::string>() << ", target "
      << extra["target"].get<std::string>() << ", boundary " << settings.boundary << ")\n"
      << "mesh     " << d << "D, " << mesh.n_nodes() << " nodes, " << mesh.n_cells() << " cells, order " << mesh.order()
      << "; " << slide_nodes << " sliding nodes" << (initial_inverted ? "; " + std::to_string(initial_inverted) + " inverted, untangled first" : std::string())
      << "\n";
  std::snprintf(line, sizeof line, "work     %lld Newton steps, %lld %s (%s)\n", r.newton, r.linear,
                r.solver == "matrix-free" ? "CG iterations" : "linear solves", r.solver.empty() ? "none" : r.solver.c_str());
  out << line;
  std::snprintf(line, sizeof line, "quality  F %.6g -> %.6g; mu min/mean/max %.4g / %.4g / %.4g; min det J %.3g -> %.3g; inverted %zu\n",
                r.energy0, r.energy, r.mu_min, r.mu_mean, r.mu_max, r.min_det0, r.min_det, q.inverted_elements);
  out << line;
  return detail::print_result(out, report, output);
}

}  // namespace

void add_optimize_command(CLI::App& app, Command& run, const int& threads) {
  auto args = std::make_shared<OptimizeArgs>();
  CLI::App* cmd = app.add_subcommand("optimize", "TMOP mesh optimization with a fixed or sliding boundary (paper 003 §2.2)");
  cmd->add_option("INPUT", args->input, "Mesh, or case file (JSON, docs/case-file.md)")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh (default: the case's \"output\"; for a mesh, NAME_optimized.EXT)")
      ->type_name("OUT");
  cmd->add_option("--report", args->report, "Report JSON (overrides the case's \"report\")")->type_name("FILE");
  cmd->add_option("--metric", args->metric, "mu2 (2D) | mu303 (3D) | mu77 | mu80 | distortion | distortion2")
      ->check(CLI::IsMember({"mu2", "mu303", "mu77", "mu80", "distortion", "distortion2"}));
  cmd->add_option("--target", args->target, "ideal (default) | input | ideal_unit (MFEM's -tid 1)")
      ->check(CLI::IsMember({"ideal", "input", "ideal_unit"}));
  cmd->add_option("--boundary", args->boundary,
                  "fixed (default) | slide (on the boundary's own planes and curved facets) | slide-planes (on its planes only)")
      ->check(CLI::IsMember({"fixed", "slide", "slide-planes"}));
  cmd->add_option("--solver", args->solver, "auto (default) | cholesky | iterative | matrix-free")
      ->check(CLI::IsMember({"auto", "cholesky", "iterative", "matrix-free"}));
  cmd->callback([args, &run, &threads] {
    run = [args, &threads](std::ostream& out) { return run_optimize(*args, threads, out); };
  });
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
// `meshmorph untangle CASE.json | MESH`: simultaneous untangling and smoothing (paper 001).
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "app/detail/method_output.h"
#include "meshmorph/app/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/commands.h"
#include "meshmorph/app/report.h"
#include "meshmorph/app/untangle_case.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/methods/untangle.h"

namespace meshmorph {
namespace {

struct UntangleArgs {
  std::string input;  // a case file (.json) or a mesh
  std::string output;
  std::string report;
};

Outcome run_untangle(const UntangleArgs& a, int threads, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const bool is_case = std::filesystem::path(a.input).extension() == ".json";
  std::optional<CaseFile> c;
  Mesh input;
  if (is_case) {
    c = read_case_file(a.input);
    reject_unused_keys(*c, "untangle", {"interface", "trim"});
    input = read_mesh(c->mesh);
    check_case_against_mesh(*c, input);
  } else {
    input = read_mesh(a.input);
  }
  std::optional<UntangleReference> reference;
  UntangleOptions options = read_untangle_options(c ? c->options : nlohmann::json::object(), a.input, threads, reference);
  if (c && c->order && below_order(input, *c->order)) input = elevate_order(input, *c->order);
  const std::size_t input_inverted = count_invalid_cells(input);
  resolve_untangle_reference(options, reference, input_inverted, a.input);

  std::optional<std::filesystem::path> output, report_path;
  if (!a.output.empty()) output = a.output;
  else if (c) output = c->output;
  else {  // a bare mesh: next to it, never over it
    const std::filesystem::path in(a.input);
    output = in.parent_path() / (in.stem().string() + "_untangled" + in.extension().string());
  }
  if (!a.report.empty()) report_path = a.report;
  else if (c) report_path = c->report;

  const Topology topology = build_topology(input);
  std::optional<BoundaryMotion> motion;
  BoundaryTargets bare;
  if (c) motion.emplace(*c, input, topology);
  else bare = detail::fixed_boundary(input, topology);
  const BoundaryTargets& bc = motion ? motion->targets() : bare;
  detail::check_outputs(c ? &*c : nullptr, output, report_path);
  const int steps = c ? c->steps : 1;

  Report report;
  int step_files = 0;  // output_each_step files written
  report.method = "untangle";
  if (c) report.case_file = a.input;
  std::unique_ptr<Untangler> untangler;
  try {
    untangler = std::make_unique<Untangler>(input, topology, bc, options);
  } catch (const InputError& e) {
    throw InputError(a.input + ": " + e.what());
  }
  Eigen::MatrixXd x = input.x;
  IterationCounts counts;
  std::size_t initial_inverted = 0;
  double min_edge_quality = 0.0;
  report.converged = true;
  for (int s = 1; s <= steps; ++s) {
    const Eigen::MatrixXd target = motion ? motion->at(static_cast<double>(s) / steps) : input.x;
    const UntangleResult r = untangler->solve(target, x, s);
    if (s == 1) initial_inverted = r.initial_inverted;
    counts.outer += r.delta_updates;
    counts.nonlinear += 1;
    counts.newton += r.newton;
    counts.linear += r.linear;
    min_edge_quality = r.min_quality;
    for (HistoryRow& row : untangle_history(r)) report.history.push_back(std::move(row));
    report.message = (steps > 1 ? "step " + std::to_string(s) + ": " : std::string()) + r.message;
    if (!r.converged) {
      report.converged = false;
      break;
    }
    if (c && c->output_each_step && output && s < steps) {
      Mesh moved = input;
      moved.x = x;
      detail::write_step_mesh(*output, s, moved, step_files);
    }
  }
  report.iterations = counts;

  Mesh moved = input;
  moved.x = x;
  const QualityReport q = detail::fill_result(report, moved, input_inverted == 0 ? &input : nullptr, bc);
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // A mesh only when the run reached its goal; the report always.
  detail::write_result_mesh(report, moved, q, output);
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();
  extra["initial_inverted_elements"] = initial_inverted;
  extra["min_edge_quality"] = min_edge_quality;
  extra["steps"] = steps;
  extra["predictor"] = options.predictor;
  extra["reference"] = options.reference == UntangleReference::Input ? "input" : "regular";
  if (report_path) write_report(*report_path, report, extra);

  char line[200];
  out << "untangle " << a.input << " (reference " << extra["reference"].get<std::string>() << ")\n"
      << "mesh     " << input.dim << "D, " << input.n_nodes() << " nodes, " << input.n_cells() << " cells, order "
      << input.order() << "; " << initial_inverted << " inverted once the boundary is placed\n";
  std::snprintf(line, sizeof line, "work     %d step%s, %lld Newton steps, %lld delta updates, %lld linear solves\n",
                steps, steps > 1 ? "s" : "", counts.newton, counts.outer, counts.linear);
  out << line;
  std::snprintf(line, sizeof line, "quality  q_min (eq. 3) %.4f, min shape quality %.4f; inverted %zu\n", min_edge_quality,
                q.min_shape_quality, q.inverted_elements);
  out << line;
  return detail::print_result(out, report, output, step_files);
}

}  // namespace

void add_untangle_command(CLI::App& app, Command& run, const int& threads) {
  auto args = std::make_shared<UntangleArgs>();
  CLI::App* cmd = app.add_subcommand("untangle", "Untangle and smooth a mesh after a boundary motion (paper 001)");
  cmd->add_option("INPUT", args->input, "Case file (JSON, docs/case-file.md) or a mesh whose boundary stays fixed")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh (default: the case's \"output\"; for a mesh, NAME_untangled.EXT)")
      ->type_name("OUT");
  cmd->add_option("--report", args->report, "Report JSON (overrides the case's \"report\")")->type_name("FILE");
  cmd->callback([args, &run, &threads] {
    run = [args, &threads](std::ostream& out) { return run_untangle(*args, threads, out); };
  });
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
// `meshmorph morph CASE.json`: boundary-displacement morphing by the augmented Lagrangian of
// paper 000, or one of the two baselines (options.method = "laplace" | "elastic").
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "app/detail/method_output.h"
#include "meshmorph/app/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/commands.h"
#include "meshmorph/app/morph_case.h"
#include "meshmorph/app/report.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/log.h"
#include "meshmorph/methods/baselines.h"
#include "meshmorph/methods/morph.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph {
namespace {

struct MorphArgs {
  std::string case_file;
  std::string output;
  std::string report;
};

Outcome run_morph(const MorphArgs& a, int threads, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const CaseFile c = read_case_file(a.case_file);
  reject_unused_keys(c, "morph", {"interface", "trim"});
  Mesh input = read_mesh(c.mesh);
  check_case_against_mesh(c, input);
  const MorphSettings settings = read_morph_settings(c, threads);
  if (c.order && below_order(input, *c.order)) input = elevate_order(input, *c.order);
  if (const std::size_t bad = count_invalid_cells(input); bad > 0)
    throw InputError(c.mesh.string() + ": " + std::to_string(bad) +
                     " inverted elements: morph needs a valid input mesh (untangle recovers one)");
  const std::optional<std::filesystem::path> output = a.output.empty() ? c.output : std::optional(std::filesystem::path(a.output));
  const std::optional<std::filesystem::path> report_path = a.report.empty() ? c.report : std::optional(std::filesystem::path(a.report));

  const Topology topology = build_topology(input);
  const BoundaryMotion motion(c, input, topology);
  const BoundaryTargets& bc = motion.targets();
  detail::check_outputs(&c, output, report_path);

  Report report;
  int step_files = 0;  // output_each_step files written
  report.method = settings.method == "morph" ? "morph" : "morph/" + settings.method;
  report.case_file = a.case_file;
  Eigen::MatrixXd x = input.x;
  long long krylov = 0;  // CG iterations, also those preconditioned by a Cholesky factor (printed, not in the report)
  std::size_t guarded = 0;  // cells guarded at their validity samples (MorphResult::guarded_cells)
  nlohmann::ordered_json finishes = nlohmann::ordered_json::array();  // untangle passes (MorphResult::finish)
  if (settings.method == "morph") {
    Morpher morpher(input, topology, bc, settings.morph);
    IterationCounts counts;
    report.converged = true;
    for (int s = 1; s <= c.steps; ++s) {
      const MorphResult r = morpher.solve(motion.at(static_cast<double>(s) / c.steps), x, s);
      counts.outer += r.outer;
      counts.nonlinear += r.nonlinear;
      counts.newton += r.newton;
      counts.linear += r.linear;
      krylov += r.krylov;
      guarded = r.guarded_cells;
      for (HistoryRow& row : morph_history(r)) report.history.push_back(std::move(row));
      if (r.finish) {
        finishes.push_back(untangle_pass(*r.finish, s));
        if (r.converged) report.message = (c.steps > 1 ? "step " + std::to_string(s) + ": " : std::string()) + r.message;
      }
      if (!r.converged) {
        report.converged = false;
        report.message = (c.steps > 1 ? "step " + std::to_string(s) + ": " : std::string()) + r.message;
        break;
      }
      if (c.output_each_step && output && s < c.steps) {
        Mesh moved = input;
        moved.x = x;
        detail::write_step_mesh(*output, s, moved, step_files);
      }
    }
    report.iterations = counts;
  } else {
    // With `steps`, each increment is one linear solve on the mesh the last one left (the
    // incremental Laplacian / elasticity of the mesh-motion literature).
    Mesh current = input;
    BoundaryTargets step = bc;
    long long solves = 0;
    report.converged = true;
    for (int s = 1; s <= c.steps && report.converged; ++s) {
      step.target = motion.at(static_cast<double>(s) / c.steps);
      const BaselineResult r = settings.method == "laplace" ? laplace_morph(current, topology, step, settings.baseline)
                                                            : elastic_morph(current, topology, step, settings.baseline);
      solves += r.linear_solves;
      current.x = r.x;
      report.converged = r.linear.ok;
      if (!r.linear.ok) {
        report.message = (c.steps > 1 ? "step " + std::to_string(s) + ": " : std::string()) +
                         "the linear solver did not converge: " + r.linear.message;
      } else if (s < c.steps) {
        // The next increment's stiffness needs valid cells; a baseline that inverted some ends here.
        if (const std::size_t bad = count_invalid_cells(current); bad > 0) {
          report.converged = false;
          report.message = "step " + std::to_string(s) + ": " + std::to_string(bad) + " inverted elements";
        } else if (c.output_each_step && output) {
          detail::write_step_mesh(*output, s, current, step_files);
        }
      }
    }
    x = current.x;
    report.iterations = IterationCounts{0, c.steps, 0, solves};
  }

  Mesh moved = input;
  moved.x = x;
  const QualityReport q = detail::fill_result(report, moved, &input, bc);
  if (report.converged && report.message.empty()) report.message = "boundary reached, mesh valid";
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // Only a converged, valid result is written as a mesh (issue 3: a run that misses its goal
  // writes none); the report is always written.
  detail::write_result_mesh(report, moved, q, output);
  nlohmann::ordered_json extra = nlohmann::ordered_json::object();
  if (settings.method == "morph") {
    extra["guarded_cells"] = guarded;
    extra["untangle_passes"] = finishes;
  }
  if (report_path) write_report(*report_path, report, extra);

  out << "morph    " << a.case_file << " (" << report.method << ")\n"
      << "mesh     " << input.dim << "D, " << input.n_nodes() << " nodes, " << input.n_cells() << " cells, order "
      << input.order() << "\n";
  if (report.iterations)
    out << "work     " << report.iterations->outer << " AL iterations, " << report.iterations->nonlinear
        << " nonlinear solves, " << report.iterations->newton << " Newton steps, " << report.iterations->linear
        << " linear solves" << (krylov > 0 ? " (" + std::to_string(krylov) + " CG iterations)" : std::string())
        << (guarded > 0 ? "; " + std::to_string(guarded) + " cells guarded at their validity samples" : std::string())
        << "\n";
  char line[160];
  std::snprintf(line, sizeof line, "quality  min %.4f, mean %.4f; inverted %zu\n", q.min_quality, q.mean_quality,
                q.inverted_elements);
  out << line;
  std::snprintf(line, sizeof line, "boundary max error %.3g, rms %.3g\n", *report.boundary_error_max, *report.boundary_error_l2);
  out << line;
  return detail::print_result(out, report, output, step_files);
}

}  // namespace

void add_morph_command(CLI::App& app, Command& run, const int& threads) {
  auto args = std::make_shared<MorphArgs>();
  CLI::App* cmd = app.add_subcommand("morph", "Move the mesh to follow a prescribed boundary motion (paper 000)");
  cmd->add_option("CASE", args->case_file, "Case file (JSON, see docs/case-file.md)")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh (overrides the case's \"output\")")->type_name("OUT");
  cmd->add_option("--report", args->report, "Report JSON (overrides the case's \"report\")")->type_name("FILE");
  cmd->callback([args, &run, &threads] {
    run = [args, &threads](std::ostream& out) { return run_morph(*args, threads, out); };
  });
}

}  // namespace meshmorph

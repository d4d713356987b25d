// SPDX-License-Identifier: MIT
// `meshmorph deform CASE.json`: CVT surface repair and Eikonal convection volume deformation
// (paper 004).
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/detail/output_files.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/deform_case.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

struct DeformArgs {
  std::string case_file;
  std::string output;
  std::string report;
};

Outcome run_deform(const DeformArgs& a, int threads, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const CaseFile c = read_case_file(a.case_file);
  const DeformRunner runner(c, read_mesh(c.mesh), threads);
  const auto output = detail::output_path(a.output, &c, a.case_file);
  const auto report_path = detail::report_path(a.report, &c);
  detail::check_outputs(&c, output, report_path);

  int step_files = 0;
  DeformOutput run = runner.run([&](int step, const Mesh& mesh) {
    if (c.output_each_step && output) detail::write_step_mesh(*output, step, mesh, step_files);
  });
  detail::write_run(run, output, report_path, a.case_file, seconds_since(start));

  const nlohmann::ordered_json& extra = run.extra;
  const IterationCounts& counts = *run.report.iterations;
  char line[200];
  out << "deform   " << a.case_file << " (" << extra["deform_method"].get<std::string>() << (runner.options().cvt ? " + CVT" : "")
      << ")\n"
      << detail::mesh_line(runner.input()) << "; " << run.design_nodes << " design nodes\n";
  std::snprintf(line, sizeof line, "work     %d step%s, %d CVT iterations, %lld Newton steps, %lld linear solves\n", c.steps,
                c.steps > 1 ? "s" : "", extra["cvt_iterations"].get<int>(), counts.newton, counts.linear);
  out << line;
  std::snprintf(line, sizeof line, "surface  spacing ratio %.3f at input, %.3f unrepaired, %.3f now\n",
                extra["spacing_ratio_input"].get<double>(), extra["spacing_ratio_unrepaired"].get<double>(),
                extra["spacing_ratio"].get<double>());
  out << line;
  std::snprintf(line, sizeof line, "quality  min %.4f, mean %.4f, min shape %.4f; inverted %zu\n", run.quality.min_quality,
                run.quality.mean_quality, run.quality.min_shape_quality, run.quality.inverted_elements);
  out << line;
  return detail::print_result(out, run.report, output, step_files);
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

// SPDX-License-Identifier: MIT
// `meshmorph untangle CASE.json | MESH`: simultaneous untangling and smoothing (paper 001).
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/detail/method_command.h"
#include "cli/detail/output_files.h"
#include "cli/detail/series_output.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/untangle_case.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph::detail {
namespace {

struct UntangleArgs : MethodArgs {
  int max_newton = 0;
  double eps_q = -1.0;
  std::string boundary;
};

Outcome run_untangle(const UntangleArgs& a, int threads, std::ostream& out) {
  const RunTimings timings;
  const std::optional<CaseFile> c = case_or_mesh(a.input);
  CaseFile run_case = with_flags(c ? *c : bare_case(a.input), a);
  set_option(run_case, "max_newton", a.max_newton, a.max_newton > 0);
  set_option(run_case, "eps_q", a.eps_q, a.eps_q >= 0.0);
  set_option(run_case, "boundary", a.boundary, !a.boundary.empty());
  UntangleRunner runner(run_case, read_mesh(c ? c->mesh : std::filesystem::path(a.input)), threads);
  const RunFiles files = run_files(a.output, a.report, a.plot, c ? &*c : nullptr, a.input, "_untangled");

  SeriesOutput series(runner.input(), c ? &*c : nullptr, files);
  RunOutput run = runner.run([&](int step, const Mesh& mesh) {
    series.step(step, mesh);
  });
  series.finish(run, timings);

  const IterationCounts& counts = *run.report.iterations;
  const int steps = run.extra["steps"].get<int>();
  char line[240];
  out << "untangle " << a.input << " (reference " << run.extra["reference"].get<std::string>() << ")\n"
      << mesh_line(runner.input()) << "; " << run.extra["initial_inverted_elements"].get<std::size_t>()
      << " inverted once the boundary is placed\n";
  if (runner.sliding()) {
    std::snprintf(line, sizeof line, "boundary slides along itself (%s); max distance from its surface %.3g\n",
                  run.extra["boundary_choice"].get<std::string>().c_str(), run.extra["boundary_deviation_max"].get<double>());
    out << line;
  }
  std::snprintf(line, sizeof line, "work     %d step%s, %lld Newton steps, %lld delta updates, %lld linear solves\n",
                steps, steps > 1 ? "s" : "", counts.newton, counts.outer, counts.linear);
  out << line;
  std::snprintf(line, sizeof line, "quality  q_min (eq. 3) %.4f, min shape quality %.4f; inverted %zu\n",
                run.extra["min_edge_quality"].get<double>(), run.quality.min_shape_quality, run.quality.inverted_elements);
  out << line;
  return print_result(out, run.report, files.output, series.step_files(), writes_mesh(run));
}

}  // namespace

void add_untangle_command(CLI::App& app, Command& run, const int& threads) {
  auto args = std::make_shared<UntangleArgs>();
  CLI::App* cmd = add_method_command(
      app, run, threads,
      {"untangle", "Untangle and smooth a mesh after a boundary motion (paper 001)", "INPUT",
       "Case file (JSON, docs/case-file.md) or a mesh (its boundary fixed, or sliding along itself where it must move)",
       "Output mesh (default: the case's \"output\"; for a mesh, NAME_untangled.EXT)"},
      args, &run_untangle);
  cmd->add_option("--max-newton", args->max_newton, "Newton steps per step of a time series (default 300)")
      ->check(CLI::Range(1, 100000))
      ->type_name("N");
  cmd->add_option("--eps-q", args->eps_q, "Stop once valid and q_min changes by less than this (default 0.01)")
      ->check(CLI::Range(0.0, 1.0))
      ->type_name("E");
  cmd->add_option("--boundary", args->boundary,
                  "auto (a mesh's default: fixed unless the boundary must move) | fixed | slide (along the boundary's own "
                  "facets)")
      ->check(CLI::IsMember({"auto", "fixed", "slide"}));
}

}  // namespace meshmorph::detail

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

namespace meshmorph {
namespace detail {

Outcome run_untangle(const MethodArgs& a, int threads, std::ostream& out) {
  const RunTimings timings;
  const std::optional<CaseFile> c = case_or_mesh(a.input);
  const CaseFile run_case = with_flags(c ? *c : bare_case(a.input), a);
  UntangleRunner runner(run_case, read_mesh(c ? c->mesh : std::filesystem::path(a.input)), threads);
  const RunFiles files = run_files(a.output, a.report, a.plot, c ? &*c : nullptr, a.input, "_untangled");

  SeriesOutput series(runner.input(), c ? &*c : nullptr, files);
  RunOutput run = runner.run([&](int step, const Mesh& mesh) {
    series.step(step, mesh);
  });
  series.finish(run, timings);

  const IterationCounts& counts = *run.report.iterations;
  const int steps = run.extra["steps"].get<int>();
  char line[200];
  out << "untangle " << a.input << " (reference " << run.extra["reference"].get<std::string>() << ")\n"
      << mesh_line(runner.input()) << "; " << run.extra["initial_inverted_elements"].get<std::size_t>()
      << " inverted once the boundary is placed\n";
  std::snprintf(line, sizeof line, "work     %d step%s, %lld Newton steps, %lld delta updates, %lld linear solves\n",
                steps, steps > 1 ? "s" : "", counts.newton, counts.outer, counts.linear);
  out << line;
  std::snprintf(line, sizeof line, "quality  q_min (eq. 3) %.4f, min shape quality %.4f; inverted %zu\n",
                run.extra["min_edge_quality"].get<double>(), run.quality.min_shape_quality, run.quality.inverted_elements);
  out << line;
  return print_result(out, run.report, files.output, series.step_files());
}

}  // namespace detail
}  // namespace meshmorph

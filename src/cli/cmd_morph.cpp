// SPDX-License-Identifier: MIT
// `meshmorph morph CASE.json`: boundary-displacement morphing by the augmented Lagrangian of
// paper 000, or one of the two baselines (options.method = "laplace" | "elastic").
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/detail/method_command.h"
#include "cli/detail/output_files.h"
#include "cli/detail/series_output.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/morph_case.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace detail {

Outcome run_morph(const MethodArgs& a, int threads, std::ostream& out) {
  const RunTimings timings;
  const CaseFile c = with_flags(read_case_file(a.input), a);
  MorphRunner runner(c, read_mesh(c.mesh), threads);
  const RunFiles files = run_files(a.output, a.report, a.plot, &c, a.input);

  SeriesOutput series(runner.input(), &c, files);
  MorphOutput run = runner.run([&](int step, const Mesh& mesh) {
    series.step(step, mesh);
  });
  series.finish(run, timings);

  const Report& report = run.report;
  const std::size_t guarded = run.extra.value("guarded_cells", std::size_t{0});
  out << "morph    " << a.input << " (" << report.method << ")\n" << mesh_line(runner.input()) << "\n";
  out << "work     " << report.iterations->outer << " AL iterations, " << report.iterations->nonlinear
      << " nonlinear solves, " << report.iterations->newton << " Newton steps, " << report.iterations->linear
      << " linear solves" << (run.krylov > 0 ? " (" + std::to_string(run.krylov) + " CG iterations)" : std::string())
      << (guarded > 0 ? "; " + std::to_string(guarded) + " cells guarded at their validity samples" : std::string())
      << "\n";
  char line[160];
  std::snprintf(line, sizeof line, "quality  min %.4f, mean %.4f; inverted %zu\n", run.quality.min_quality,
                run.quality.mean_quality, run.quality.inverted_elements);
  out << line;
  std::snprintf(line, sizeof line, "boundary max error %.3g, rms %.3g\n", *report.boundary_error_max, *report.boundary_error_l2);
  out << line;
  return print_result(out, report, files.output, series.step_files());
}

}  // namespace detail
}  // namespace meshmorph

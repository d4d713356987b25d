// SPDX-License-Identifier: MIT
// `meshmorph deform CASE.json`: CVT surface repair and Eikonal convection volume deformation
// (paper 004).
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/detail/method_command.h"
#include "cli/detail/output_files.h"
#include "cli/detail/series_output.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/deform_case.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace detail {

Outcome run_deform(const MethodArgs& a, int threads, std::ostream& out) {
  const RunTimings timings;
  const CaseFile c = with_flags(read_case_file(a.input), a);
  const DeformRunner runner(c, read_mesh(c.mesh), threads);
  const RunFiles files = run_files(a.output, a.report, a.plot, &c, a.input);

  SeriesOutput series(runner.input(), &c, files);
  DeformOutput run = runner.run([&](int step, const Mesh& mesh) {
    series.step(step, mesh);
  });
  series.finish(run, timings);

  const nlohmann::ordered_json& extra = run.extra;
  const IterationCounts& counts = *run.report.iterations;
  char line[200];
  out << "deform   " << a.input << " (" << extra["deform_method"].get<std::string>() << (runner.options().cvt ? " + CVT" : "")
      << ")\n"
      << mesh_line(runner.input()) << "; " << run.design_nodes << " design nodes\n";
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
  return print_result(out, run.report, files.output, series.step_files());
}

}  // namespace detail
}  // namespace meshmorph

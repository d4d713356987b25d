// SPDX-License-Identifier: MIT
// `meshmorph fit CASE.json`: boundary and interface fitting to level sets (paper 003).
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/detail/method_command.h"
#include "cli/detail/output_files.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/fit_case.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace detail {

Outcome run_fit(const MethodArgs& a, int threads, std::ostream& out) {
  const RunTimings timings;
  const CaseFile c = with_flags(read_case_file(a.input), a);
  const FitRunner runner(c, read_mesh(c.mesh), threads);
  const RunFiles files = run_files(a.output, a.report, a.plot, &c, a.input);

  RunOutput run = runner.run();
  write_run(run, files, timings, runner.setup().mesh);

  const Report& report = run.report;
  const FitSetup& setup = runner.setup();
  char line[200];
  out << "fit      " << a.input << "\n"
      << mesh_line(setup.mesh) << "; " << run.extra["fitted_nodes"].get<std::size_t>() << " fitted nodes"
      << (setup.split_cells ? ", " + std::to_string(setup.split_cells) + " cells split" : std::string()) << "\n";
  std::snprintf(line, sizeof line, "work     %lld Newton steps, %lld weight increases, %lld linear solves\n",
                report.iterations->newton, report.iterations->outer, report.iterations->linear);
  out << line;
  std::snprintf(line, sizeof line, "fit      max |sigma| %.3g -> %.3g; min det J %.3g -> %.3g; inverted %zu\n",
                run.extra["fit_error_initial"].get<double>(), *report.fit_error_max, run.extra["min_det_initial"].get<double>(),
                run.extra["min_det_final"].get<double>(), report.inverted_elements);
  out << line;
  if (runner.settings().fit.flat_edges)
    out << "flat     " << run.extra["flat_edge_cells"].get<std::size_t>() << " cells with det J <= 0 only on their flat edges\n";
  return print_result(out, report, files.output);
}

}  // namespace detail
}  // namespace meshmorph

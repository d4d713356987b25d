// SPDX-License-Identifier: MIT
// `meshmorph fit CASE.json`: boundary and interface fitting to level sets (paper 003).
#include <chrono>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <CLI/CLI.hpp>

#include "app/detail/method_output.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/commands.h"
#include "meshmorph/app/fit_case.h"
#include "meshmorph/app/report.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/methods/fit.h"

namespace meshmorph {
namespace {

struct FitArgs {
  std::string case_file;
  std::string output;
  std::string report;
};

Outcome run_fit(const FitArgs& a, int threads, std::ostream& out) {
  const auto start = std::chrono::steady_clock::now();
  const CaseFile c = read_case_file(a.case_file);
  reject_unused_keys(c, "fit", {"steps", "output_each_step"});
  Mesh mesh = read_mesh(c.mesh);
  check_case_against_mesh(c, mesh);
  const FitSettings settings = read_fit_settings(c, threads);
  if (const std::size_t bad = count_invalid_cells(mesh); bad > 0)
    throw InputError(c.mesh.string() + ": " + std::to_string(bad) + " inverted elements: fit needs a valid input mesh");
  const FitSetup setup = prepare_fit(c, std::move(mesh), settings, a.case_file);

  const std::optional<std::filesystem::path> output = a.output.empty() ? c.output : std::optional(std::filesystem::path(a.output));
  const std::optional<std::filesystem::path> report_path = a.report.empty() ? c.report : std::optional(std::filesystem::path(a.report));
  detail::check_outputs(&c, output, report_path);

  Eigen::MatrixXd x = setup.mesh.x;
  const FitResult r = fit_to_level_sets(setup.mesh, setup.topology, setup.terms, setup.fixed, settings.fit, x);
  FitOutcome o = fit_outcome(setup, settings, r, x);
  Report& report = o.report;
  report.case_file = a.case_file;
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  detail::write_result_mesh(report, o.moved, o.quality, output);
  if (report_path) write_report(*report_path, report, o.extra);

  const Mesh& m = setup.mesh;
  const std::size_t fitted = o.extra["fitted_nodes"].get<std::size_t>();
  char line[200];
  out << "fit      " << a.case_file << "\n"
      << "mesh     " << m.dim << "D, " << m.n_nodes() << " nodes, " << m.n_cells() << " cells, order " << m.order() << "; "
      << fitted << " fitted nodes"
      << (setup.split_cells ? ", " + std::to_string(setup.split_cells) + " cells split" : std::string()) << "\n";
  std::snprintf(line, sizeof line, "work     %lld Newton steps, %lld weight increases, %lld linear solves\n", r.newton,
                r.weight_updates, r.linear);
  out << line;
  std::snprintf(line, sizeof line, "fit      max |sigma| %.3g -> %.3g; min det J %.3g -> %.3g; inverted %zu\n", r.fit_error0,
                r.fit_error, r.min_det0, r.min_det, report.inverted_elements);
  out << line;
  if (settings.fit.flat_edges) out << "flat     " << r.flat << " cells with det J <= 0 only on their flat edges\n";
  return detail::print_result(out, report, output);
}

}  // namespace

void add_fit_command(CLI::App& app, Command& run, const int& threads) {
  auto args = std::make_shared<FitArgs>();
  CLI::App* cmd = app.add_subcommand("fit", "Fit the mesh's interface or boundary to a level set (paper 003)");
  cmd->add_option("CASE", args->case_file, "Case file (JSON, see docs/case-file.md)")->required();
  cmd->add_option("-o,--output", args->output, "Output mesh (overrides the case's \"output\")")->type_name("OUT");
  cmd->add_option("--report", args->report, "Report JSON (overrides the case's \"report\")")->type_name("FILE");
  cmd->callback([args, &run, &threads] {
    run = [args, &threads](std::ostream& out) { return run_fit(*args, threads, out); };
  });
}

}  // namespace meshmorph

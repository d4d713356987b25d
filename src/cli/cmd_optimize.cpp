// SPDX-License-Identifier: MIT
// `meshmorph optimize MESH | CASE.json`: TMOP mesh optimization with a fixed or sliding boundary.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>
#include <omp.h>

#include "cli/detail/method_command.h"
#include "cli/detail/output_files.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/optimize_case.h"
#include "meshmorph/app/optimize_ranks.h"
#include "meshmorph/cli/commands.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/parallel/ranks.h"

namespace meshmorph {
namespace {

struct OptimizeArgs : detail::MethodArgs {
  std::string metric, target, boundary, solver;
  int max_newton = 0;
  double rtol = -1.0;
};

// What the run reads and where it writes: rank 0's alone on MPI ranks.
struct Prepared {
  std::optional<CaseFile> c;
  std::optional<OptimizeRunner> runner;
  detail::RunFiles files;
};

void prepare(const OptimizeArgs& a, int threads, Prepared& p) {
  p.c = detail::case_or_mesh(a.input);
  CaseFile run_case = detail::with_flags(p.c ? *p.c : bare_case(a.input), a);
  detail::set_option(run_case, "max_newton", a.max_newton, a.max_newton > 0);
  detail::set_option(run_case, "rtol", a.rtol, a.rtol >= 0.0);
  p.runner.emplace(run_case, read_mesh(p.c ? p.c->mesh : std::filesystem::path(a.input)), threads,
                   OptimizeFlags{a.metric, a.target, a.boundary, a.solver});
  // The rest of the run, its summary included, on the threads the runner picked for this size.
  if (p.runner->threads() > 0) omp_set_num_threads(p.runner->threads());
  // Every input is read by now.
  p.files = detail::run_files(a.output, a.report, a.plot, p.c ? &*p.c : nullptr, a.input, "_optimized");
}

Outcome finish(const OptimizeArgs& a, const Prepared& p, RunOutput& run, const RunTimings& timings, std::ostream& out) {
  const OptimizeRunner& runner = *p.runner;
  detail::write_run(run, p.files, timings, runner.input());

  const nlohmann::ordered_json& extra = run.extra;
  const std::size_t inverted = runner.initial_inverted();
  const std::string solver = extra["solver"].get<std::string>();
  char line[240];
  out << "optimize " << a.input << " (" << extra["metric"].get<std::string>() << ", target "
      << extra["target"].get<std::string>() << ", boundary " << runner.settings().boundary << ")\n"
      << detail::mesh_line(runner.input()) << "; " << runner.constraints().slide_nodes << " sliding nodes"
      << (inverted ? "; " + std::to_string(inverted) + " inverted, untangled first" : std::string()) << "\n";
  if (extra.contains("ranks"))
    out << "ranks    " << extra["ranks"].get<int>() << " (cells partitioned by " << extra["partitioner"].get<std::string>() << ")\n";
  std::snprintf(line, sizeof line, "work     %lld Newton steps, %lld %s (%s)\n",
                run.report.iterations->newton - extra["untangle_newton"].get<long long>(), run.report.iterations->linear,
                solver == "matrix-free" || extra.contains("ranks") ? "CG iterations" : "linear solves",
                solver.empty() ? "none" : solver.c_str());
  out << line;
  std::snprintf(line, sizeof line, "quality  F %.6g -> %.6g; mu min/mean/max %.4g / %.4g / %.4g; min det J %.3g -> %.3g; inverted %zu\n",
                extra["energy_initial"].get<double>(), extra["energy_final"].get<double>(), extra["mu_min"].get<double>(),
                extra["mu_mean"].get<double>(), extra["mu_max"].get<double>(), extra["min_det_initial"].get<double>(),
                extra["min_det_final"].get<double>(), run.quality.inverted_elements);
  out << line;
  return detail::print_result(out, run.report, p.files.output, 0, detail::writes_mesh(run));
}

Outcome run_optimize(const OptimizeArgs& a, int threads, std::ostream& out) {
  const RunTimings timings;
  Prepared p;
  if (!on_ranks()) {
    prepare(a, threads, p);
    RunOutput run = p.runner->run();
    return finish(a, p, run, timings, out);
  }
  // On MPI ranks (docs/parallel.md): rank 0 reads and writes; every rank optimizes its part.
  on_root([&] {
    prepare(a, threads, p);
    check_runs_on_ranks(*p.runner);
  }, report_exception);
  RunOutput run = run_on_ranks(p.runner ? &*p.runner : nullptr);
  int outcome = 0;
  on_root([&] { outcome = static_cast<int>(finish(a, p, run, timings, out)); }, report_exception);
  return static_cast<Outcome>(broadcast_from_root(outcome));
}

}  // namespace

void add_optimize_command(CLI::App& app, Command& run, const int& threads) {
  auto args = std::make_shared<OptimizeArgs>();
  CLI::App* cmd = detail::add_method_command(
      app, run, threads,
      {"optimize", "TMOP mesh optimization with a fixed or sliding boundary (paper 003 §2.2)", "INPUT",
       "Mesh, or case file (JSON, docs/case-file.md)",
       "Output mesh (default: the case's \"output\"; for a mesh, NAME_optimized.EXT)"},
      args, &run_optimize);
  cmd->add_option("--metric", args->metric, "mu2 (2D) | mu303 (3D) | mu77 | mu80 | distortion | distortion2")
      ->check(CLI::IsMember({"mu2", "mu303", "mu77", "mu80", "distortion", "distortion2"}));
  cmd->add_option("--target", args->target, "ideal (default) | input | ideal_unit (MFEM's -tid 1)")
      ->check(CLI::IsMember({"ideal", "input", "ideal_unit"}));
  cmd->add_option("--boundary", args->boundary,
                  "fixed (default) | slide (on the boundary's own planes and curved facets) | slide-planes (on its planes only)")
      ->check(CLI::IsMember({"fixed", "slide", "slide-planes"}));
  cmd->add_option("--solver", args->solver, "auto (default) | cholesky | iterative | matrix-free | petsc-gamg | petsc-hypre")
      ->check(CLI::IsMember({"auto", "cholesky", "iterative", "matrix-free", "petsc-gamg", "petsc-hypre"}));
  cmd->add_option("--max-newton", args->max_newton, "Newton steps at most (default 50)")->check(CLI::Range(1, 100000))->type_name("N");
  cmd->add_option("--rtol", args->rtol, "Stop at |grad F| <= rtol |grad F0| (default 1e-10)")->check(CLI::Range(0.0, 1.0))->type_name("R");
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
// meshmorph: parse the command line, run one subcommand, map the outcome to an exit code
// (0 goal reached, 1 ran without reaching it, 2 bad input or usage; DESIGN §3.1).
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>
#include <dlfcn.h>
#include <strings.h>
#include <unistd.h>

#include "meshmorph/cli/commands.h"
#include "meshmorph/error.h"
#include "meshmorph/io/atomic_file.h"
#include "meshmorph/io/input_files.h"
#include "meshmorph/parallel/ranks.h"

namespace {

constexpr int kExitMissed = 1;
constexpr int kExitBadInput = 2;

// Settings that the libraries read once, when they load: where one is missing, set it and
// run once more (a failed exec leaves everything as it was). Not under valgrind, which would
// run the second program unchecked.
// - Debian 12's OpenBLAS 0.3.21 (the BLAS behind CHOLMOD) does not know every recent Xeon and
//   falls back to its SSE3 "Prescott" kernels, which made a CHOLMOD-bound morph 1.3x slower
//   here: OPENBLAS_CORETYPE names the family the CPU supports.
// - libgomp's threads spin at a barrier until the slowest arrives. Where another job shares
//   the cores, the one they wait for is often paused, and their spinning keeps it so: with
//   one other busy process on 2 cores a 2-thread morph took 3 times longer than on one thread,
//   8 times under heavier load (bench/README.md, "Threads on a shared machine"). OMP_WAIT_POLICY=passive makes them
//   sleep; unless the user chose a policy or a spin count.
void set_runtime_environment(char** argv) {
  if (std::getenv("MESHMORPH_ENVIRONMENT_SET") != nullptr) return;
  if (const char* preload = std::getenv("LD_PRELOAD"); preload != nullptr && std::strstr(preload, "vgpreload") != nullptr)
    return;
  bool changed = false;
  using CoreName = char* (*)();
  const auto name = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  if (std::getenv("OPENBLAS_CORETYPE") == nullptr && name != nullptr && strcasecmp(name(), "Prescott") == 0) {
    const char* core = __builtin_cpu_supports("avx512f") ? "SkylakeX" : __builtin_cpu_supports("avx2") ? "Haswell" : nullptr;
    if (core != nullptr) {
      setenv("OPENBLAS_CORETYPE", core, 1);
      changed = true;
    }
  }
  if (std::getenv("OMP_WAIT_POLICY") == nullptr && std::getenv("GOMP_SPINCOUNT") == nullptr) {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    changed = true;
  }
  if (!changed) return;
  setenv("MESHMORPH_ENVIRONMENT_SET", "1", 1);
  execv("/proc/self/exe", argv);
}

int report_error(const char* what) {
  if (meshmorph::mpi_rank() == 0) std::fprintf(stderr, "meshmorph: error: %s\n", what);
  return kExitBadInput;
}

// Runs the command. On MPI ranks, optimize runs on every rank; any other command runs on rank
// 0 alone while the others wait for its exit code.
int run_command(const meshmorph::Command& run, bool on_every_rank) {
  if (meshmorph::on_ranks() && !on_every_rank) {
    int code = 0;
    meshmorph::on_root([&] { code = run(std::cout) == meshmorph::Outcome::GoalReached ? 0 : kExitMissed; },
                       meshmorph::report_exception);
    std::cout.flush();
    return meshmorph::broadcast_from_root(code);
  }
  std::ostream silent(nullptr);  // the summary is rank 0's
  const meshmorph::Outcome outcome = run(meshmorph::mpi_rank() == 0 ? std::cout : silent);
  std::cout.flush();
  return outcome == meshmorph::Outcome::GoalReached ? 0 : kExitMissed;
}

}  // namespace

int main(int argc, char** argv) {
  set_runtime_environment(argv);
  try {
    meshmorph::start_ranks();  // MPI through PETSc, where mpirun started the process
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meshmorph: error: %s\n", e.what());
    return 3;
  }
  CLI::App app{"meshmorph: moves the nodes of finite-element meshes and keeps them valid"};
  app.name("meshmorph");
  meshmorph::CommonOptions common;
  meshmorph::Command run;
  meshmorph::add_common_options(app, common);
  meshmorph::add_quality_command(app, run);
  meshmorph::add_convert_command(app, run);
  meshmorph::add_check_command(app, run);
  meshmorph::add_method_commands(app, run, common.threads);
  meshmorph::add_optimize_command(app, run, common.threads);
  meshmorph::add_plot_command(app, run);
  app.require_subcommand(1);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return meshmorph::mpi_rank() == 0 ? app.exit(e) : 0;
  } catch (const CLI::ParseError& e) {
    // "A subcommand is required" also answers a misspelt one: name it and the known ones.
    std::string what = e.what();
    if (app.get_subcommands().empty())
      for (int i = 1; i < argc; ++i) {
        const std::string arg = argv[i];
        if (arg.starts_with("-")) {
          i += arg == "--threads" ? 1 : 0;  // the common option with a value
          continue;
        }
        std::string known;
        for (const CLI::App* sub : app.get_subcommands([](CLI::App*) { return true; }))
          known += (known.empty() ? "" : ", ") + sub->get_name();
        what = "unknown subcommand '" + arg + "' (expected one of: " + known + ")";
        break;
      }
    report_error(what.c_str());
    if (meshmorph::mpi_rank() == 0) std::fprintf(stderr, "Run 'meshmorph --help' for usage.\n");
    return kExitBadInput;
  }

  try {
    meshmorph::apply_common_options(common);
    meshmorph::remove_temporaries_on_signals();
    meshmorph::record_input_files(true);  // no output the run names itself replaces a file it read
    return run_command(run, app.got_subcommand("optimize"));
  } catch (const meshmorph::RootFailed& e) {  // rank 0 said why
    return e.exit_code();
  } catch (...) {
    const int code = meshmorph::report_exception(std::current_exception());
    // A failure of one rank among others that may wait for it in a collective call.
    if (meshmorph::mpi_size() > 1) meshmorph::abort_ranks(code);
    return code;
  }
}

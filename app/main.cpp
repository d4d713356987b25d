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
  std::fprintf(stderr, "meshmorph: error: %s\n", what);
  return kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  set_runtime_environment(argv);
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
    return app.exit(e);
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
    std::fprintf(stderr, "Run 'meshmorph --help' for usage.\n");
    return kExitBadInput;
  }

  try {
    meshmorph::apply_common_options(common);
    meshmorph::remove_temporaries_on_signals();
    meshmorph::record_input_files(true);  // no output the run names itself replaces a file it read
    const meshmorph::Outcome outcome = run(std::cout);
    std::cout.flush();
    return outcome == meshmorph::Outcome::GoalReached ? 0 : kExitMissed;
  } catch (const meshmorph::InputError& e) {
    return report_error(e.what());
  } catch (const meshmorph::IoError& e) {
    return report_error(e.what());
  } catch (const std::invalid_argument& e) {
    return report_error(e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meshmorph: internal error: %s\n", e.what());
    return 3;
  }
}

// SPDX-License-Identifier: MIT
// meshmorph: parse the command line, run one subcommand, map the outcome to an exit code
// (0 goal reached, 1 ran without reaching it, 2 bad input or usage; DESIGN §3.1).
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <iostream>
#include <stdexcept>

#include <CLI/CLI.hpp>
#include <dlfcn.h>
#include <strings.h>
#include <unistd.h>

#include "meshmorph/app/commands.h"
#include "meshmorph/error.h"
#include "meshmorph/io/input_files.h"

namespace {

constexpr int kExitMissed = 1;
constexpr int kExitBadInput = 2;

// Debian 12's OpenBLAS 0.3.21 (the BLAS behind CHOLMOD) does not know every recent Xeon and
// falls back to its SSE3 "Prescott" kernels, which made a CHOLMOD-bound morph 1.3x slower
// here. It picks its kernels when it loads, from OPENBLAS_CORETYPE: run once more with the
// family the CPU supports. A failed exec leaves everything as it was.
void choose_blas_kernels(char** argv) {
  if (std::getenv("OPENBLAS_CORETYPE") != nullptr || std::getenv("MESHMORPH_BLAS_CHOSEN") != nullptr) return;
  using CoreName = char* (*)();
  const auto name = reinterpret_cast<CoreName>(dlsym(RTLD_DEFAULT, "openblas_get_corename"));
  if (name == nullptr || strcasecmp(name(), "Prescott") != 0) return;
  const char* core = __builtin_cpu_supports("avx512f") ? "SkylakeX" : __builtin_cpu_supports("avx2") ? "Haswell" : nullptr;
  if (core == nullptr) return;
  setenv("OPENBLAS_CORETYPE", core, 1);
  setenv("MESHMORPH_BLAS_CHOSEN", "1", 1);
  execv("/proc/self/exe", argv);
}

int report_error(const char* what) {
  std::fprintf(stderr, "meshmorph: error: %s\n", what);
  return kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
  choose_blas_kernels(argv);
  CLI::App app{"meshmorph: moves the nodes of finite-element meshes and keeps them valid"};
  app.name("meshmorph");
  meshmorph::CommonOptions common;
  meshmorph::Command run;
  meshmorph::add_common_options(app, common);
  meshmorph::add_quality_command(app, run);
  meshmorph::add_convert_command(app, run);
  meshmorph::add_check_command(app, run);
  meshmorph::add_morph_command(app, run, common.threads);
  meshmorph::add_untangle_command(app, run, common.threads);
  meshmorph::add_fit_command(app, run, common.threads);
  meshmorph::add_deform_command(app, run, common.threads);
  meshmorph::add_optimize_command(app, run, common.threads);
  app.require_subcommand(1);

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {  // --help, --version
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    report_error(e.what());
    std::fprintf(stderr, "Run 'meshmorph --help' for usage.\n");
    return kExitBadInput;
  }

  try {
    meshmorph::apply_common_options(common);
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

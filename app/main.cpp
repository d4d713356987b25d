// SPDX-License-Identifier: MIT
// meshmorph: parse the command line, run one subcommand, map the outcome to an exit code
// (0 goal reached, 1 ran without reaching it, 2 bad input or usage; DESIGN §3.1).
#include <cstdio>
#include <exception>
#include <iostream>
#include <stdexcept>

#include <CLI/CLI.hpp>

#include "meshmorph/app/commands.h"
#include "meshmorph/error.h"

namespace {

constexpr int kExitMissed = 1;
constexpr int kExitBadInput = 2;

int report_error(const char* what) {
  std::fprintf(stderr, "meshmorph: error: %s\n", what);
  return kExitBadInput;
}

}  // namespace

int main(int argc, char** argv) {
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

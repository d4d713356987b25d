// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <ostream>
#include <string>

#include <CLI/CLI.hpp>

#include "meshmorph/app/case_file.h"
#include "meshmorph/cli/commands.h"

namespace meshmorph::detail {

/// What every method subcommand takes: its input and the -o and --report overrides.
struct MethodArgs {
  std::string input;   ///< CASE.json, or (untangle, optimize) a mesh
  std::string output;  ///< -o: over the case's "output"
  std::string report;  ///< --report: over the case's "report"
  bool reorient = false;  ///< --reorient: as the case's "reorient"
  std::string plot;       ///< --plot: input and output side by side (write_comparison)
};

/// The case with the flags of the command line over its keys.
inline CaseFile with_flags(CaseFile c, const MethodArgs& a) {
  c.reorient = c.reorient || a.reorient;
  return c;
}

/// The words of a method subcommand in --help.
struct MethodHelp {
  const char* name;
  const char* description;
  const char* input;        ///< "CASE" or "INPUT"
  const char* input_help;
  const char* output_help;
};

/// Adds the subcommand: its input, -o and --report bound to `args` (a MethodArgs, or one
/// that adds the subcommand's own options); when it is chosen, `run` calls `body` with the
/// common --threads value. Returns it for more options.
template <class Args>
CLI::App* add_method_command(CLI::App& app, Command& run, const int& threads, const MethodHelp& help,
                             std::shared_ptr<Args> args, Outcome (*body)(const Args&, int, std::ostream&)) {
  CLI::App* cmd = app.add_subcommand(help.name, help.description);
  cmd->add_option(help.input, args->input, help.input_help)->required();
  cmd->add_option("-o,--output", args->output, help.output_help)->type_name("OUT");
  cmd->add_option("--report", args->report, "Report JSON (overrides the case's \"report\")")->type_name("FILE");
  cmd->add_flag("--reorient", args->reorient,
                "List cells that are mirrored against their neighbours the right way round instead of refusing the mesh");
  cmd->add_option("--plot", args->plot, "Also draw the input and the output side by side, where the output is written")
      ->type_name("FILE.png|.svg");
  cmd->callback([args, body, &run, &threads] {
    run = [args, body, &threads](std::ostream& out) { return body(*args, threads, out); };
  });
  return cmd;
}

/// `option` = `value` in the case's "options", over what the case says, where `given`.
template <class T>
void set_option(CaseFile& c, const char* option, const T& value, bool given) {
  if (given) c.options[option] = value;
}

/// The runs of the subcommands of add_method_commands (cli/cmd_<name>.cpp).
Outcome run_morph(const MethodArgs& a, int threads, std::ostream& out);
/// `meshmorph untangle` with its own options (--max-newton, --eps-q, --boundary).
void add_untangle_command(CLI::App& app, Command& run, const int& threads);
Outcome run_fit(const MethodArgs& a, int threads, std::ostream& out);
Outcome run_deform(const MethodArgs& a, int threads, std::ostream& out);

}  // namespace meshmorph::detail

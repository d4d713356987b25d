// SPDX-License-Identifier: MIT
#pragma once
#include <exception>
#include <functional>
#include <ostream>

namespace CLI {
class App;
}

namespace meshmorph {

/// What a subcommand returns: whether it reached its goal (exit 0) or ran without reaching
/// it (exit 1). Bad input is an exception (InputError, IoError, std::invalid_argument),
/// which app/main.cpp maps to exit 2.
enum class Outcome { GoalReached, GoalMissed };

/// A parsed subcommand, ready to run; `out` receives its tables (main passes stdout).
using Command = std::function<Outcome(std::ostream& out)>;

/// Prints why a command failed on stderr ("meshmorph: error: …", or "meshmorph: internal
/// error: …") and returns its exit code: 2 for bad input or usage (InputError, IoError,
/// std::invalid_argument), 3 for anything else.
int report_exception(std::exception_ptr error);

/// Options shared by every subcommand.
struct CommonOptions {
  int threads = 0;  ///< OpenMP threads; 0 = the OpenMP default
  bool quiet = false;
  bool verbose = false;
};

/// Adds --threads, --quiet, --verbose and --version to the top-level app.
void add_common_options(CLI::App& app, CommonOptions& options);
/// Installs the stderr log sink ("meshmorph: ..."), silent with --quiet and on MPI ranks
/// other than 0, detailed with --verbose, and sets the OpenMP thread count.
void apply_common_options(const CommonOptions& options);

/// `meshmorph quality MESH [--json FILE] [-o OUT.vtu]`; sets `run` when chosen.
void add_quality_command(CLI::App& app, Command& run);
/// `meshmorph convert IN OUT [--order P] [--binary] [--msh22]`; sets `run` when chosen.
void add_convert_command(CLI::App& app, Command& run);
/// `meshmorph morph`, `untangle`, `fit` and `deform` CASE.json [-o OUT] [--report FILE]
/// (DESIGN §3.1; untangle also takes a bare mesh); `threads` is read when the command runs
/// (the common --threads option).
void add_method_commands(CLI::App& app, Command& run, const int& threads);
/// `meshmorph optimize MESH | CASE.json [-o OUT] [--report FILE] [--metric M] [--target T]
/// [--boundary fixed|slide]`: TMOP mesh optimization (docs/optimize.md).
void add_optimize_command(CLI::App& app, Command& run, const int& threads);
/// `meshmorph plot MESH [-o FILE.png|.svg] [--field F] [--reference MESH]`: a picture of the
/// mesh coloured by a cell field, with its histogram (docs/cli.md).
void add_plot_command(CLI::App& app, Command& run);
/// `meshmorph check CASE.json`: validates a case file against its mesh; writes nothing.
void add_check_command(CLI::App& app, Command& run);

}  // namespace meshmorph

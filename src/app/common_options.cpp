// SPDX-License-Identifier: MIT
#include <omp.h>
#include <unistd.h>

#include <cstdio>
#include <string>

#include <CLI/CLI.hpp>

#include "meshmorph/app/commands.h"
#include "meshmorph/app/report.h"
#include "meshmorph/log.h"

namespace meshmorph {

void add_common_options(CLI::App& app, CommonOptions& options) {
  app.set_version_flag("--version", std::string("meshmorph ") + meshmorph_version());
  app.add_option("--threads", options.threads, "Number of threads (default: all cores)")
      ->check(CLI::PositiveNumber)
      ->type_name("N");
  auto* quiet = app.add_flag("-q,--quiet", options.quiet, "Print errors only");
  app.add_flag("-v,--verbose", options.verbose, "Print details and progress")->excludes(quiet);
}

void apply_common_options(const CommonOptions& options) {
  if (options.threads > 0) omp_set_num_threads(options.threads);
  if (options.quiet) {
    set_log_sink({});
    return;
  }
  // Progress lines only where a person watches; detail only on request.
  const LogLevel max_level = options.verbose ? LogLevel::Detail
                                             : (isatty(STDERR_FILENO) ? LogLevel::Progress : LogLevel::Info);
  set_log_sink(
      [](LogLevel level, std::string_view message) {
        const char* prefix = level == LogLevel::Error ? "meshmorph: error: "
                             : level == LogLevel::Warning ? "meshmorph: warning: "
                                                          : "meshmorph: ";
        std::fprintf(stderr, "%s%.*s\n", prefix, static_cast<int>(message.size()), message.data());
      },
      max_level);
}

}  // namespace meshmorph

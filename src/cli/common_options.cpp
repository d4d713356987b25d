// SPDX-License-Identifier: MIT
#include <omp.h>

#include <chrono>
#include <cstdio>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "meshmorph/cli/commands.h"
#include "meshmorph/app/report.h"
#include "meshmorph/error.h"
#include "meshmorph/log.h"
#include "meshmorph/parallel/ranks.h"

namespace meshmorph {

void add_common_options(CLI::App& app, CommonOptions& options) {
  // Common options may also follow the subcommand: `meshmorph morph case.json --quiet`.
  app.fallthrough();
  app.set_version_flag("--version", std::string("meshmorph ") + meshmorph_version());
  app.add_option("--threads", options.threads,
                 "Number of threads (default: all cores; optimize: one below 30 000 unknowns)")
      ->check(CLI::Range(1, 1024))  // libgomp fails to start 32 768 threads, and crashed at 65 536
      ->type_name("N");
  auto* quiet = app.add_flag("-q,--quiet", options.quiet, "Print errors only");
  app.add_flag("-v,--verbose", options.verbose, "Print details and progress")->excludes(quiet);
}

void apply_common_options(const CommonOptions& options) {
  if (options.threads > 0) omp_set_num_threads(options.threads);
  if (options.quiet || mpi_rank() != 0) {
    set_log_sink({});
    return;
  }
  // Progress lines once a run has taken more than a second (quick runs stay silent);
  // detail only on request.
  const LogLevel max_level = options.verbose ? LogLevel::Detail : LogLevel::Progress;
  const auto start = std::chrono::steady_clock::now();
  set_log_sink(
      [verbose = options.verbose, start](LogLevel level, std::string_view message) {
        if (level == LogLevel::Progress && !verbose && std::chrono::steady_clock::now() - start < std::chrono::seconds(1))
          return;
        const char* prefix = level == LogLevel::Error ? "meshmorph: error: "
                             : level == LogLevel::Warning ? "meshmorph: warning: "
                                                          : "meshmorph: ";
        std::fprintf(stderr, "%s%.*s\n", prefix, static_cast<int>(message.size()), message.data());
      },
      max_level);
}

int report_exception(std::exception_ptr error) {
  try {
    std::rethrow_exception(error);
  } catch (const InputError& e) {
    std::fprintf(stderr, "meshmorph: error: %s\n", e.what());
  } catch (const IoError& e) {
    std::fprintf(stderr, "meshmorph: error: %s\n", e.what());
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "meshmorph: error: %s\n", e.what());
  } catch (const std::exception& e) {
    std::fprintf(stderr, "meshmorph: internal error: %s\n", e.what());
    return 3;
  } catch (...) {
    std::fprintf(stderr, "meshmorph: internal error\n");
    return 3;
  }
  return 2;
}

}  // namespace meshmorph

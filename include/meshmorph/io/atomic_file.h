// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <functional>
#include <ostream>

namespace meshmorph {

/// Writes a file atomically: `write` fills a temporary file in the same folder
/// (`.NAME.tmp-XXXXXX`), which is flushed and renamed over `path` only if `write` returns
/// normally. On any exception the temporary is removed, `path` is untouched, and the
/// exception propagates. Temporaries of writes to `path` older than this process (left by a
/// run that was killed) are removed first. Throws IoError when the folder is not writable.
void write_atomically(const std::filesystem::path& path, bool binary,
                      const std::function<void(std::ostream&)>& write);

/// write_atomically for writers that open a file by name (the CGNS and Exodus II
/// libraries): `write` creates or overwrites the temporary file whose path it is given.
void write_atomically_at(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write);

/// Installs handlers of SIGINT, SIGTERM and SIGHUP that remove the temporaries of the writes
/// in progress, then end the process as the signal would (the command line's; a library
/// caller such as Python keeps its own handlers).
void remove_temporaries_on_signals();

}  // namespace meshmorph

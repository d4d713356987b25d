// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <functional>
#include <ostream>

namespace meshmorph {

/// Writes a file atomically: `write` fills a temporary file in the same folder, which is
/// flushed and renamed over `path` only if `write` returns normally. On any exception the
/// temporary is removed, `path` is untouched, and the exception propagates. Throws
/// IoError when the folder is not writable.
void write_atomically(const std::filesystem::path& path, bool binary,
                      const std::function<void(std::ostream&)>& write);

}  // namespace meshmorph

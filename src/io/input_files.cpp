// SPDX-License-Identifier: MIT
#include "meshmorph/io/input_files.h"

#include <mutex>
#include <system_error>
#include <vector>

namespace meshmorph {
namespace {

struct Inputs {
  std::mutex mutex;
  bool on = false;
  std::vector<std::filesystem::path> files;  // as the reader named them
};

Inputs& inputs() {
  static Inputs instance;
  return instance;
}

}  // namespace

bool same_file(const std::filesystem::path& a, const std::filesystem::path& b) {
  std::error_code ec;
  if (std::filesystem::equivalent(a, b, ec)) return true;  // both exist: compares the files themselves
  // Absolute first: weakly_canonical leaves a relative path whose first part does not exist as it is.
  std::error_code ea, eb;
  const std::filesystem::path ca = std::filesystem::weakly_canonical(std::filesystem::absolute(a, ea), ea);
  const std::filesystem::path cb = std::filesystem::weakly_canonical(std::filesystem::absolute(b, eb), eb);
  return !ea && !eb && ca == cb;
}

void record_input_files(bool on) {
  Inputs& in = inputs();
  const std::lock_guard lock(in.mutex);
  in.on = on;
  if (!on) in.files.clear();
}

void note_input_file(const std::filesystem::path& path) {
  Inputs& in = inputs();
  const std::lock_guard lock(in.mutex);
  if (in.on) in.files.push_back(path);
}

std::optional<std::filesystem::path> input_file_at(const std::filesystem::path& path) {
  Inputs& in = inputs();
  const std::lock_guard lock(in.mutex);
  for (const std::filesystem::path& f : in.files)
    if (same_file(f, path)) return f;
  return std::nullopt;
}

}  // namespace meshmorph

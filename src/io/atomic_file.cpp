// SPDX-License-Identifier: MIT
#include "meshmorph/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>
#include <system_error>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

// When this run started: temporaries of a write to the same path older than that were left by
// a run that was killed (kill -9 leaves them whatever the signal handlers do).
const std::filesystem::file_time_type run_start = std::filesystem::file_time_type::clock::now();

// The temporaries being written now, for the signal handler: fixed slots it can read without
// allocating or locking (unlink is async-signal-safe).
struct Slot {
  std::atomic<bool> used{false};
  char path[4096]{};
};
std::array<Slot, 8> live;

Slot* hold(const std::string& name) {
  if (name.size() >= sizeof(Slot::path)) return nullptr;
  for (Slot& s : live) {
    bool expected = false;
    if (s.used.load() || !s.used.compare_exchange_strong(expected, true)) continue;
    std::memcpy(s.path, name.c_str(), name.size() + 1);
    return &s;
  }
  return nullptr;  // more writes at once than slots: such a temporary goes with the next run
}

void release(Slot* s) {
  if (s) s->used.store(false);
}

extern "C" void remove_live_temporaries(int sig) {
  for (Slot& s : live)
    if (s.used.load()) ::unlink(s.path);
  std::signal(sig, SIG_DFL);
  std::raise(sig);
}

// `.NAME.tmp-` + 6 characters: the temporaries of writes to `path`.
std::string hidden_prefix(const std::filesystem::path& path) {
  // Appended, not "." + name: GCC 12 warns (-Wrestrict, a false positive) on that operator+.
  std::string hidden = ".";
  hidden += path.filename().string();
  hidden += ".tmp-";
  return hidden;
}

// Removes the temporaries of writes to `path` that are older than this run.
void remove_stale_temporaries(const std::filesystem::path& folder, const std::filesystem::path& path) {
  const std::string prefix = hidden_prefix(path);
  std::error_code ec;
  for (const auto& entry : std::filesystem::directory_iterator(folder, ec)) {
    const std::string name = entry.path().filename().string();
    if (name.size() != prefix.size() + 6 || name.compare(0, prefix.size(), prefix) != 0) continue;
    std::error_code e;
    if (entry.is_regular_file(e) && entry.last_write_time(e) < run_start && !e) std::filesystem::remove(entry.path(), e);
  }
}

// Creates a unique empty file next to `path` and returns its name.
std::filesystem::path make_temporary(const std::filesystem::path& path) {
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  remove_stale_temporaries(folder, path);
  std::string name = (folder / (hidden_prefix(path) + "XXXXXX")).string();
  const int fd = ::mkstemp(name.data());
  if (fd < 0)
    throw IoError(path.string() + ": cannot create a temporary file in " + folder.string() + ": " +
                  std::generic_category().message(errno));
  ::close(fd);
  return name;
}

void sync_file(const std::filesystem::path& file) {
  const int fd = ::open(file.c_str(), O_RDONLY);
  if (fd >= 0) {
    ::fsync(fd);
    ::close(fd);
  }
}

}  // namespace

void remove_temporaries_on_signals() {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) std::signal(sig, remove_live_temporaries);
}

void write_atomically(const std::filesystem::path& path, bool binary,
                      const std::function<void(std::ostream&)>& write) {
  write_atomically_at(path, [&](const std::filesystem::path& tmp) {
    std::ofstream out(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
    if (!out) throw IoError(path.string() + ": cannot open " + tmp.string() + " for writing");
    write(out);
    out.flush();
    if (!out) throw IoError(path.string() + ": write error (disk full?)");
  });
}

void write_atomically_at(const std::filesystem::path& path, const std::function<void(const std::filesystem::path&)>& write) {
  const std::filesystem::path tmp = make_temporary(path);
  Slot* slot = hold(tmp.string());
  try {
    write(tmp);
    sync_file(tmp);
    // mkstemp creates the file with mode 0600; give it the usual permissions (umask applies).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    std::filesystem::permissions(tmp, static_cast<std::filesystem::perms>(0666 & ~mask));
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw IoError(path.string() + ": cannot rename the temporary file into place: " + ec.message());
    release(slot);
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    release(slot);
    throw;
  }
}

}  // namespace meshmorph

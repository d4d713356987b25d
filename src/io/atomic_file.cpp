// SPDX-License-Identifier: MIT
#include "meshmorph/io/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <string>
#include <system_error>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

// Creates a unique empty file next to `path` and returns its name.
std::filesystem::path make_temporary(const std::filesystem::path& path) {
  const std::filesystem::path folder = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
  // Appended, not "." + name: GCC 12 warns (-Wrestrict, a false positive) on that operator+.
  std::string hidden = ".";
  hidden += path.filename().string();
  hidden += ".tmp-XXXXXX";
  std::string name = (folder / hidden).string();
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

void write_atomically(const std::filesystem::path& path, bool binary,
                      const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path tmp = make_temporary(path);
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::trunc);
      if (!out) throw IoError(path.string() + ": cannot open " + tmp.string() + " for writing");
      write(out);
      out.flush();
      if (!out) throw IoError(path.string() + ": write error (disk full?)");
    }
    sync_file(tmp);
    // mkstemp creates the file with mode 0600; give it the usual permissions (umask applies).
    const mode_t mask = ::umask(0);
    ::umask(mask);
    std::filesystem::permissions(tmp, static_cast<std::filesystem::perms>(0666 & ~mask));
    std::error_code ec;
    std::filesystem::rename(tmp, path, ec);
    if (ec) throw IoError(path.string() + ": cannot rename the temporary file into place: " + ec.message());
  } catch (...) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    throw;
  }
}

}  // namespace meshmorph

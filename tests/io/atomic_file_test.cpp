// SPDX-License-Identifier: MIT
#include "meshmorph/io/atomic_file.h"

#include <sys/wait.h>
#include <unistd.h>

#include <csignal>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/io/input_files.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t n_entries(const fs::path& dir) {
  return static_cast<std::size_t>(std::distance(fs::directory_iterator(dir), fs::directory_iterator()));
}

class AtomicFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("meshmorph_atomic_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override {
    fs::permissions(dir_, fs::perms::owner_all);
    fs::remove_all(dir_);
  }
  fs::path dir_;
};

TEST_F(AtomicFile, WritesTheContentAndLeavesNoTemporary) {
  const fs::path p = dir_ / "out.txt";
  write_atomically(p, true, [](std::ostream& o) { o << "hello\n"; });
  EXPECT_EQ(slurp(p), "hello\n");
  EXPECT_EQ(n_entries(dir_), 1u);
  write_atomically(p, false, [](std::ostream& o) { o << "replaced"; });
  EXPECT_EQ(slurp(p), "replaced");
  EXPECT_EQ(n_entries(dir_), 1u);
}

TEST_F(AtomicFile, AnExceptionLeavesTheOldFileAndNoTemporary) {
  const fs::path p = dir_ / "out.txt";
  std::ofstream(p) << "old";
  EXPECT_THROW(write_atomically(p, true,
                                [](std::ostream& o) {
                                  o << "partial new content";
                                  throw InputError("cannot hold this mesh");
                                }),
               InputError);
  EXPECT_EQ(slurp(p), "old");
  EXPECT_EQ(n_entries(dir_), 1u);
  // No file at all is created when there was none.
  EXPECT_THROW(write_atomically(dir_ / "new.txt", true, [](std::ostream&) { throw std::runtime_error("x"); }),
               std::runtime_error);
  EXPECT_FALSE(fs::exists(dir_ / "new.txt"));
  EXPECT_EQ(n_entries(dir_), 1u);
}

// A run killed while it wrote (kill -9 runs no handler) leaves `.NAME.tmp-XXXXXX`: the next
// write to the same path removes those older than its run, and nothing else.
TEST_F(AtomicFile, TheNextWriteRemovesTheTemporariesOfAKilledRun) {
  const auto older = fs::file_time_type::clock::now() - std::chrono::hours(1);
  const auto later = fs::file_time_type::clock::now() + std::chrono::hours(1);
  const auto make = [&](const std::string& name, fs::file_time_type when) {
    std::ofstream(dir_ / name) << "partial";
    fs::last_write_time(dir_ / name, when);
  };
  make(".out.vtu.tmp-AbC123", older);   // a killed run's
  make(".out.vtu.tmp-XyZ789", later);   // written during this run: another writer's
  make(".other.vtu.tmp-AbC123", older); // another path's
  make(".out.vtu.tmp-AbC1234", older);  // not a temporary's name
  write_atomically(dir_ / "out.vtu", false, [](std::ostream& o) { o << "done"; });
  EXPECT_EQ(slurp(dir_ / "out.vtu"), "done");
  EXPECT_FALSE(fs::exists(dir_ / ".out.vtu.tmp-AbC123"));
  EXPECT_TRUE(fs::exists(dir_ / ".out.vtu.tmp-XyZ789"));
  EXPECT_TRUE(fs::exists(dir_ / ".other.vtu.tmp-AbC123"));
  EXPECT_TRUE(fs::exists(dir_ / ".out.vtu.tmp-AbC1234"));
  EXPECT_EQ(n_entries(dir_), 4u);
}

// SIGINT, SIGTERM or SIGHUP while a write is under way: the handlers remove its temporary and
// the process ends as the signal would have it. A child process takes the signal, raised from
// inside the write so that the temporary surely exists then.
TEST_F(AtomicFile, ASignalDuringAWriteLeavesNoTemporary) {
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) {
    SCOPED_TRACE(sig);
    const pid_t pid = ::fork();
    ASSERT_GE(pid, 0);
    if (pid == 0) {
      remove_temporaries_on_signals();
      write_atomically(dir_ / "out.vtu", false, [&](std::ostream& o) {
        o << "partial" << std::flush;
        std::raise(sig);
      });
      ::_exit(0);  // the signal ends the process before this
    }
    int status = 0;
    ASSERT_EQ(::waitpid(pid, &status, 0), pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
    EXPECT_EQ(n_entries(dir_), 0u);
  }
}

TEST_F(AtomicFile, AMissingFolderIsAnIoError) {
  EXPECT_THROW(write_atomically(dir_ / "no" / "such" / "out.txt", true, [](std::ostream& o) { o << 1; }), IoError);
}

TEST_F(AtomicFile, AReadOnlyFolderIsAnIoError) {
  if (::geteuid() == 0) GTEST_SKIP() << "root can write into read-only folders";
  fs::permissions(dir_, fs::perms::owner_read | fs::perms::owner_exec);
  EXPECT_THROW(write_atomically(dir_ / "out.txt", true, [](std::ostream& o) { o << 1; }), IoError);
}

// While recording (the CLI's), a mesh read through a link is known as an input by any of its
// names; recording off (the library's default) forgets it.
TEST_F(AtomicFile, ReadersNoteTheirFilesAsInputsWhileRecording) {
  const fs::path mesh = dir_ / "in.msh";
  std::ofstream(mesh) << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n3\n1 0 0 0\n2 1 0 0\n3 0 1 0\n$EndNodes\n"
                         "$Elements\n1\n1 2 2 1 1 1 2 3\n$EndElements\n";
  fs::create_symlink(mesh, dir_ / "link.msh");
  read_mesh(dir_ / "link.msh");
  EXPECT_FALSE(input_file_at(mesh).has_value());  // not recording
  record_input_files(true);
  read_mesh(dir_ / "link.msh");
  EXPECT_TRUE(input_file_at(mesh).has_value());
  EXPECT_TRUE(input_file_at(dir_ / "." / "in.msh").has_value());
  EXPECT_TRUE(input_file_at(dir_ / "link.msh").has_value());
  EXPECT_FALSE(input_file_at(dir_ / "out.msh").has_value());
  record_input_files(false);
  EXPECT_FALSE(input_file_at(mesh).has_value());
}

TEST(SameFile, ComparesPathsThatDoNotExistYet) {
  const fs::path cwd = fs::current_path();
  EXPECT_TRUE(same_file("no_such_output.vtu", "./no_such_output.vtu"));
  EXPECT_TRUE(same_file("no_such_output.vtu", cwd / "sub" / ".." / "no_such_output.vtu"));
  EXPECT_FALSE(same_file("no_such_output.vtu", "no_such_report.json"));
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
// group_name_problem and the writers' refusal of names no format can hold.
#include "meshmorph/io/mesh_io.h"

#include <filesystem>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

TEST(GroupName, PlainAndMultiByteNamesAreStorable) {
  for (const char* name : {"", "inlet", "wall 2", "paroi_\xc3\xa9", "\xe6\xb5\x81\xe5\x85\xa5", "\xf0\x9f\x8c\x8a", "a'b&c<d>"})
    EXPECT_FALSE(group_name_problem(name)) << name;
}

TEST(GroupName, ControlBytesQuotesAndBrokenUtf8AreNamed) {
  const std::pair<std::string, std::string> cases[] = {
      {std::string("do\0m", 4), "holds the control byte 0x00 at byte 2"},
      {"a\nb", "holds the control byte 0x0a at byte 1"},
      {"del\x7f", "holds the control byte 0x7f at byte 3"},
      {"say \"hi\"", "holds a double quote at byte 4 (MSH keeps names in quotes)"},
      {"x\xff", "is not valid UTF-8 (byte 0xff at byte 1)"},
      {"\xc3", "is not valid UTF-8 (byte 0xc3 at byte 0)"},            // cut after its lead byte
      {"\xc0\x80", "is not valid UTF-8 (byte 0xc0 at byte 0)"},        // overlong NUL
      {"\xed\xa0\x80", "is not valid UTF-8 (byte 0xed at byte 0)"},    // a surrogate
      {"\xf4\x90\x80\x80", "is not valid UTF-8 (byte 0xf4 at byte 0)"},  // above U+10FFFF
  };
  for (const auto& [name, why] : cases) {
    const auto problem = group_name_problem(name);
    ASSERT_TRUE(problem) << name;
    EXPECT_EQ(*problem, why);
  }
}

TEST(GroupName, EveryWriterRefusesBeforeWritingAnything) {
  Mesh mesh = structured_mesh(ElementType::Triangle, 1, 2);
  mesh.groups.push_back(PhysicalGroup{2, 7, std::string("bad\x01name")});
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_group_name_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  for (const char* file : {"out.msh", "out.vtu", "out.mesh"}) {
    try {
      write_mesh(dir / file, mesh);
      ADD_FAILURE() << file << " was written";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("the name of physical group 7 (dimension 2) holds the control byte 0x01"),
                std::string::npos)
          << e.what();
    }
    EXPECT_FALSE(fs::exists(dir / file)) << file;
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace meshmorph

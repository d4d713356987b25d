// SPDX-License-Identifier: MIT
// Fuzz target: parse_case_file on any bytes, then check_case_against_mesh on a unit square of two
// triangles with named boundary groups and an unnamed one. Bad input must end in InputError (or IoError
// for a referenced file that cannot be read); anything else is a crash. The case names no
// existing folder, so that "mesh" and file references fail unless the fuzzer reaches the tree.
#include <cstddef>
#include <cstdint>
#include <string>

#include "meshmorph/app/case_file.h"
#include "meshmorph/error.h"

namespace {

meshmorph::Mesh unit_square() {
  meshmorph::Mesh m;
  m.dim = 2;
  m.x.resize(2, 4);
  m.x << 0, 1, 1, 0,  //
      0, 0, 1, 1;
  m.node_tags = {1, 2, 3, 4};
  meshmorph::CellBlock tri{meshmorph::ElementType::Triangle, 1, {}, {}, {}};
  const std::int32_t t[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& c : t) tri.push_back(c, 10, 1);
  meshmorph::CellBlock line{meshmorph::ElementType::Line, 1, {}, {}, {}};
  const std::int32_t l[4][2] = {{0, 1}, {1, 2}, {2, 3}, {3, 0}};
  const std::int32_t group[4] = {1, 3, 1, 2};
  for (int i = 0; i < 4; ++i) line.push_back(l[i], group[i], i + 1);
  m.cells = {tri};
  m.facets = {line};
  m.groups = {{1, 1, "wall"}, {1, 2, "inlet"}, {2, 10, "domain"}};
  return m;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const meshmorph::Mesh square = unit_square();
  try {
    const std::string text(reinterpret_cast<const char*>(data), size);
    const meshmorph::CaseFile c = meshmorph::parse_case_file(text, "fuzz-no-folder/case.json", false);
    meshmorph::check_case_against_mesh(c, square);
  } catch (const meshmorph::InputError&) {
  } catch (const meshmorph::IoError&) {
  }
  return 0;
}

// SPDX-License-Identifier: MIT
// Fuzz target: parse_vtu on any bytes (ASCII, base64 and appended arrays, zlib or not). Bad input
// must end in InputError; any other exception, a sanitizer report or a mesh that breaks
// check_mesh is a crash.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "check_mesh.h"
#include "meshmorph/error.h"
#include "meshmorph/io/vtu.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    meshmorph::fuzz::check_mesh(meshmorph::parse_vtu(bytes, "fuzz.vtu"));
  } catch (const meshmorph::InputError&) {
  }
  return 0;
}

// SPDX-License-Identifier: MIT
// Fuzz target: parse_msh on any bytes; the reader dispatches on $MeshFormat to MSH 2.2 or 4.1,
// ASCII or binary. Bad input must end in InputError; any other exception, a sanitizer report
// or a mesh that breaks check_mesh is a crash.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "check_mesh.h"
#include "meshmorph/error.h"
#include "meshmorph/io/msh.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  try {
    const std::string_view bytes(reinterpret_cast<const char*>(data), size);
    meshmorph::fuzz::check_mesh(meshmorph::parse_msh(bytes, "fuzz.msh"));
  } catch (const meshmorph::InputError&) {
  }
  return 0;
}

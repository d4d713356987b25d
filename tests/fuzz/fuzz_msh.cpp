// SPDX-License-Identifier: MIT
// Fuzz target: parse_msh on any bytes; the reader dispatches on $MeshFormat to MSH 2.2 or 4.1,
// ASCII or binary.
#include <cstddef>
#include <cstdint>

#include "meshmorph/io/msh.h"
#include "reader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return meshmorph::fuzz::read_bytes(meshmorph::parse_msh, data, size, "fuzz.msh");
}

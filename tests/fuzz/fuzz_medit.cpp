// SPDX-License-Identifier: MIT
// Fuzz target: parse_medit on any bytes.
#include <cstddef>
#include <cstdint>

#include "meshmorph/io/medit.h"
#include "reader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return meshmorph::fuzz::read_bytes(meshmorph::parse_medit, data, size, "fuzz.mesh");
}

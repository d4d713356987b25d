// SPDX-License-Identifier: MIT
// Fuzz target: parse_su2 on any bytes.
#include <cstddef>
#include <cstdint>

#include "meshmorph/io/su2.h"
#include "reader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return meshmorph::fuzz::read_bytes(meshmorph::parse_su2, data, size, "fuzz.su2");
}

// SPDX-License-Identifier: MIT
// Fuzz target: parse_vtu on any bytes (ASCII, base64 and appended arrays, zlib or not).
#include <cstddef>
#include <cstdint>

#include "meshmorph/io/vtu.h"
#include "reader_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  return meshmorph::fuzz::read_bytes(meshmorph::parse_vtu, data, size, "fuzz.vtu");
}

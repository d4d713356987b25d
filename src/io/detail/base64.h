// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace meshmorph::detail {

/// Appends the base64 encoding of `bytes` (with '=' padding) to `out`.
void base64_encode(std::string_view bytes, std::string& out);

/// Decodes base64 text, ignoring whitespace. Concatenated padded segments (VTK encodes a
/// block header and its data separately) decode to the concatenation of their bytes.
/// Returns nothing, with the offset of the offending character in `bad_at`, on bad input.
std::optional<std::string> base64_decode(std::string_view text, std::size_t& bad_at);

}  // namespace meshmorph::detail

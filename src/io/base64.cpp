// SPDX-License-Identifier: MIT
#include "io/detail/base64.h"

#include <array>

namespace meshmorph::detail {
namespace {

constexpr char k_alphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

constexpr std::array<std::int8_t, 256> make_table() {
  std::array<std::int8_t, 256> t{};
  for (auto& v : t) v = -1;
  for (int i = 0; i < 64; ++i) t[static_cast<unsigned char>(k_alphabet[i])] = static_cast<std::int8_t>(i);
  return t;
}
constexpr std::array<std::int8_t, 256> k_table = make_table();

}  // namespace

void base64_encode(std::string_view bytes, std::string& out) {
  std::size_t o = out.size();
  out.resize(o + (bytes.size() + 2) / 3 * 4);
  char* p = out.data() + o;
  std::size_t i = 0;
  const auto b = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[k])); };
  for (; i + 3 <= bytes.size(); i += 3, p += 4) {
    const std::uint32_t v = b(i) << 16 | b(i + 1) << 8 | b(i + 2);
    p[0] = k_alphabet[v >> 18 & 63];
    p[1] = k_alphabet[v >> 12 & 63];
    p[2] = k_alphabet[v >> 6 & 63];
    p[3] = k_alphabet[v & 63];
  }
  const std::size_t rest = bytes.size() - i;
  if (rest == 0) return;
  const std::uint32_t v = b(i) << 16 | (rest == 2 ? b(i + 1) << 8 : 0);
  p[0] = k_alphabet[v >> 18 & 63];
  p[1] = k_alphabet[v >> 12 & 63];
  p[2] = rest == 2 ? k_alphabet[v >> 6 & 63] : '=';
  p[3] = '=';
}

std::optional<std::string> base64_decode(std::string_view text, std::size_t& bad_at) {
  std::string out;
  out.reserve(text.size() / 4 * 3 + 3);
  std::uint32_t acc = 0;
  int n = 0;     // sextets in the current quantum
  int pads = 0;  // '=' seen in the current quantum
  for (std::size_t i = 0; i < text.size(); ++i) {
    // Fast path: four alphabet characters at a quantum boundary.
    if (n == 0 && pads == 0 && i + 4 <= text.size()) {
      const std::int8_t a = k_table[static_cast<unsigned char>(text[i])], b = k_table[static_cast<unsigned char>(text[i + 1])],
                        c = k_table[static_cast<unsigned char>(text[i + 2])], d = k_table[static_cast<unsigned char>(text[i + 3])];
      if ((a | b | c | d) >= 0) {
        const auto v = static_cast<std::uint32_t>(a) << 18 | static_cast<std::uint32_t>(b) << 12 |
                       static_cast<std::uint32_t>(c) << 6 | static_cast<std::uint32_t>(d);
        out.push_back(static_cast<char>(v >> 16 & 255));
        out.push_back(static_cast<char>(v >> 8 & 255));
        out.push_back(static_cast<char>(v & 255));
        i += 3;
        continue;
      }
    }
    const char ch = text[i];
    if (ch == ' ' || ch == '\n' || ch == '\r' || ch == '\t') continue;
    if (ch == '=') {
      if (n + pads < 2) {
        bad_at = i;
        return std::nullopt;
      }
      ++pads;
    } else {
      const std::int8_t v = k_table[static_cast<unsigned char>(ch)];
      if (v < 0 || pads > 0) {
        bad_at = i;
        return std::nullopt;
      }
      acc = acc << 6 | static_cast<std::uint32_t>(v);
      ++n;
    }
    if (n + pads == 4) {
      acc <<= 6 * pads;
      out.push_back(static_cast<char>(acc >> 16 & 255));
      if (n >= 3) out.push_back(static_cast<char>(acc >> 8 & 255));
      if (n == 4) out.push_back(static_cast<char>(acc & 255));
      acc = 0;
      n = 0;
      pads = 0;
    }
  }
  if (n + pads != 0) {
    bad_at = text.size();
    return std::nullopt;
  }
  return out;
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#include "io/detail/vtu_arrays.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <optional>
#include <type_traits>

#include <zlib.h>

#include "io/detail/base64.h"

namespace meshmorph::detail {
namespace {

std::size_t scalar_size(std::string_view type) {
  if (type == "Int8" || type == "UInt8") return 1;
  if (type == "Int16" || type == "UInt16") return 2;
  if (type == "Int32" || type == "UInt32" || type == "Float32") return 4;
  if (type == "Int64" || type == "UInt64" || type == "Float64") return 8;
  return 0;
}

// Converts little-endian values of VTK type `type` to T (the type is resolved once per array).
template <class T>
void convert(const std::string& bytes, std::string_view type, std::vector<T>& out) {
  const auto run = [&]<class S>(S) {
    out.resize(bytes.size() / sizeof(S));
    for (std::size_t i = 0; i < out.size(); ++i) {
      S v;
      std::memcpy(&v, bytes.data() + i * sizeof(S), sizeof v);
      out[i] = static_cast<T>(v);
    }
  };
  if (type == "Int8") run(std::int8_t{});
  else if (type == "UInt8") run(std::uint8_t{});
  else if (type == "Int16") run(std::int16_t{});
  else if (type == "UInt16") run(std::uint16_t{});
  else if (type == "Int32") run(std::int32_t{});
  else if (type == "UInt32") run(std::uint32_t{});
  else if (type == "Float32") run(float{});
  else if (type == "Int64") run(std::int64_t{});
  else if (type == "UInt64") run(std::uint64_t{});
  else run(double{});
}

// Reads one header integer (UInt32 or UInt64) from `bytes` at `pos`.
std::optional<std::uint64_t> header_value(const VtuFile& f, std::string_view bytes, std::size_t& pos) {
  const std::size_t size = f.header64 ? 8 : 4;
  if (bytes.size() < pos + size) return std::nullopt;
  std::uint64_t v = 0;
  if (f.header64) {
    std::memcpy(&v, bytes.data() + pos, 8);
  } else {
    std::uint32_t w;
    std::memcpy(&w, bytes.data() + pos, 4);
    v = w;
  }
  pos += size;
  return v;
}

// Header + data bytes (as stored) → the array's uncompressed payload, of at most `max_bytes`.
std::string payload(const VtuFile& f, const pugi::xml_node& node, std::string_view bytes, std::uint64_t max_bytes) {
  const std::string name = node.attribute("Name").as_string();
  const auto too_large = [&](std::uint64_t announced) {
    f.fail(node, "DataArray '" + name + "' header announces " + std::to_string(announced) + " bytes, expected at most " +
                     std::to_string(max_bytes));
  };
  std::size_t pos = 0;
  if (!f.compressed) {
    const auto n = header_value(f, bytes, pos);
    if (n && *n > max_bytes) too_large(*n);
    if (!n || bytes.size() - pos < *n) f.fail(node, "binary DataArray is shorter than its byte-count header");
    return std::string(bytes.substr(pos, *n));
  }
  const auto n_blocks = header_value(f, bytes, pos);
  const auto block_size = header_value(f, bytes, pos);
  const auto last_size = header_value(f, bytes, pos);
  if (!n_blocks || !block_size || !last_size || *n_blocks > bytes.size())
    f.fail(node, "truncated compression header in DataArray");
  std::vector<std::uint64_t> csize(*n_blocks);
  for (auto& c : csize) {
    const auto v = header_value(f, bytes, pos);
    if (!v) f.fail(node, "truncated compression header in DataArray");
    c = *v;
  }
  // Every size is checked before the output is allocated. zlib's ratio is 1032:1 at most,
  // which also keeps the total from overflowing.
  const auto raw_size = [&](std::uint64_t b) { return b + 1 == *n_blocks && *last_size != 0 ? *last_size : *block_size; };
  std::uint64_t total = 0;
  std::size_t end = pos;
  for (std::uint64_t b = 0; b < *n_blocks; ++b) {
    if (csize[b] > bytes.size() - end) f.fail(node, "compressed block exceeds the data");
    end += csize[b];
    if (raw_size(b) > 1032 * csize[b])
      f.fail(node, "DataArray '" + name + "' block " + std::to_string(b) + " announces " + std::to_string(raw_size(b)) +
                       " bytes, more than its " + std::to_string(csize[b]) + " compressed bytes can inflate to");
    total += raw_size(b);
  }
  if (total > max_bytes) too_large(total);
  std::string out(total, '\0');
  std::size_t start = 0;
  for (std::uint64_t b = 0; b < *n_blocks; ++b) {
    uLongf dest = static_cast<uLongf>(raw_size(b));
    const int rc = uncompress(reinterpret_cast<Bytef*>(out.data() + start), &dest,
                              reinterpret_cast<const Bytef*>(bytes.data() + pos), static_cast<uLong>(csize[b]));
    if (rc != Z_OK || dest != raw_size(b)) f.fail(node, "zlib cannot decompress DataArray block " + std::to_string(b));
    start += dest;
    pos += csize[b];
  }
  return out;
}

}  // namespace

template <class T>
std::vector<T> read_array(const VtuFile& f, const pugi::xml_node& node, ValueCount count, bool allow_nonfinite) {
  const std::string_view name = node.attribute("Name").as_string();
  const std::string_view type = node.attribute("type").as_string();
  const std::string_view format = node.attribute("format").as_string("ascii");
  const std::size_t size = scalar_size(type);
  if (size == 0) f.fail(node, "DataArray '" + std::string(name) + "' has unknown type '" + std::string(type) + "'");
  const bool is_float = type.starts_with("Float");
  if (std::is_integral_v<T> && is_float) f.fail(node, "DataArray '" + std::string(name) + "' must hold integers");
  const std::uint64_t max_bytes = count.n > std::numeric_limits<std::uint64_t>::max() / size
                                       ? std::numeric_limits<std::uint64_t>::max()
                                       : count.n * size;
  std::vector<T> values;
  if (format == "ascii") {
    const std::string_view body = node.text().get();
    Cursor c(f.path, body);
    while (c.skip_space()) {
      const std::string_view t = c.token("a value");
      T v{};
      const char* b = t.data() + (t[0] == '+' ? 1 : 0);
      const auto [end, ec] = std::from_chars(b, t.data() + t.size(), v);
      if (ec != std::errc() || end != t.data() + t.size())
        f.fail(node, "DataArray '" + std::string(name) + "': bad value '" + Cursor::shorten(t) + "'");
      values.push_back(v);
    }
  } else {
    std::string bytes;
    std::size_t bad = 0;
    if (format == "binary") {
      auto decoded = base64_decode(node.text().get(), bad);
      if (!decoded) f.fail(node, "DataArray '" + std::string(name) + "': invalid base64 data");
      bytes = payload(f, node, *decoded, max_bytes);
    } else if (format == "appended") {
      if (f.appended == std::string_view::npos) f.fail(node, "format=\"appended\" but there is no AppendedData");
      const std::size_t offset = f.appended_offset(node);
      if (offset > f.appended_end - f.appended) f.fail(node, "DataArray offset is outside the AppendedData");
      const auto next = std::upper_bound(f.appended_offsets.begin(), f.appended_offsets.end(), offset);
      const std::size_t end = next == f.appended_offsets.end() ? f.appended_end - f.appended : *next;
      std::string_view region = f.text.substr(f.appended + offset, end - offset);
      if (f.appended_base64) {
        auto decoded = base64_decode(region, bad);
        if (!decoded) f.fail(node, "DataArray '" + std::string(name) + "': invalid base64 in AppendedData");
        bytes = payload(f, node, *decoded, max_bytes);
      } else {
        bytes = payload(f, node, region, max_bytes);
      }
    } else {
      f.fail(node, "DataArray '" + std::string(name) + "' has unknown format '" + std::string(format) + "'");
    }
    if (bytes.size() % size != 0) f.fail(node, "DataArray '" + std::string(name) + "' size is not a multiple of its type");
    convert(bytes, type, values);
  }
  if constexpr (std::is_floating_point_v<T>) {
    if (!allow_nonfinite)
      for (const T v : values)
        if (!std::isfinite(v)) f.fail(node, "DataArray '" + std::string(name) + "' holds a non-finite value");
  }
  if (count.exact ? values.size() != count.n : values.size() > count.n)
    f.fail(node, "DataArray '" + std::string(name) + "' holds " + std::to_string(values.size()) + " values, expected " +
                     (count.exact ? "" : "at most ") + std::to_string(count.n));
  return values;
}

template std::vector<double> read_array<double>(const VtuFile&, const pugi::xml_node&, ValueCount, bool);
template std::vector<std::int64_t> read_array<std::int64_t>(const VtuFile&, const pugi::xml_node&, ValueCount, bool);

}  // namespace meshmorph::detail

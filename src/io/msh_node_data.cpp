// SPDX-License-Identifier: MIT
// $NodeData sections (MSH 2.2 and 4.1). The header is text in both encodings: string tags
// (the first is the field name), real tags (the time), integer tags (time step, number of
// components, number of values[, partition]). The records follow as text or, in binary
// files, as (int32 node tag, components × double): Gmsh writes 4-byte tags in 4.1 too,
// although the 4.1 specification says size_t, and meshio reads them the same way.
#include <algorithm>
#include <cstdint>
#include <limits>
#include <string>

#include "io/detail/msh_reader.h"

namespace meshmorph::detail {
namespace {

std::string quoted(Cursor& c, const std::string& what) {
  if (!c.skip_space()) c.fail("unexpected end of file, expected " + what);
  const std::string_view t = c.text();
  const std::size_t open = c.pos();
  if (t[open] != '"') c.fail("expected " + what + " in double quotes");
  std::size_t close = open + 1;
  while (close < t.size() && t[close] != '"' && t[close] != '\n') ++close;
  if (close >= t.size() || t[close] != '"') c.fail_at(open, "missing closing quote in " + what);
  c.seek(close + 1);
  return std::string(t.substr(open + 1, close - open - 1));
}

}  // namespace

void read_node_data(MshState& s, std::size_t at) {
  Cursor& c = s.cur;
  const auto n_strings = c.integer<std::uint64_t>("number of string tags");
  s.check_count(n_strings, 3, c.token_start());
  if (n_strings == 0) c.fail_at(c.token_start(), "$NodeData needs a string tag (the field name)");
  std::string name;
  for (std::uint64_t i = 0; i < n_strings; ++i) {
    std::string tag = quoted(c, "string tag");
    if (i == 0) name = std::move(tag);
  }
  if (name.empty()) c.fail("$NodeData has an empty field name");
  const auto n_reals = c.integer<std::uint64_t>("number of real tags");
  s.check_count(n_reals, 2, c.token_start());
  for (std::uint64_t i = 0; i < n_reals; ++i) c.real("real tag");
  const auto n_ints = c.integer<std::uint64_t>("number of integer tags");
  s.check_count(n_ints, 2, c.token_start());
  if (n_ints < 3)
    c.fail_at(c.token_start(), "$NodeData needs 3 integer tags (time step, number of components, number of values), found " +
                                   std::to_string(n_ints));
  const auto step = c.integer<std::int64_t>("time step");
  const int n_components = c.integer<int>("number of components");
  if (n_components < 1 || n_components > 9) c.fail_at(c.token_start(), "number of components must be 1..9");
  const auto n_values = c.integer<std::uint64_t>("number of values");
  const std::size_t n_values_at = c.token_start();
  for (std::uint64_t i = 3; i < n_ints; ++i) c.integer<std::int64_t>("integer tag");
  const auto components = static_cast<std::size_t>(n_components);
  s.check_count(n_values, s.binary ? 4 + 8 * components : 2 * (1 + components), n_values_at);

  // Only scalar fields are kept; the others are read (and so checked) and dropped.
  MshState::NodeField* field = nullptr;
  if (n_components == 1) {
    auto [it, fresh] = s.node_fields.try_emplace(name);
    if (fresh || it->second.step != step) {
      const std::size_t n_nodes = s.builder.tags.size();
      it->second.step = step;
      it->second.values.assign(n_nodes, std::numeric_limits<double>::quiet_NaN());
      it->second.given.assign(n_nodes, 0);
    }
    it->second.at = at;
    field = &it->second;
  }
  if (s.binary) {
    c.skip_line();  // the rest of the last integer tag's line
    c.binary = true;
  }
  for (std::uint64_t i = 0; i < n_values; ++i) {
    std::int64_t tag = 0;
    std::size_t tag_at = 0;
    if (s.binary) {
      tag_at = c.pos();
      tag = c.raw<std::int32_t>("node tag");
    } else {
      tag = c.integer<std::int64_t>("node tag");
      tag_at = c.token_start();
    }
    const std::int32_t node = s.index.find(tag);
    if (node < 0)
      c.fail_at(tag_at, "$NodeData \"" + name + "\" gives a value to undefined node tag " + std::to_string(tag));
    for (std::size_t k = 0; k < components; ++k) {
      const double v = s.binary ? c.raw<double>("field value") : c.number("field value");
      if (field && k == 0) {
        field->values[static_cast<std::size_t>(node)] = v;
        field->given[static_cast<std::size_t>(node)] = 1;
      }
    }
  }
}

void finish_node_data(MshState& s) {
  for (auto& [name, field] : s.node_fields) {
    const auto missing = std::find(field.given.begin(), field.given.end(), std::uint8_t{0});
    if (missing != field.given.end()) {
      const auto node = static_cast<std::size_t>(missing - field.given.begin());
      const auto have = std::count(field.given.begin(), field.given.end(), std::uint8_t{1});
      throw_input_error(s.cur.file(), s.cur.text(), field.at, s.binary,
                        "$NodeData \"" + name + "\" (time step " + std::to_string(field.step) + ") has no value for node tag " +
                            std::to_string(s.builder.tags[node]) + " (" + std::to_string(have) + " of " +
                            std::to_string(field.given.size()) + " nodes have one)");
    }
    s.builder.node_fields[name] = std::move(field.values);
  }
  s.node_fields.clear();
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#include "app/detail/json_reader.h"

#include <cmath>
#include <limits>

#include "meshmorph/error.h"

namespace meshmorph::detail {

using nlohmann::json;

JsonWhere JsonWhere::key(std::string_view k) const {
  return {file, path.empty() ? std::string(k) : path + "." + std::string(k)};
}

JsonWhere JsonWhere::index(std::size_t i) const {
  return {file, path + "[" + std::to_string(i) + "]"};
}

void JsonWhere::fail(const std::string& what) const {
  throw InputError(file + ": " + (path.empty() ? std::string("(top level)") : path) + ": " + what);
}

std::string json_type_phrase(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array";
    case json::value_t::string: return "a string";
    case json::value_t::boolean: return "a boolean";
    case json::value_t::binary: return "binary data";
    case json::value_t::discarded: return "nothing";
    default: return "a number";
  }
}

ObjectReader::ObjectReader(const json& j, JsonWhere where) : j_(j), where_(std::move(where)) {
  if (!j_.is_object()) where_.fail("expected an object, found " + json_type_phrase(j_));
}

const json* ObjectReader::optional(std::string_view key) {
  known_.emplace(key);
  auto it = j_.find(key);
  return it == j_.end() ? nullptr : &*it;
}

const json& ObjectReader::required(std::string_view key) {
  const json* j = optional(key);
  if (!j) where_.fail("missing key \"" + std::string(key) + "\"");
  return *j;
}

void ObjectReader::finish() const {
  for (const auto& [key, value] : j_.items()) {
    if (known_.count(key)) continue;
    std::string expected;
    for (const auto& k : known_) {
      if (!expected.empty()) expected += ", ";
      expected += k;
    }
    where_.key(key).fail("unknown key (expected one of: " + expected + ")");
  }
}

double read_number(const json& j, const JsonWhere& w) {
  if (!j.is_number()) w.fail("expected a number, found " + json_type_phrase(j));
  const double v = j.get<double>();
  if (!std::isfinite(v)) w.fail("expected a finite number");
  return v;
}

double read_positive(const json& j, const JsonWhere& w) {
  const double v = read_number(j, w);
  if (!(v > 0)) w.fail("expected a positive number, found " + j.dump());
  return v;
}

long long read_integer(const json& j, const JsonWhere& w) {
  if (j.is_number_integer()) return j.get<long long>();
  if (j.is_number_float()) {
    // 2.0 is accepted as 2; 2.5 is not.
    const double v = j.get<double>();
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9.0e15) return static_cast<long long>(v);
    w.fail("expected an integer, found " + j.dump());
  }
  w.fail("expected an integer, found " + json_type_phrase(j));
}

bool read_bool(const json& j, const JsonWhere& w) {
  if (!j.is_boolean()) w.fail("expected true or false, found " + json_type_phrase(j));
  return j.get<bool>();
}

std::string read_string(const json& j, const JsonWhere& w) {
  if (!j.is_string()) w.fail("expected a string, found " + json_type_phrase(j));
  std::string s = j.get<std::string>();
  if (s.empty()) w.fail("expected a non-empty string");
  return s;
}

CaseVector read_vector(const json& j, const JsonWhere& w) {
  if (!j.is_array() || j.size() < 2 || j.size() > 3)
    w.fail("expected 2 or 3 numbers, found " + (j.is_array() ? std::to_string(j.size()) + " entries"
                                                             : json_type_phrase(j)));
  CaseVector v(static_cast<Eigen::Index>(j.size()));
  for (std::size_t i = 0; i < j.size(); ++i) v(static_cast<Eigen::Index>(i)) = read_number(j[i], w.index(i));
  return v;
}

CaseVector read_direction(const json& j, const JsonWhere& w) {
  const CaseVector v = read_vector(j, w);
  // stableNorm: |(1e308, 1e308)| overflows in norm(), and v / inf is the zero vector.
  const double length = v.stableNorm();
  if (!(length > 0)) w.fail("expected a non-zero vector");
  return v / length;
}

}  // namespace meshmorph::detail

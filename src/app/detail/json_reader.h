// SPDX-License-Identifier: MIT
#pragma once
#include <initializer_list>
#include <set>
#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

#include "meshmorph/app/case_file.h"

namespace meshmorph::detail {

/// Where a JSON value sits: the file (for messages) and its key path ("boundary[2].rotate").
struct JsonWhere {
  std::string file;
  std::string path;

  JsonWhere key(std::string_view k) const;
  JsonWhere index(std::size_t i) const;
  /// Throws InputError "file: path: what".
  [[noreturn]] void fail(const std::string& what) const;
};

/// "a string", "a number", ... for "expected X, found Y" messages.
std::string json_type_phrase(const nlohmann::json& j);

/// Reads the members of one JSON object; finish() rejects members nobody asked for.
class ObjectReader {
 public:
  ObjectReader(const nlohmann::json& j, JsonWhere where);
  /// The member `key`, or nullptr; either way `key` becomes a known key.
  const nlohmann::json* optional(std::string_view key);
  /// The member `key`; throws "path: missing key "key"" when absent.
  const nlohmann::json& required(std::string_view key);
  /// Throws for the first member (in file order) that was never asked for.
  void finish() const;
  const JsonWhere& where() const { return where_; }
  JsonWhere at(std::string_view key) const { return where_.key(key); }

 private:
  const nlohmann::json& j_;
  JsonWhere where_;
  std::set<std::string, std::less<>> known_;
};

double read_number(const nlohmann::json& j, const JsonWhere& w);        ///< finite
double read_positive(const nlohmann::json& j, const JsonWhere& w);      ///< finite, > 0
long long read_integer(const nlohmann::json& j, const JsonWhere& w);    ///< integral value
bool read_bool(const nlohmann::json& j, const JsonWhere& w);
std::string read_string(const nlohmann::json& j, const JsonWhere& w);   ///< non-empty
/// 2 or 3 finite numbers.
CaseVector read_vector(const nlohmann::json& j, const JsonWhere& w);
/// As read_vector, and not the zero vector (axes, normals).
CaseVector read_direction(const nlohmann::json& j, const JsonWhere& w);

}  // namespace meshmorph::detail

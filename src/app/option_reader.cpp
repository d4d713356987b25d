// SPDX-License-Identifier: MIT
#include "meshmorph/app/option_reader.h"

#include <cmath>

#include "app/detail/json_reader.h"
#include "meshmorph/error.h"

namespace meshmorph {

using detail::JsonWhere;

OptionReader::OptionReader(const nlohmann::json& options, std::string file, std::string path)
    : options_(options), file_(std::move(file)), path_(std::move(path)) {
  if (!options_.is_object())
    JsonWhere{file_, path_}.fail("expected an object, found " + detail::json_type_phrase(options_));
}

const nlohmann::json* OptionReader::find(std::string_view name) {
  declared_.emplace(name);
  auto it = options_.find(name);
  return it == options_.end() ? nullptr : &*it;
}

bool OptionReader::has(std::string_view name) { return find(name) != nullptr; }

void OptionReader::read(std::string_view name, double& value, double lo, double hi) {
  const nlohmann::json* j = find(name);
  if (!j) return;
  const JsonWhere w = JsonWhere{file_, path_}.key(name);
  const double v = detail::read_number(*j, w);
  if (v < lo || v > hi) w.fail("expected a number in [" + nlohmann::json(lo).dump() + ", " + nlohmann::json(hi).dump() +
                               "], found " + j->dump());
  value = v;
}

void OptionReader::read(std::string_view name, int& value, int lo, int hi) {
  const nlohmann::json* j = find(name);
  if (!j) return;
  const JsonWhere w = JsonWhere{file_, path_}.key(name);
  const long long v = detail::read_integer(*j, w);
  if (v < lo || v > hi)
    w.fail("expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], found " + j->dump());
  value = static_cast<int>(v);
}

void OptionReader::read(std::string_view name, bool& value) {
  if (const nlohmann::json* j = find(name)) value = detail::read_bool(*j, JsonWhere{file_, path_}.key(name));
}

void OptionReader::read(std::string_view name, std::string& value, std::initializer_list<std::string_view> choices) {
  const nlohmann::json* j = find(name);
  if (!j) return;
  const JsonWhere w = JsonWhere{file_, path_}.key(name);
  std::string v = detail::read_string(*j, w);
  if (choices.size() > 0) {
    std::string list;
    bool ok = false;
    for (auto c : choices) {
      ok = ok || c == v;
      if (!list.empty()) list += ", ";
      list += std::string(c);
    }
    if (!ok) w.fail("expected one of: " + list + "; found \"" + v + "\"");
  }
  value = std::move(v);
}

void OptionReader::finish() const {
  for (const auto& item : options_.items()) {
    if (declared_.count(item.key())) continue;
    std::string list;
    for (const auto& d : declared_) {
      if (!list.empty()) list += ", ";
      list += d;
    }
    JsonWhere{file_, path_}.key(item.key()).fail(list.empty() ? std::string("unknown option (this method takes none)")
                                                              : "unknown option (expected one of: " + list + ")");
  }
}

}  // namespace meshmorph

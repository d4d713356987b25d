// SPDX-License-Identifier: MIT
#include "meshmorph/app/case_file.h"

#include <algorithm>
#include <fstream>
#include <set>
#include <tuple>
#include <sstream>

#include "app/detail/case_parts.h"
#include "app/detail/json_reader.h"
#include "meshmorph/error.h"
#include "meshmorph/io/foam.h"
#include "meshmorph/io/input_files.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/timings.h"

namespace meshmorph {

using nlohmann::json;
using detail::JsonWhere;

namespace {

// 1-based line and column of a 1-based byte position (nlohmann's parse_error::byte).
std::pair<std::size_t, std::size_t> line_column(const std::string& text, std::size_t byte) {
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i + 1 < byte && i < text.size(); ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return {line, column};
}

// Rejects repeated keys, which nlohmann would silently collapse to the last one, and nesting
// deeper than any case needs: level sets are read (and CSG trees evaluated) recursively, and
// 10 000 nested unions overflowed the stack.
class StructureGuard {
 public:
  explicit StructureGuard(std::string file) : file_(std::move(file)) {}
  static constexpr std::size_t k_max_depth = 128;

  bool operator()(int, json::parse_event_t event, json& parsed) {
    using E = json::parse_event_t;
    if ((event == E::object_start || event == E::array_start || event == E::value) && !frames_.empty() &&
        !frames_.back().is_object)
      frames_.back().index = frames_.back().count++;
    if (event == E::object_start || event == E::array_start) {
      if (frames_.size() == k_max_depth)
        JsonWhere{file_, path()}.fail("nested more than " + std::to_string(k_max_depth) + " levels deep");
      frames_.push_back({event == E::object_start, {}, {}, 0, 0});
    } else if (event == E::object_end || event == E::array_end) {
      frames_.pop_back();
    } else if (event == E::key) {
      Frame& f = frames_.back();
      const std::string key = parsed.get<std::string>();
      if (!f.keys.insert(key).second) {
        std::string where = path();
        if (!where.empty()) where += '.';
        where += key;
        JsonWhere{file_, where}.fail("duplicate key");
      }
      f.last_key = key;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_object;
    std::set<std::string> keys;
    std::string last_key;
    std::size_t index, count;
  };
  // Path of the object on top of the stack (each frame but the last contributes its child).
  std::string path() const {
    std::string p;
    for (std::size_t i = 0; i + 1 < frames_.size(); ++i) {
      const Frame& f = frames_[i];
      if (f.is_object) {
        if (!p.empty()) p += '.';
        p += f.last_key;
      } else {
        p += '[';
        p += std::to_string(f.index);
        p += ']';
      }
    }
    return p;
  }
  std::string file_;
  std::vector<Frame> frames_;
};

std::optional<LevelSet> optional_level_set(detail::ObjectReader& r, std::string_view key,
                                           const std::filesystem::path& base) {
  if (const json* j = r.optional(key)) return detail::parse_level_set(*j, r.at(key), base);
  return std::nullopt;
}

std::filesystem::path output_path(const json& j, const JsonWhere& w, const std::filesystem::path& base,
                                  bool mesh_format) {
  const std::filesystem::path p = base / detail::read_string(j, w);
  if (mesh_format) {
    if (!known_mesh_format(p) && !is_foam_time_folder(p))
      w.fail("expected a .msh, .vtu or .mesh file name (or .su2, .cgns, .exo, or an OpenFOAM case's time folder), found \"" +
             p.filename().string() + "\"");
  }
  return p;
}

}  // namespace

CaseFile parse_case_file(const std::string& text, const std::filesystem::path& file, bool mesh_required) {
  const std::string name = file.string();
  json root;
  try {
    root = json::parse(text, StructureGuard(name));
  } catch (const json::parse_error& e) {
    const auto [line, column] = line_column(text, e.byte);
    std::string what = e.what();
    if (auto at = what.find("column "); at != std::string::npos && what.find(": ", at) != std::string::npos)
      what = what.substr(what.find(": ", at) + 2);
    throw InputError(name + ":" + std::to_string(line) + ":" + std::to_string(column) + ": invalid JSON: " + what);
  } catch (const json::out_of_range& e) {
    // A number too large for a double ("1e999"): nlohmann names the literal, not its place.
    std::string what = e.what();
    std::size_t line = 0, column = 0;
    if (auto q = what.find('\''); q != std::string::npos) {
      const std::string literal = what.substr(q + 1, what.find('\'', q + 1) - q - 1);
      if (auto at = text.find(literal); at != std::string::npos) std::tie(line, column) = line_column(text, at + 1);
      what = "number out of range: " + literal;
    }
    throw InputError(name + ":" + std::to_string(line) + ":" + std::to_string(column) + ": invalid JSON: " + what);
  }

  const std::filesystem::path base = file.parent_path();
  CaseFile c;
  c.file = file;
  detail::ObjectReader r(root, JsonWhere{name, ""});
  if (root.is_object())
    for (const auto& item : root.items()) c.keys.push_back(item.key());
  if (const json* j = mesh_required ? &r.required("mesh") : r.optional("mesh")) {
    const std::string mesh_name = detail::read_string(*j, r.at("mesh"));
    const std::filesystem::path folder =
        std::filesystem::path(mesh_name).is_absolute() ? std::filesystem::path(mesh_name) : base / mesh_name;
    std::error_code ec;  // a folder is an OpenFOAM case (io/foam.h)
    c.mesh = std::filesystem::is_directory(folder, ec) ? folder : detail::existing_file(mesh_name, base, r.at("mesh"));
  }
  if (const json* j = r.optional("order")) {
    const long long order = detail::read_integer(*j, r.at("order"));
    if (order < 1 || order > 4) r.at("order").fail("expected an order from 1 to 4, found " + j->dump());
    c.order = static_cast<int>(order);
  }
  if (const json* j = r.optional("boundary")) {
    if (!j->is_array()) r.at("boundary").fail("expected a list of boundary entries, found " + detail::json_type_phrase(*j));
    for (std::size_t i = 0; i < j->size(); ++i)
      c.boundary.push_back(detail::parse_boundary_condition((*j)[i], r.at("boundary").index(i), base));
  }
  c.interface = optional_level_set(r, "interface", base);
  c.trim = optional_level_set(r, "trim", base);
  if (const json* j = r.optional("steps")) {
    const long long steps = detail::read_integer(*j, r.at("steps"));
    if (steps < 1 || steps > 1000000) r.at("steps").fail("expected a step count from 1 to 1000000, found " + j->dump());
    c.steps = static_cast<int>(steps);
  }
  if (const json* j = r.optional("output_each_step")) c.output_each_step = detail::read_bool(*j, r.at("output_each_step"));
  if (const json* j = r.optional("dt")) c.dt = detail::read_positive(*j, r.at("dt"));
  if (const json* j = r.optional("reorient")) c.reorient = detail::read_bool(*j, r.at("reorient"));
  if (const json* j = r.optional("options")) {
    if (!j->is_object()) r.at("options").fail("expected an object, found " + detail::json_type_phrase(*j));
    c.options = *j;
  }
  if (const json* j = r.optional("output")) c.output = output_path(*j, r.at("output"), base, true);
  if (const json* j = r.optional("report")) c.report = output_path(*j, r.at("report"), base, false);
  r.finish();
  return c;
}

void reject_unused_keys(const CaseFile& c, const std::string& method, std::initializer_list<std::string_view> unused) {
  for (const std::string& key : c.keys)
    if (std::find(unused.begin(), unused.end(), key) != unused.end()) {
      const std::string owner = key == "interface" || key == "trim" ? "fit" : "morph, untangle and deform";
      throw InputError(c.file.string() + ": " + key + ": " + method + " does not use this key; it is for " + owner +
                       " (docs/case-file.md)");
    }
}

CaseFile bare_case(const std::filesystem::path& path) {
  CaseFile c;
  c.file = path;
  c.mesh = path;
  return c;
}

CaseFile read_case_file(const std::filesystem::path& path) {
  const PhaseTimer timer(Phase::Io);
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw IoError(path.string() + ": is a folder, not a case file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot open the case file");
  note_input_file(path);
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError(path.string() + ": cannot read the case file");
  return parse_case_file(text.str(), path);
}

}  // namespace meshmorph

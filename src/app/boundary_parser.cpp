// SPDX-License-Identifier: MIT
#include <cmath>
#include <string>

#include "app/detail/case_parts.h"
#include "meshmorph/error.h"

namespace meshmorph::detail {

using nlohmann::json;

namespace {

constexpr const char* kMotions = "fixed, translate, rotate, scale, project, displace, slide";

bool is_motion(const std::string& key) {
  for (const char* m : {"fixed", "translate", "rotate", "scale", "project", "displace", "slide"})
    if (key == m) return true;
  return false;
}

// "fixed": true and "slide": true are flags; false would mean "no motion given".
void require_true(const json& v, const JsonWhere& w) {
  if (!read_bool(v, w)) w.fail("expected true (omit the entry to leave the group to the default)");
}

std::string read_group(const json& g, const JsonWhere& w) {
  if (g.is_string()) {
    std::string name = g.get<std::string>();
    if (name.empty()) w.fail("expected a group name or number, found an empty string");
    return name;
  }
  if (g.is_number()) {
    const long long tag = read_integer(g, w);
    if (tag < 1) w.fail("expected a positive physical-group number, found " + g.dump());
    return std::to_string(tag);
  }
  w.fail("expected a group name (string) or number, found " + json_type_phrase(g));
}

Motion parse_motion(const std::string& kind, const json& v, const JsonWhere& at,
                    const std::filesystem::path& base) {
  if (kind == "fixed") {
    require_true(v, at);
    return FixedMotion{};
  }
  if (kind == "slide") {
    require_true(v, at);
    return SlideMotion{};
  }
  if (kind == "translate") return TranslateMotion{read_vector(v, at)};
  if (kind == "rotate") {
    ObjectReader r(v, at);
    RotateMotion m;
    m.center = read_vector(r.required("center"), r.at("center"));
    if (const json* axis = r.optional("axis")) {
      m.axis = read_direction(*axis, r.at("axis"));
      if (m.axis->size() != 3) r.at("axis").fail("expected 3 numbers (a rotation axis exists only in 3D)");
    }
    m.degrees = read_number(r.required("degrees"), r.at("degrees"));
    r.finish();
    return m;
  }
  if (kind == "scale") {
    ObjectReader r(v, at);
    ScaleMotion m;
    m.center = read_vector(r.required("center"), r.at("center"));
    m.factor = read_positive(r.required("factor"), r.at("factor"));
    r.finish();
    return m;
  }
  if (kind == "project") return ProjectMotion{parse_level_set(v, at, base)};
  if (kind == "displace") {
    ObjectReader r(v, at);
    const JsonWhere wf = r.at("file");
    const std::filesystem::path file = existing_file(read_string(r.required("file"), wf), base, wf);
    r.finish();
    return DisplaceMotion{read_displacement_csv(file)};
  }
  at.fail(std::string("unknown motion (expected one of: ") + kMotions + ")");
}

}  // namespace

BoundaryCondition parse_boundary_condition(const json& j, const JsonWhere& w, const std::filesystem::path& base) {
  if (!j.is_object()) w.fail("expected an object {\"group\": ..., <motion>: ...}, found " + json_type_phrase(j));
  BoundaryCondition bc;
  bc.key_path = w.path;
  std::string motion_key;
  for (const auto& item : j.items()) {
    const std::string& key = item.key();
    if (key == "group") continue;
    if (!is_motion(key)) w.key(key).fail(std::string("unknown key (expected one of: group, ") + kMotions + ")");
    if (!motion_key.empty())
      w.key(key).fail("a boundary entry takes one motion; \"" + motion_key + "\" is already given");
    motion_key = key;
  }
  auto g = j.find("group");
  if (g == j.end()) w.fail("missing key \"group\"");
  bc.group = read_group(*g, w.key("group"));
  if (motion_key.empty()) w.fail(std::string("missing motion (one of: ") + kMotions + ")");
  bc.motion = parse_motion(motion_key, j.at(motion_key), w.key(motion_key), base);
  return bc;
}

}  // namespace meshmorph::detail

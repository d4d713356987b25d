// SPDX-License-Identifier: MIT
#include <cmath>
#include <cstdint>
#include <string>

#include <muParser.h>

#include "app/detail/case_parts.h"
#include "meshmorph/error.h"

namespace meshmorph::detail {

using nlohmann::json;

namespace {

constexpr const char* kKinds =
    "sphere, cylinder, plane, box, torus, expr, union, intersection, difference, mesh, distance";

std::vector<LevelSet> parse_operands(const json& j, const JsonWhere& w, const std::filesystem::path& base,
                                     std::size_t min_count, std::size_t max_count) {
  if (!j.is_array()) w.fail("expected a list of level sets, found " + json_type_phrase(j));
  if (j.size() < min_count || j.size() > max_count) {
    w.fail(min_count == max_count ? "expected exactly " + std::to_string(min_count) + " level sets, found " +
                                        std::to_string(j.size())
                                  : "expected at least " + std::to_string(min_count) + " level set");
  }
  std::vector<LevelSet> operands;
  for (std::size_t i = 0; i < j.size(); ++i) operands.push_back(parse_level_set(j[i], w.index(i), base));
  return operands;
}

}  // namespace

void check_expression(const std::string& expression, const JsonWhere& w) {
  if (expression.find_first_not_of(" \t\r\n") == std::string::npos) w.fail("empty expression");
  double x = 0.1, y = 0.2, z = 0.3;
  try {
    mu::Parser parser;
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.DefineVar("z", &z);
    parser.DefineConst("pi", 3.14159265358979323846);
    parser.SetExpr(expression);
    // muparser parses lazily: the first evaluation reports syntax and name errors.
    (void)parser.Eval();
    // "x, y" is two expressions to muparser, of which σ would silently be the last.
    if (parser.GetNumResults() != 1)
      w.fail("expression \"" + expression + "\" gives " + std::to_string(parser.GetNumResults()) +
             " values (separated by commas); a level set is one");
  } catch (const mu::Parser::exception_type& e) {
    w.fail("invalid expression \"" + expression + "\": " + e.GetMsg() + " (at character " +
           std::to_string(e.GetPos() + 1) + ")");
  }
}

std::filesystem::path existing_file(const std::string& relative, const std::filesystem::path& base,
                                    const JsonWhere& w) {
  const std::filesystem::path p = std::filesystem::path(relative).is_absolute() ? std::filesystem::path(relative)
                                                                                : base / relative;
  std::error_code ec;
  if (!std::filesystem::is_regular_file(p, ec)) w.fail("file not found: " + p.string());
  return p;
}

LevelSet parse_level_set(const json& j, const JsonWhere& w, const std::filesystem::path& base) {
  if (!j.is_object()) w.fail(std::string("expected a level-set object {\"<kind>\": ...} (kinds: ") + kKinds +
                             "), found " + json_type_phrase(j));
  // A CSG kind may carry "blend" beside it.
  const bool blended = j.size() == 2 && j.contains("blend");
  if (j.size() != 1 && !blended)
    w.fail(std::string("expected exactly one level-set kind (") + kKinds + "), found " + std::to_string(j.size()) +
           " keys");
  const auto first = blended && j.begin().key() == "blend" ? std::next(j.begin()) : j.begin();
  const std::string kind = first.key();
  const json& v = first.value();
  const JsonWhere at = w.key(kind);
  // Read here for the CSG kinds; beside any other known kind it is rejected after the
  // chain below, where an unknown kind has failed first.
  double blend = 0.0;
  if (blended && (kind == "union" || kind == "intersection" || kind == "difference"))
    blend = read_positive(j.at("blend"), w.key("blend"));
  LevelSet ls;
  ls.key_path = w.path;
  if (kind == "sphere") {
    ObjectReader r(v, at);
    ls.shape = SphereLevelSet{read_vector(r.required("center"), r.at("center")),
                              read_positive(r.required("radius"), r.at("radius"))};
    r.finish();
  } else if (kind == "cylinder") {
    ObjectReader r(v, at);
    ls.shape = CylinderLevelSet{read_vector(r.required("center"), r.at("center")),
                                read_direction(r.required("axis"), r.at("axis")),
                                read_positive(r.required("radius"), r.at("radius"))};
    r.finish();
  } else if (kind == "plane") {
    ObjectReader r(v, at);
    ls.shape = PlaneLevelSet{read_vector(r.required("point"), r.at("point")),
                             read_direction(r.required("normal"), r.at("normal"))};
    r.finish();
  } else if (kind == "box") {
    ObjectReader r(v, at);
    BoxLevelSet box{read_vector(r.required("center"), r.at("center")),
                    read_vector(r.required("size"), r.at("size"))};
    if (box.size.minCoeff() <= 0) r.at("size").fail("expected positive edge lengths");
    if (box.size.size() != box.center.size()) r.at("size").fail("expected as many entries as \"center\"");
    ls.shape = std::move(box);
    r.finish();
  } else if (kind == "torus") {
    ObjectReader r(v, at);
    ls.shape = TorusLevelSet{read_vector(r.required("center"), r.at("center")),
                             read_direction(r.required("axis"), r.at("axis")),
                             read_positive(r.required("major"), r.at("major")),
                             read_positive(r.required("minor"), r.at("minor"))};
    r.finish();
  } else if (kind == "expr") {
    if (!v.is_string()) at.fail("expected an expression string in x, y, z, found " + json_type_phrase(v));
    std::string expression = v.get<std::string>();
    check_expression(expression, at);
    ls.shape = ExprLevelSet{std::move(expression)};
  } else if (kind == "union") {
    ls.shape = UnionLevelSet{parse_operands(v, at, base, 1, SIZE_MAX), blend};
  } else if (kind == "intersection") {
    ls.shape = IntersectionLevelSet{parse_operands(v, at, base, 1, SIZE_MAX), blend};
  } else if (kind == "difference") {
    ls.shape = DifferenceLevelSet{parse_operands(v, at, base, 2, 2), blend};
  } else if (kind == "mesh") {
    ObjectReader r(v, at);
    MeshLevelSet m;
    m.file = existing_file(read_string(r.required("file"), r.at("file")), base, r.at("file"));
    m.field = read_string(r.required("field"), r.at("field"));
    ls.shape = std::move(m);
    r.finish();
  } else if (kind == "distance") {
    ObjectReader r(v, at);
    DistanceLevelSet d;
    d.operands.push_back(parse_level_set(r.required("of"), r.at("of"), base));
    d.lower = read_vector(r.required("lower"), r.at("lower"));
    d.upper = read_vector(r.required("upper"), r.at("upper"));
    if (d.upper.size() != d.lower.size()) r.at("upper").fail("expected as many entries as \"lower\"");
    if (!((d.upper - d.lower).minCoeff() > 0)) r.at("upper").fail("expected every entry above \"lower\"'s");
    const auto integer = [&](const char* key, int& value, int lo, int hi) {
      if (const json* given = r.optional(key)) {
        const long long n = read_integer(*given, r.at(key));
        if (n < lo || n > hi) r.at(key).fail("expected an integer from " + std::to_string(lo) + " to " + std::to_string(hi));
        value = static_cast<int>(n);
      }
    };
    integer("cells", d.cells, 1, 1024);
    integer("levels", d.levels, 0, 12);
    integer("order", d.order, 1, 3);
    ls.shape = std::move(d);
    r.finish();
  } else {
    at.fail(std::string("unknown level-set kind (expected one of: ") + kKinds + ")");
  }
  if (blended && blend == 0.0)
    w.key("blend").fail("\"blend\" goes with \"union\", \"intersection\" or \"difference\", not \"" + kind + "\"");
  return ls;
}

}  // namespace meshmorph::detail

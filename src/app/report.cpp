// SPDX-License-Identifier: MIT
#include "meshmorph/app/report.h"

#include <sys/resource.h>

#include <cmath>
#include <fstream>

#include "app/detail/json_reader.h"
#include "meshmorph/error.h"
#include "meshmorph/io/atomic_file.h"

#ifndef MESHMORPH_VERSION
#define MESHMORPH_VERSION "unknown"
#endif

namespace meshmorph {

using nlohmann::json;
using nlohmann::ordered_json;
using detail::JsonWhere;

namespace {

ordered_json number_or_null(std::optional<double> v) {
  return v && std::isfinite(*v) ? ordered_json(*v) : ordered_json(nullptr);
}

ordered_json number_or_null(double v) { return number_or_null(std::optional<double>(v)); }

std::optional<double> optional_number(const json& j, const JsonWhere& w) {
  if (j.is_null()) return std::nullopt;
  return detail::read_number(j, w);
}

std::size_t read_count(const json& j, const JsonWhere& w) {
  const long long v = detail::read_integer(j, w);
  if (v < 0) w.fail("expected a count ≥ 0");
  return static_cast<std::size_t>(v);
}

}  // namespace

double peak_memory_mb() {
  rusage usage{};
  if (getrusage(RUSAGE_SELF, &usage) != 0) return 0;
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports KiB
}

const char* meshmorph_version() { return MESHMORPH_VERSION; }

ordered_json report_to_json(const Report& r) {
  ordered_json j;
  j["meshmorph_version"] = r.meshmorph_version;
  j["method"] = r.method;
  j["case"] = r.case_file ? ordered_json(*r.case_file) : ordered_json(nullptr);
  j["dim"] = r.dim;
  j["order"] = r.order;
  j["nodes"] = r.nodes;
  j["elements"] = r.elements;
  j["valid"] = r.valid;
  j["inverted_elements"] = r.inverted_elements;
  j["flipped_elements"] = r.flipped_elements;
  j["boundary_crossings"] = r.boundary_crossings;
  j["cell_volume"] = number_or_null(r.cell_volume);
  j["enclosed_volume"] = number_or_null(r.enclosed_volume);
  j["min_quality"] = number_or_null(r.min_quality);
  j["mean_quality"] = number_or_null(r.mean_quality);
  j["min_shape_quality"] = number_or_null(r.min_shape_quality);
  j["min_scaled_jacobian"] = number_or_null(r.min_scaled_jacobian);
  j["boundary_error_max"] = number_or_null(r.boundary_error_max);
  j["boundary_error_l2"] = number_or_null(r.boundary_error_l2);
  j["fit_error_max"] = number_or_null(r.fit_error_max);
  if (r.iterations) {
    j["iterations"] = {{"outer", r.iterations->outer}, {"nonlinear", r.iterations->nonlinear},
                       {"newton", r.iterations->newton}, {"linear", r.iterations->linear}};
  } else {
    j["iterations"] = nullptr;
  }
  j["seconds"] = number_or_null(r.seconds);
  j["peak_memory_mb"] = number_or_null(r.peak_memory_mb);
  j["converged"] = r.converged;
  j["message"] = r.message;
  j["history"] = ordered_json::array();
  for (const auto& row : r.history) {
    ordered_json o = ordered_json::object();
    for (const auto& [name, value] : row) o[name] = number_or_null(value);
    j["history"].push_back(std::move(o));
  }
  j["timings"] = nullptr;
  if (r.timings) {
    j["timings"] = ordered_json::object();
    for (int p = 0; p < k_phases; ++p) j["timings"][std::string(phase_key(Phase(p)))] = number_or_null((*r.timings)[Phase(p)]);
  }
  if (!r.cell_types.empty()) {
    j["cell_types"] = ordered_json::object();
    for (const CellTypeMinima& t : r.cell_types)
      j["cell_types"][t.type] = {{"elements", t.elements},
                                 {"min_quality", number_or_null(t.min_quality)},
                                 {"min_shape_quality", number_or_null(t.min_shape_quality)},
                                 {"min_scaled_jacobian", number_or_null(t.min_scaled_jacobian)}};
  }
  return j;
}

Report report_from_json(const ordered_json& oj, const std::string& file) {
  const json j(oj);
  detail::ObjectReader o(j, JsonWhere{file, ""});
  Report r;
  auto str = [&](const char* key) {
    const json& v = o.required(key);
    if (!v.is_string()) o.at(key).fail("expected a string, found " + detail::json_type_phrase(v));
    return v.get<std::string>();
  };
  auto num = [&](const char* key) { return optional_number(o.required(key), o.at(key)); };
  r.meshmorph_version = str("meshmorph_version");
  r.method = str("method");
  if (!o.required("case").is_null()) r.case_file = str("case");
  r.dim = static_cast<int>(detail::read_integer(o.required("dim"), o.at("dim")));
  r.order = static_cast<int>(detail::read_integer(o.required("order"), o.at("order")));
  r.nodes = read_count(o.required("nodes"), o.at("nodes"));
  r.elements = read_count(o.required("elements"), o.at("elements"));
  r.valid = detail::read_bool(o.required("valid"), o.at("valid"));
  r.inverted_elements = read_count(o.required("inverted_elements"), o.at("inverted_elements"));
  if (const json* v = o.optional("flipped_elements")) r.flipped_elements = read_count(*v, o.at("flipped_elements"));
  if (const json* v = o.optional("boundary_crossings")) r.boundary_crossings = read_count(*v, o.at("boundary_crossings"));
  if (const json* v = o.optional("cell_volume")) r.cell_volume = optional_number(*v, o.at("cell_volume"));
  if (const json* v = o.optional("enclosed_volume")) r.enclosed_volume = optional_number(*v, o.at("enclosed_volume"));
  r.min_quality = num("min_quality");
  r.mean_quality = num("mean_quality");
  r.min_shape_quality = num("min_shape_quality");
  r.min_scaled_jacobian = num("min_scaled_jacobian");
  r.boundary_error_max = num("boundary_error_max");
  r.boundary_error_l2 = num("boundary_error_l2");
  r.fit_error_max = num("fit_error_max");
  if (const json& it = o.required("iterations"); !it.is_null()) {
    detail::ObjectReader io(it, o.at("iterations"));
    IterationCounts c;
    c.outer = detail::read_integer(io.required("outer"), io.at("outer"));
    c.nonlinear = detail::read_integer(io.required("nonlinear"), io.at("nonlinear"));
    c.newton = detail::read_integer(io.required("newton"), io.at("newton"));
    c.linear = detail::read_integer(io.required("linear"), io.at("linear"));
    io.finish();
    r.iterations = c;
  }
  r.seconds = num("seconds").value_or(0.0);
  r.peak_memory_mb = num("peak_memory_mb");
  r.converged = detail::read_bool(o.required("converged"), o.at("converged"));
  r.message = str("message");
  (void)o.required("history");
  const ordered_json& history = oj.at("history");
  if (!history.is_array()) o.at("history").fail("expected a list");
  for (std::size_t i = 0; i < history.size(); ++i) {
    const JsonWhere w = o.at("history").index(i);
    if (!history[i].is_object()) w.fail("expected an object");
    HistoryRow row;
    for (const auto& item : history[i].items())
      row.emplace_back(item.key(), optional_number(json(item.value()), w.key(item.key())).value_or(NAN));
    r.history.push_back(std::move(row));
  }
  if (const json* t = o.optional("timings"); t && !t->is_null()) {
    detail::ObjectReader to(*t, o.at("timings"));
    Timings timings;
    for (int p = 0; p < k_phases; ++p) {
      const std::string key(phase_key(Phase(p)));
      timings.seconds[static_cast<std::size_t>(p)] = optional_number(to.required(key), to.at(key)).value_or(0.0);
    }
    to.finish();
    r.timings = timings;
  }
  if (const json* types = o.optional("cell_types")) {
    if (!types->is_object()) o.at("cell_types").fail("expected an object, found " + detail::json_type_phrase(*types));
    for (const auto& item : oj.at("cell_types").items()) {
      const json value(item.value());
      detail::ObjectReader to(value, o.at("cell_types").key(item.key()));
      CellTypeMinima t;
      t.type = item.key();
      t.elements = read_count(to.required("elements"), to.at("elements"));
      t.min_quality = optional_number(to.required("min_quality"), to.at("min_quality"));
      t.min_shape_quality = optional_number(to.required("min_shape_quality"), to.at("min_shape_quality"));
      t.min_scaled_jacobian = optional_number(to.required("min_scaled_jacobian"), to.at("min_scaled_jacobian"));
      to.finish();
      r.cell_types.push_back(std::move(t));
    }
  }
  o.finish();
  return r;
}

ordered_json report_json(Report report, const ordered_json& extra) {
  if (report.meshmorph_version.empty()) report.meshmorph_version = meshmorph_version();
  if (!report.peak_memory_mb) report.peak_memory_mb = peak_memory_mb();
  ordered_json j = report_to_json(report);
  for (const auto& item : extra.items()) j[item.key()] = item.value();
  return j;
}

void write_report(const std::filesystem::path& path, Report report, const ordered_json& extra) {
  const PhaseTimer timer(Phase::Io);
  const std::string text = report_json(std::move(report), extra).dump(2) + "\n";
  write_atomically(path, false, [&](std::ostream& out) { out << text; });
}

Report read_report(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot open the report");
  ordered_json j;
  try {
    j = ordered_json::parse(in);
  } catch (const json::parse_error& e) {
    throw InputError(path.string() + ": byte " + std::to_string(e.byte) + ": invalid JSON");
  }
  return report_from_json(j, path.string());
}

}  // namespace meshmorph

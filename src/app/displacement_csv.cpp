// SPDX-License-Identifier: MIT
#include <charconv>
#include <cmath>
#include <fstream>
#include <string>
#include <unordered_set>
#include <vector>

#include "meshmorph/app/case_file.h"
#include "meshmorph/error.h"
#include "meshmorph/io/input_files.h"
#include "meshmorph/timings.h"

namespace meshmorph {

namespace {

std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

std::vector<std::string_view> split_fields(std::string_view line) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const auto comma = line.find(',', start);
    fields.push_back(trim(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start)));
    if (comma == std::string_view::npos) return fields;
    start = comma + 1;
  }
}

bool parse_double(std::string_view s, double& v) {
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size();
}

bool parse_tag(std::string_view s, std::int64_t& v) {
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  return !s.empty() && ec == std::errc() && end == s.data() + s.size();
}

}  // namespace

DisplacementTable read_displacement_csv(const std::filesystem::path& path) {
  const PhaseTimer timer(Phase::Io);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path.string() + ": cannot open the displacement file");
  note_input_file(path);
  DisplacementTable t;
  t.file = path;
  std::vector<double> values;
  std::unordered_set<std::int64_t> seen;
  std::size_t columns = 0;
  bool first_content_line = true;
  std::string raw;
  const std::string name = path.string();
  auto fail = [&](int line, const std::string& what) -> void {
    throw InputError(name + ":" + std::to_string(line) + ": " + what);
  };
  for (int line = 1; std::getline(in, raw); ++line) {
    const std::string_view text = trim(raw);
    if (text.empty()) continue;
    const auto fields = split_fields(text);
    std::int64_t tag = 0;
    const bool numeric_start = parse_tag(fields[0], tag);
    if (first_content_line) {
      first_content_line = false;
      if (!numeric_start) {
        // A header: any first line whose first field is not a node number, e.g. "node,dx,dy,dz".
        continue;
      }
    }
    if (!numeric_start) fail(line, "expected a node number, found \"" + std::string(fields[0]) + "\"");
    if (tag < 1) fail(line, "node numbers start at 1, found " + std::to_string(tag));
    if (fields.size() != 3 && fields.size() != 4)
      fail(line, "expected node,dx,dy or node,dx,dy,dz, found " + std::to_string(fields.size()) + " fields");
    if (columns == 0) columns = fields.size();
    if (fields.size() != columns)
      fail(line, "expected " + std::to_string(columns) + " fields like the first row, found " +
                     std::to_string(fields.size()));
    if (!seen.insert(tag).second) fail(line, "node " + std::to_string(tag) + " is listed twice");
    for (std::size_t k = 1; k < fields.size(); ++k) {
      double v = 0;
      if (!parse_double(fields[k], v)) fail(line, "field " + std::to_string(k + 1) + ": expected a number, found \"" +
                                                      std::string(fields[k]) + "\"");
      if (!std::isfinite(v)) fail(line, "field " + std::to_string(k + 1) + ": expected a finite number");
      values.push_back(v);
    }
    t.node_tags.push_back(tag);
    t.line.push_back(line);
  }
  if (in.bad()) throw IoError(name + ": cannot read the displacement file");
  if (t.node_tags.empty()) throw InputError(name + ":1: no displacement rows (expected node,dx,dy[,dz] lines)");
  const auto rows = static_cast<Eigen::Index>(columns - 1);
  t.displacement = Eigen::Map<const Eigen::MatrixXd>(values.data(), rows, static_cast<Eigen::Index>(t.node_tags.size()));
  return t;
}

}  // namespace meshmorph

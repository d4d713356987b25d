// SPDX-License-Identifier: MIT
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "io/detail/cursor.h"
#include "io/detail/mesh_builder.h"
#include "io/detail/su2_types.h"
#include "meshmorph/error.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/io/su2.h"
#include "meshmorph/io/vtk_ordering.h"

namespace meshmorph {
namespace {

class Su2Reader {
 public:
  Su2Reader(const std::filesystem::path& path, std::string_view data) : c_(path, data) {}

  Mesh read() {
    if (!next_line()) c_.fail_at(0, "empty file");
    while (next_line()) {
      const std::string_view key = keyword();
      const std::size_t at = c_.token_start();
      if (key == "NDIME") {
        if (dim_ != 0) c_.fail_at(at, "second NDIME=");
        dim_ = c_.integer<int>("dimension");
        if (dim_ != 2 && dim_ != 3) c_.fail_at(c_.token_start(), "NDIME must be 2 or 3");
        end_of_line("NDIME=");
      } else if (key == "NZONE" || key == "IZONE") {
        const int n = c_.integer<int>(key == "NZONE" ? "number of zones" : "zone");
        if (n != 1)
          c_.fail_at(c_.token_start(), "multi-zone SU2 files (" + std::string(key) + "= " + std::to_string(n) +
                                           ") are not supported: write one zone a file");
        end_of_line(key);
      } else if (key == "NELEM") {
        need_dim(at, key);
        if (have_elements_) c_.fail_at(at, "second NELEM= section");
        have_elements_ = true;
        const std::size_t n = count("number of elements");
        for (std::size_t e = 0; e < n; ++e) {
          section_goes_on("NELEM", n, e, "elements");
          element(0, true);
        }
      } else if (key == "NPOIN") {
        points(at);
      } else if (key == "NMARK") {
        need_dim(at, key);
        if (have_markers_) c_.fail_at(at, "second NMARK= section");
        have_markers_ = true;
        const std::size_t n = count("number of markers");
        for (std::size_t m = 0; m < n; ++m) marker();
      } else if (key == "FFD_NBOX") {
        break;  // SU2_DEF's free-form deformation boxes follow the mesh
      } else if (key == "MARKER_TAG" || key == "MARKER_ELEMS") {
        c_.fail_at(at, std::string(key) + "= outside an NMARK= section");
      } else {
        c_.fail_at(at, "unknown SU2 keyword '" + detail::Cursor::shorten(key) + "='");
      }
    }
    if (dim_ == 0) c_.fail("no NDIME= line");
    if (!have_elements_) c_.fail("no NELEM= section");
    if (!have_points_) c_.fail("no NPOIN= section");
    const auto n_points = static_cast<std::int64_t>(builder_.tags.size());
    if (max_node_ >= n_points)
      c_.fail_at(max_node_at_, "node id " + std::to_string(max_node_) + " is outside 0.." +
                                   std::to_string(n_points - 1) + " (NPOIN= " + std::to_string(n_points) + ")");
    return builder_.finish(c_.where(c_.pos()));
  }

 private:
  // Skips blank space and '%' comment lines; true if a token follows.
  bool next_line() {
    while (c_.skip_space()) {
      if (c_.text()[c_.pos()] != '%') return true;
      c_.skip_line();
    }
    return false;
  }

  // "KEY=" (the value may follow the '=' without a space); leaves the cursor after the '='.
  std::string_view keyword() {
    const std::string_view t = c_.token("a keyword");
    const std::size_t eq = t.find('=');
    if (eq == std::string_view::npos || eq == 0)
      c_.fail_at(c_.token_start(), "expected a keyword such as NELEM=, got '" + detail::Cursor::shorten(t) + "'");
    c_.seek(c_.token_start() + eq + 1);
    return t.substr(0, eq);
  }

  // Skips blanks; true at a line break or the end of the file.
  bool at_end_of_line() {
    c_.skip_blank();
    return c_.pos() >= c_.text().size() || c_.text()[c_.pos()] == '\n';
  }

  // Fails where a section of `n` entries ends (the file, or a keyword) after `i`.
  void section_goes_on(std::string_view key, std::uint64_t n, std::uint64_t i, std::string_view what) {
    if (!next_line())
      c_.fail("unexpected end of file: " + std::string(key) + "= announces " + std::to_string(n) + " " +
              std::string(what) + ", the file holds " + std::to_string(i));
    const std::size_t end = c_.text().find_first_of(" \t\r\n", c_.pos());
    if (c_.text().substr(c_.pos(), end - c_.pos()).find('=') != std::string_view::npos)
      c_.fail(std::string(key) + "= announces " + std::to_string(n) + " " + std::string(what) + ", the section holds " +
              std::to_string(i));
  }

  // Only blank space may follow on the line.
  void end_of_line(std::string_view what) {
    if (!at_end_of_line())
      c_.fail("unexpected '" + detail::Cursor::shorten(c_.token("")) + "' after " + std::string(what));
  }

  void need_dim(std::size_t at, std::string_view key) {
    if (dim_ == 0) c_.fail_at(at, std::string(key) + "= before NDIME=");
  }

  std::size_t count(std::string_view what) {
    const auto n = c_.integer<std::uint64_t>(what);
    if (n > c_.remaining() / 2 + 1)
      c_.fail_at(c_.token_start(), "count " + std::to_string(n) + " is larger than the file can hold");
    end_of_line(what);
    return static_cast<std::size_t>(n);
  }

  // One element line: cells (NELEM, with an optional index) or a marker's facets.
  void element(std::int32_t marker, bool cell) {
    const int id = c_.integer<int>("element type");
    const detail::Su2Type* t = detail::su2_type(id);
    const int want = cell ? dim_ : dim_ - 1;
    if (t == nullptr || topological_dim(t->type) != want)
      c_.fail_at(c_.token_start(), "element type " + std::to_string(id) + " is not a " +
                                       (cell ? "cell of a " : "marker facet of a ") + std::to_string(dim_) +
                                       "D SU2 mesh (expected " + detail::su2_types_of_dim(want) + ")");
    const int k = n_corners_of(t->type);
    std::int32_t file_nodes[8];
    for (int j = 0; j < k; ++j) {
      if (at_end_of_line())
        c_.fail("element type " + std::to_string(id) + " has " + std::to_string(k) + " nodes, the line holds " +
                std::to_string(j));
      const auto v = c_.integer<std::int64_t>("node id");
      if (v < 0 || v > INT32_MAX)
        c_.fail_at(c_.token_start(), "node id " + std::to_string(v) + " is negative or too large");
      if (v > max_node_) max_node_ = v, max_node_at_ = c_.token_start();
      file_nodes[j] = static_cast<std::int32_t>(v);
      if (detail::repeated_node(file_nodes, j + 1) >= 0)
        c_.fail_at(c_.token_start(), "element lists node " + std::to_string(v) + " twice (a degenerate element)");
    }
    if (cell && !at_end_of_line()) c_.integer<std::int64_t>("element index");
    end_of_line("the element's nodes");
    CellBlock& b = builder_.block(t->type, 1);
    const std::vector<int>& perm = vtk_cell_permutation(id, t->type, 1);
    std::int32_t nodes[8];
    for (int j = 0; j < k; ++j) nodes[perm[static_cast<std::size_t>(j)]] = file_nodes[j];
    b.push_back(nodes, marker, 0);
  }

  void points(std::size_t at) {
    need_dim(at, "NPOIN");
    if (have_points_) c_.fail_at(at, "second NPOIN= section");
    have_points_ = true;
    const auto n = c_.integer<std::uint64_t>("number of points");
    if (n > c_.remaining() / 4 + 1)
      c_.fail_at(c_.token_start(), "count " + std::to_string(n) + " is larger than the file can hold");
    // A partition's count of its own points may follow.
    if (!at_end_of_line()) c_.integer<std::uint64_t>("number of domain points");
    end_of_line("NPOIN=");
    builder_.tags.reserve(n);
    builder_.xyz.reserve(3 * n);
    for (std::uint64_t i = 0; i < n; ++i) {
      section_goes_on("NPOIN", n, i, "points");
      double x[3] = {0, 0, 0};
      for (int k = 0; k < dim_; ++k) {
        if (at_end_of_line())
          c_.fail("point " + std::to_string(i) + " has " + std::to_string(k) +
                  " coordinates, NDIME= " + std::to_string(dim_));
        x[k] = c_.real("coordinate");
      }
      if (!at_end_of_line()) c_.integer<std::int64_t>("point index");
      end_of_line("the point's coordinates");
      builder_.tags.push_back(static_cast<std::int64_t>(i) + 1);
      builder_.xyz.insert(builder_.xyz.end(), {x[0], x[1], x[2]});
    }
  }

  void marker() {
    if (!next_line() || !c_.text().substr(c_.pos()).starts_with("MARKER_TAG=")) c_.fail("expected MARKER_TAG=");
    keyword();
    c_.skip_blank();
    const std::size_t start = c_.pos();
    c_.skip_line();
    std::string_view name = c_.text().substr(start, c_.pos() - start);
    while (!name.empty() && detail::Cursor::is_space(name.back())) name.remove_suffix(1);
    if (name.empty()) c_.fail_at(start, "MARKER_TAG= without a name");
    if (const auto bad = group_name_problem(name)) c_.fail_at(start, "marker name " + *bad);
    auto [it, added] = tags_.emplace(std::string(name), static_cast<std::int32_t>(tags_.size()) + 1);
    if (added) builder_.named_groups.push_back(PhysicalGroup{dim_ - 1, it->second, it->first});
    if (!next_line() || !c_.text().substr(c_.pos()).starts_with("MARKER_ELEMS="))
      c_.fail("expected MARKER_ELEMS= after MARKER_TAG=");
    keyword();
    const std::size_t n = count("number of marker elements");
    for (std::size_t e = 0; e < n; ++e) {
      section_goes_on("MARKER_ELEMS", n, e, "elements");
      element(it->second, false);
    }
  }

  detail::Cursor c_;
  detail::MeshBuilder builder_;
  std::map<std::string, std::int32_t, std::less<>> tags_;
  int dim_ = 0;
  bool have_elements_ = false, have_points_ = false, have_markers_ = false;
  std::int64_t max_node_ = -1;
  std::size_t max_node_at_ = 0;
};

}  // namespace

Mesh read_su2(const std::filesystem::path& path) { return parse_su2(detail::read_file(path), path); }

Mesh parse_su2(std::string_view data, const std::filesystem::path& path) { return Su2Reader(path, data).read(); }

}  // namespace meshmorph

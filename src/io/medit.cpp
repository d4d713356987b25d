// SPDX-License-Identifier: MIT
#include "meshmorph/io/medit.h"

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include "io/detail/cursor.h"
#include "io/detail/linear_only.h"
#include "io/detail/mesh_builder.h"
#include "io/detail/out_buffer.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

struct Keyword {
  std::string_view name;
  ElementType type;
};

constexpr Keyword k_elements[] = {
    {"Edges", ElementType::Line},          {"Triangles", ElementType::Triangle},
    {"Quadrilaterals", ElementType::Quadrilateral}, {"Tetrahedra", ElementType::Tetrahedron},
    {"Hexahedra", ElementType::Hexahedron}, {"Hexaedra", ElementType::Hexahedron},
    {"Prisms", ElementType::Prism},         {"Pyramids", ElementType::Pyramid},
};

constexpr std::string_view k_flag_lists[] = {"Corners", "Ridges", "RequiredVertices", "RequiredEdges",
                                             "RequiredTriangles", "RequiredQuadrilaterals"};

// Skips '#' comments and blank space; true if a token follows.
bool next(detail::Cursor& c) {
  while (c.skip_space()) {
    if (c.text()[c.pos()] != '#') return true;
    c.skip_line();
  }
  return false;
}

}  // namespace

Mesh read_medit(const std::filesystem::path& path) { return parse_medit(detail::read_file(path), path); }

Mesh parse_medit(std::string_view data, const std::filesystem::path& path) {
  detail::Cursor c(path, data);
  if (!next(c)) c.fail_at(0, "empty file");
  detail::MeshBuilder builder;
  int dim = 0;
  bool have_vertices = false;
  while (next(c)) {
    const std::string_view key = c.token("a keyword");
    const std::size_t at = c.token_start();
    if (key == "End") break;
    if (key == "MeshVersionFormatted") {
      const int v = c.integer<int>("version");
      if (v < 1 || v > 4) c.fail_at(c.token_start(), "unsupported MeshVersionFormatted " + std::to_string(v));
    } else if (key == "Dimension") {
      dim = c.integer<int>("dimension");
      if (dim != 2 && dim != 3) c.fail_at(c.token_start(), "Dimension must be 2 or 3");
    } else if (key == "Vertices") {
      if (dim == 0) c.fail_at(at, "Vertices before Dimension");
      if (have_vertices) c.fail_at(at, "second Vertices section");
      const auto n = c.integer<std::uint64_t>("number of vertices");
      if (n > c.remaining() / 4 + 1) c.fail_at(c.token_start(), "vertex count larger than the file can hold");
      builder.tags.reserve(n);
      builder.xyz.reserve(3 * n);
      for (std::uint64_t i = 0; i < n; ++i) {
        double x[3] = {0, 0, 0};
        for (int k = 0; k < dim; ++k) x[k] = c.real("coordinate");
        if (dim == 3 && x[2] != 0.0 && builder.first_nonzero_z.empty()) builder.first_nonzero_z = c.where(c.token_start());
        c.integer<std::int64_t>("vertex reference");
        builder.tags.push_back(static_cast<std::int64_t>(i) + 1);
        builder.xyz.insert(builder.xyz.end(), {x[0], x[1], x[2]});
      }
      have_vertices = true;
    } else if (const auto* kw = std::find_if(std::begin(k_elements), std::end(k_elements),
                                             [&](const Keyword& k) { return k.name == key; });
               kw != std::end(k_elements)) {
      if (!have_vertices) c.fail_at(at, std::string(key) + " before Vertices");
      const auto n = c.integer<std::uint64_t>("number of elements");
      const int k = n_corners_of(kw->type);
      if (n > c.remaining() / (2 * static_cast<std::size_t>(k + 1)) + 1)
        c.fail_at(c.token_start(), "element count larger than the file can hold");
      CellBlock& block = builder.block(kw->type, 1);
      const auto n_vertices = static_cast<std::int64_t>(builder.tags.size());
      for (std::uint64_t e = 0; e < n; ++e) {
        for (int j = 0; j < k; ++j) {
          const auto v = c.integer<std::int64_t>("vertex index");
          if (v < 1 || v > n_vertices)
            c.fail_at(c.token_start(), "vertex index " + std::to_string(v) + " is outside 1.." + std::to_string(n_vertices));
          block.nodes.push_back(static_cast<std::int32_t>(v - 1));
          if (detail::repeated_node(block.nodes.data() + block.nodes.size() - 1 - j, j + 1) >= 0)
            c.fail_at(c.token_start(), "element lists vertex " + std::to_string(v) + " twice (a degenerate element)");
        }
        block.physical.push_back(c.integer<std::int32_t>("element reference"));
        block.entity.push_back(0);
      }
    } else if (std::find(std::begin(k_flag_lists), std::end(k_flag_lists), key) != std::end(k_flag_lists)) {
      const auto n = c.integer<std::uint64_t>("number of entries");
      if (n > c.remaining() / 2 + 1) c.fail_at(c.token_start(), "count larger than the file can hold");
      for (std::uint64_t i = 0; i < n; ++i) c.integer<std::int64_t>("index");
    } else if (key.find("P2") != std::string_view::npos || key.find("Q2") != std::string_view::npos ||
               key.find("P3") != std::string_view::npos || key.find("Q3") != std::string_view::npos) {
      c.fail_at(at, "curved Medit elements (" + detail::Cursor::shorten(key) + ") are not supported");
    } else {
      c.fail_at(at, "unknown or unsupported Medit keyword '" + detail::Cursor::shorten(key) + "'");
    }
  }
  if (!have_vertices) c.fail("no Vertices section");
  return builder.finish(c.where(c.pos()));
}

void write_medit(std::ostream& out, const Mesh& mesh) {
  detail::require_linear(mesh, "Medit .mesh");
  std::vector<std::int32_t> vertex_ref(mesh.n_nodes(), 0);
  for (const CellBlock& b : mesh.facets)
    if (b.type == ElementType::Point)
      for (std::size_t c = 0; c < b.n_cells(); ++c) vertex_ref[static_cast<std::size_t>(b.cell(c)[0])] = c < b.physical.size() ? b.physical[c] : 0;
  detail::OutBuffer o(out);
  o << "MeshVersionFormatted 2\n\nDimension " << mesh.dim << "\n\nVertices\n" << mesh.n_nodes() << '\n';
  for (std::size_t j = 0; j < mesh.n_nodes(); ++j) {
    for (int k = 0; k < mesh.dim; ++k) o << mesh.x(k, static_cast<Eigen::Index>(j)) << ' ';
    o << vertex_ref[j] << '\n';
  }
  for (const Keyword& kw : k_elements) {
    if (kw.name == "Hexaedra") continue;
    std::size_t n = 0;
    for (const auto* list : {&mesh.facets, &mesh.cells})
      for (const CellBlock& b : *list) n += b.type == kw.type ? b.n_cells() : 0;
    if (n == 0) continue;
    o << '\n' << kw.name << '\n' << n << '\n';
    for (const auto* list : {&mesh.facets, &mesh.cells})
      for (const CellBlock& b : *list) {
        if (b.type != kw.type) continue;
        const int k = b.n_nodes_per_cell();
        for (std::size_t c = 0; c < b.n_cells(); ++c) {
          for (int j = 0; j < k; ++j) o << b.cell(c)[j] + 1 << ' ';
          o << (c < b.physical.size() ? b.physical[c] : 0) << '\n';
        }
      }
  }
  o << "\nEnd\n";
  o.flush();
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/io/vtu.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <functional>
#include <optional>
#include <set>
#include <string>
#include <string_view>

#include <pugixml.hpp>

#include "io/detail/cursor.h"
#include "io/detail/mesh_builder.h"
#include "io/detail/vtu_arrays.h"
#include "meshmorph/error.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/io/vtk_ordering.h"

namespace meshmorph {
namespace {

constexpr std::int64_t k_vtk_lagrange_hexahedron = 72;

using detail::at_most;
using detail::exactly;
using detail::read_array;
using detail::VtuFile;

pugi::xml_node named_array(const pugi::xml_node& parent, std::string_view name) {
  for (pugi::xml_node a : parent.children("DataArray"))
    if (name == a.attribute("Name").as_string()) return a;
  return {};
}

// Integer tags per cell; float arrays are accepted when every value is an integer.
std::vector<std::int64_t> read_tags(const VtuFile& f, const pugi::xml_node& node, std::size_t n) {
  if (!std::string_view(node.attribute("type").as_string()).starts_with("Float"))
    return read_array<std::int64_t>(f, node, exactly(n));
  const std::vector<double> v = read_array<double>(f, node, exactly(n));
  std::vector<std::int64_t> tags(n);
  for (std::size_t i = 0; i < n; ++i) {
    if (v[i] != std::floor(v[i]) || std::abs(v[i]) > 2e9)
      f.fail(node, "cell array '" + std::string(node.attribute("Name").as_string()) + "' holds a non-integer tag");
    tags[i] = static_cast<std::int64_t>(v[i]);
  }
  return tags;
}

struct VtkCell {
  ElementType type;
  int order;         // 0: derive from the point count
  int n_listed = 0;  // an incomplete (serendipity) cell's point count, read as the complete cell
};

std::optional<VtkCell> vtk_cell(int code) {
  switch (code) {
    case 1: return VtkCell{ElementType::Point, 1};
    case 3: return VtkCell{ElementType::Line, 1};
    case 21: return VtkCell{ElementType::Line, 2};
    case 68: return VtkCell{ElementType::Line, 0};
    case 5: return VtkCell{ElementType::Triangle, 1};
    case 22: return VtkCell{ElementType::Triangle, 2};
    case 69: return VtkCell{ElementType::Triangle, 0};
    case 9: return VtkCell{ElementType::Quadrilateral, 1};
    case 28: return VtkCell{ElementType::Quadrilateral, 2};
    case 70: return VtkCell{ElementType::Quadrilateral, 0};
    case 10: return VtkCell{ElementType::Tetrahedron, 1};
    case 24: return VtkCell{ElementType::Tetrahedron, 2};
    case 71: return VtkCell{ElementType::Tetrahedron, 0};
    case 12: return VtkCell{ElementType::Hexahedron, 1};
    case 29: return VtkCell{ElementType::Hexahedron, 2};
    case 72: return VtkCell{ElementType::Hexahedron, 0};
    case 13: return VtkCell{ElementType::Prism, 1};
    case 73: return VtkCell{ElementType::Prism, 0};
    case 14: return VtkCell{ElementType::Pyramid, 1};
    case 74: return VtkCell{ElementType::Pyramid, 0};
    case 23: return VtkCell{ElementType::Quadrilateral, 2, 8};
    case 25: return VtkCell{ElementType::Hexahedron, 2, 20};
    case 26: return VtkCell{ElementType::Prism, 2, 15};
    case 27: return VtkCell{ElementType::Pyramid, 2, 13};
    default: return std::nullopt;
  }
}

bool is_numeric_type(std::string_view type) {
  for (const std::string_view t : {"Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64", "UInt64", "Float32", "Float64"})
    if (type == t) return true;
  return false;
}

// Scalar numeric PointData arrays (NumberOfComponents absent or 1) → node fields; vector and
// tensor arrays, unnamed ones and String or Bit arrays are not kept. Every piece must hold
// the same scalar arrays, so that each field has a value at every node.
void read_point_data(const VtuFile& f, const pugi::xml_node& piece, std::size_t n_points, bool first_piece,
                     detail::MeshBuilder& builder) {
  const pugi::xml_node point_data = piece.child("PointData");
  std::set<std::string, std::less<>> seen;
  for (const pugi::xml_node a : point_data.children("DataArray")) {
    const std::string name = a.attribute("Name").as_string();
    if (name.empty() || a.attribute("NumberOfComponents").as_int(1) != 1 || !is_numeric_type(a.attribute("type").as_string()))
      continue;
    if (!seen.insert(name).second) f.fail(a, "PointData holds two arrays named '" + name + "'");
    auto it = builder.node_fields.find(name);
    if (!first_piece && it == builder.node_fields.end())
      f.fail(a, "PointData array '" + name + "' is missing in the first Piece");
    const std::vector<double> values = read_array<double>(f, a, exactly(n_points), true);
    if (first_piece) it = builder.node_fields.emplace(name, std::vector<double>{}).first;
    it->second.insert(it->second.end(), values.begin(), values.end());
  }
  if (!first_piece)
    for (const auto& [name, values] : builder.node_fields)
      if (!seen.count(name)) f.fail(point_data ? point_data : piece, "Piece has no PointData array '" + name + "' (the first Piece has one)");
}

void read_piece(const VtuFile& f, const pugi::xml_node& piece, bool first_piece, detail::MeshBuilder& builder) {
  const long long n_points = piece.attribute("NumberOfPoints").as_llong(-1);
  const long long n_cells = piece.attribute("NumberOfCells").as_llong(-1);
  if (n_points < 0 || n_cells < 0) f.fail(piece, "Piece needs NumberOfPoints and NumberOfCells");
  if (static_cast<std::size_t>(n_points) > f.text.size() || static_cast<std::size_t>(n_cells) > f.text.size())
    f.fail(piece, "NumberOfPoints/NumberOfCells larger than the file can hold");
  const std::size_t np = static_cast<std::size_t>(n_points), nc = static_cast<std::size_t>(n_cells);
  const pugi::xml_node points = piece.child("Points").child("DataArray");
  if (!points) f.fail(piece, "Piece has no Points DataArray");
  if (points.attribute("NumberOfComponents").as_int(1) != 3) f.fail(points, "Points must have 3 components");
  const std::vector<double> xyz = read_array<double>(f, points, exactly(3 * np));
  const std::int64_t base = static_cast<std::int64_t>(builder.tags.size());
  for (std::size_t j = 0; j < np; ++j) {
    builder.tags.push_back(base + static_cast<std::int64_t>(j) + 1);
    if (xyz[3 * j + 2] != 0.0 && builder.first_nonzero_z.empty())
      builder.first_nonzero_z = detail::location(f.path, f.text, static_cast<std::size_t>(points.offset_debug()), false);
  }
  builder.xyz.insert(builder.xyz.end(), xyz.begin(), xyz.end());
  read_point_data(f, piece, np, first_piece, builder);

  const pugi::xml_node cells = piece.child("Cells");
  const pugi::xml_node conn_node = named_array(cells, "connectivity");
  const pugi::xml_node off_node = named_array(cells, "offsets");
  const pugi::xml_node type_node = named_array(cells, "types");
  if (!conn_node || !off_node || !type_node)
    f.fail(cells ? cells : piece, "Cells needs DataArrays 'connectivity', 'offsets' and 'types'");
  const auto offsets = read_array<std::int64_t>(f, off_node, exactly(nc));
  const auto types = read_array<std::int64_t>(f, type_node, exactly(nc));
  // A cell has at most the nodes of a hexahedron of order 4 (the highest order read).
  const auto max_cell_nodes = static_cast<std::size_t>(n_nodes_of(ElementType::Hexahedron, 4));
  const auto conn = read_array<std::int64_t>(f, conn_node, at_most(nc * max_cell_nodes));
  std::vector<std::int64_t> physical(nc, 0), entity(nc, 0);
  const pugi::xml_node cell_data = piece.child("CellData");
  for (const char* name : {"group", "material", "attribute", "gmsh:physical"})
    if (const pugi::xml_node a = named_array(cell_data, name)) {
      physical = read_tags(f, a, nc);
      break;
    }
  for (const char* name : {"entity", "gmsh:geometrical"})
    if (const pugi::xml_node a = named_array(cell_data, name)) {
      entity = read_tags(f, a, nc);
      break;
    }
  std::int64_t prev = 0;
  std::vector<std::int32_t> gmsh;
  const std::vector<int>* perm = nullptr;
  CellBlock* block = nullptr;  // valid until the next builder.block() call, which resets it
  ElementType last_type = ElementType::Point;
  int last_order = -1;
  std::int64_t last_code = -1;
  for (std::size_t i = 0; i < nc; ++i) {
    const std::int64_t end = offsets[i];
    if (end < prev || end > static_cast<std::int64_t>(conn.size()))
      f.fail(off_node, "offsets do not match the connectivity (cell " + std::to_string(i) + ")");
    const auto n = static_cast<int>(end - prev);
    const auto vc = vtk_cell(static_cast<int>(types[i]));
    if (!vc) f.fail(type_node, "unsupported VTK cell type " + std::to_string(types[i]) + " (cell " + std::to_string(i) + ")");
    int order = vc->order;
    if (order == 0)
      for (int p = 1; p <= 4 && order == 0; ++p)
        if (n_nodes_of(vc->type, p) == n) order = p;
    // VTK 9.1 has no Lagrange pyramid of order 2 (VTK_LAGRANGE_PYRAMID has no cell class there).
    const int highest = vc->type == ElementType::Pyramid ? 1 : vc->type == ElementType::Prism ? max_order_of(vc->type) : 4;
    if (vc->n_listed > 0 && n != vc->n_listed)
      f.fail(off_node, "cell " + std::to_string(i) + " of VTK type " + std::to_string(types[i]) + " has " +
                           std::to_string(n) + " points, not " + std::to_string(vc->n_listed));
    if (vc->n_listed == 0 && (order == 0 || order > highest || n_nodes_of(vc->type, order) != n))
      f.fail(off_node, "cell " + std::to_string(i) + " of VTK type " + std::to_string(types[i]) + " has " +
                           std::to_string(n) + " points, which is no complete Lagrange cell of order 1-" + std::to_string(highest));
    if (vc->type != last_type || order != last_order || types[i] != last_code) {  // the permutation cache takes a lock
      perm = &vtk_cell_permutation(static_cast<int>(types[i]), vc->type, order);
      last_code = types[i];
      block = &builder.block(vc->type, order);
      last_type = vc->type;
      last_order = order;
    }
    gmsh.assign(static_cast<std::size_t>(n_nodes_of(vc->type, order)), -1);  // promoted cells: −1 for the nodes they lack
    // VTK 8's Lagrange hexahedra hold edge 11's nodes where VTK 9 has edge 10's, and back.
    const int e = order - 1, swap_from = 8 + 10 * e;
    const bool v8 = f.hexahedra_v8 && types[i] == k_vtk_lagrange_hexahedron && e > 0;
    for (int k = 0; k < n; ++k) {
      const int from = !v8 || k < swap_from || k >= swap_from + 2 * e ? k : (k < swap_from + e ? k + e : k - e);
      const std::int64_t v = conn[static_cast<std::size_t>(prev + from)];
      if (v < 0 || v >= n_points) f.fail(conn_node, "connectivity index " + std::to_string(v) + " is out of range");
      gmsh[static_cast<std::size_t>((*perm)[static_cast<std::size_t>(k)])] = static_cast<std::int32_t>(base + v);
    }
    if (const int k = detail::repeated_node(gmsh.data(), n); k >= 0)
      f.fail(conn_node, "cell " + std::to_string(i) + " lists point " + std::to_string(gmsh[static_cast<std::size_t>(k)] - base) +
                            " twice (a degenerate cell)");
    block->nodes.insert(block->nodes.end(), gmsh.begin(), gmsh.end());
    block->physical.push_back(static_cast<std::int32_t>(physical[i]));
    block->entity.push_back(static_cast<std::int32_t>(entity[i]));
    prev = end;
  }
  if (prev != static_cast<std::int64_t>(conn.size()))
    f.fail(off_node, "the last offset " + std::to_string(prev) + " does not match the connectivity length " +
                         std::to_string(conn.size()));
}

}  // namespace

Mesh read_vtu(const std::filesystem::path& path) { return parse_vtu(detail::read_file(path), path); }

Mesh parse_vtu(std::string_view data, const std::filesystem::path& path) {
  VtuFile f;
  f.path = path;
  f.text = data;
  if (data.find_first_not_of(" \t\r\n") == std::string::npos) detail::throw_input_error(path, data, 0, false, "empty file");
  // Raw appended data is not XML: parse the text before it and locate the arrays by offset.
  std::string xml;  // parsed in place: one copy of the file
  const std::size_t app = data.find("<AppendedData");
  if (app != std::string::npos) {
    const std::size_t close = data.find('>', app);
    const std::size_t mark = close == std::string::npos ? close : data.find('_', close);
    const std::size_t end = data.rfind("</AppendedData>");
    if (mark == std::string::npos || end == std::string::npos || end < mark)
      detail::throw_input_error(path, data, app, false, "AppendedData without '_' marker or end tag");
    f.appended = mark + 1;
    f.appended_end = end;
    // Trailing whitespace before the end tag is not part of the last array.
    xml = std::string(data.substr(0, mark + 1)).append(data.substr(end));
  } else {
    xml = data;
  }
  pugi::xml_document doc;
  const pugi::xml_parse_result parsed = doc.load_buffer_inplace(xml.data(), xml.size(), pugi::parse_default, pugi::encoding_utf8);
  if (!parsed)
    detail::throw_input_error(path, data, static_cast<std::size_t>(std::max<std::ptrdiff_t>(0, parsed.offset)), false,
                              std::string("XML error: ") + parsed.description());
  const pugi::xml_node root = doc.child("VTKFile");
  if (!root) detail::throw_input_error(path, data, 0, false, "not a VTK XML file (no VTKFile element)");
  if (std::string_view(root.attribute("type").as_string()) != "UnstructuredGrid")
    f.fail(root, "VTKFile type must be UnstructuredGrid");
  if (std::string_view(root.attribute("byte_order").as_string("LittleEndian")) != "LittleEndian")
    f.fail(root, "big-endian VTK files are not supported");
  const std::string_view header = root.attribute("header_type").as_string("UInt32");
  if (header != "UInt32" && header != "UInt64") f.fail(root, "header_type must be UInt32 or UInt64");
  f.header64 = header == "UInt64";
  const std::string_view compressor = root.attribute("compressor").as_string();
  if (!compressor.empty() && compressor != "vtkZLibDataCompressor")
    f.fail(root, "unsupported compressor '" + std::string(compressor) + "' (zlib only)");
  f.compressed = !compressor.empty();
  {
    const std::string_view version = root.attribute("version").as_string("0.1");
    const auto dot = version.find('.');
    const int major = std::atoi(std::string(version.substr(0, dot)).c_str());
    const int minor = dot == std::string_view::npos ? 0 : std::atoi(std::string(version.substr(dot + 1)).c_str());
    f.hexahedra_v8 = major < 2 || (major == 2 && minor < 1);
  }
  if (const pugi::xml_node ad = root.child("AppendedData")) {
    const std::string_view enc = ad.attribute("encoding").as_string("raw");
    if (enc != "raw" && enc != "base64") f.fail(ad, "AppendedData encoding must be raw or base64");
    f.appended_base64 = enc == "base64";
    for (const pugi::xpath_node& n : root.select_nodes("//DataArray[@format='appended']"))
      f.appended_offsets.push_back(f.appended_offset(n.node()));
    std::sort(f.appended_offsets.begin(), f.appended_offsets.end());
  }
  const pugi::xml_node grid = root.child("UnstructuredGrid");
  if (!grid) f.fail(root, "no UnstructuredGrid element");
  detail::MeshBuilder builder;
  for (pugi::xml_node a : grid.child("FieldData").children("DataArray")) {
    const std::string_view type = a.attribute("type").as_string();
    if (!type.starts_with("Int") && !type.starts_with("UInt")) continue;  // TimeValue, strings, ...
    const auto v = read_array<std::int64_t>(f, a, detail::ValueCount{});  // any length
    if (v.size() != 2 || v[1] < 0 || v[1] > 3) continue;
    const std::string name = a.attribute("Name").as_string();
    if (const auto bad = group_name_problem(name)) f.fail(a, "group name " + *bad);
    builder.named_groups.push_back(PhysicalGroup{static_cast<int>(v[1]), static_cast<std::int32_t>(v[0]), name});
  }
  if (!grid.child("Piece")) f.fail(grid, "no Piece element");
  bool first_piece = true;
  for (const pugi::xml_node piece : grid.children("Piece")) {
    read_piece(f, piece, first_piece, builder);
    first_piece = false;
  }
  return builder.finish(detail::location(path, data, data.size(), false), path);
}

}  // namespace meshmorph

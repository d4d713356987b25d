// SPDX-License-Identifier: MIT
#include "meshmorph/io/vtu.h"

#include <cmath>
#include <limits>
#include <string_view>
#include <type_traits>

#include "io/detail/base64.h"
#include "io/detail/out_buffer.h"
#include "meshmorph/error.h"
#include "meshmorph/io/vtk_ordering.h"

namespace meshmorph {
namespace {

std::string xml_escape(std::string_view s) {
  std::string r;
  for (const char c : s) {
    switch (c) {
      case '&': r += "&amp;"; break;
      case '<': r += "&lt;"; break;
      case '>': r += "&gt;"; break;
      case '"': r += "&quot;"; break;
      case '\'': r += "&apos;"; break;
      default: r += c;
    }
  }
  return r;
}

template <class T>
constexpr std::string_view vtk_type_name() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  else if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  else if constexpr (std::is_same_v<T, std::int32_t>) return "Int32";
  else return "UInt8";
}

// One DataArray element with its values, ASCII or base64 (UInt64 byte count + data).
// NumberOfComponents is omitted for scalars (VTK's default is 1), as meshio writes them:
// meshio returns arrays that state it as n×1 instead of n.
template <class T>
void data_array(detail::OutBuffer& o, std::string_view name, int components, const std::vector<T>& values,
                bool binary, std::string_view indent) {
  o << indent << "<DataArray type=\"" << vtk_type_name<T>() << "\" Name=\"" << xml_escape(name) << '"';
  if (components != 1) o << " NumberOfComponents=\"" << components << '"';
  o << " format=\"" << (binary ? "binary" : "ascii") << "\">\n";
  if (binary) {
    std::string bytes(sizeof(std::uint64_t) + values.size() * sizeof(T), '\0');
    const std::uint64_t size = values.size() * sizeof(T);
    std::memcpy(bytes.data(), &size, sizeof size);
    if (!values.empty()) std::memcpy(bytes.data() + sizeof size, values.data(), size);
    std::string text;
    detail::base64_encode(bytes, text);
    o << text << '\n';
  } else {
    for (std::size_t i = 0; i < values.size(); ++i) {
      if constexpr (std::is_same_v<T, std::uint8_t>) o << static_cast<int>(values[i]);
      else o << values[i];
      o << ((i + 1) % static_cast<std::size_t>(components * (components == 1 ? 12 : 1)) == 0 ? '\n' : ' ');
    }
    if (!values.empty()) o << '\n';
  }
  o << indent << "</DataArray>\n";
}

// Linear cells get VTK's classic types (readable everywhere); higher orders the Lagrange types.
std::uint8_t cell_type_code(const CellBlock& b) {
  if (b.order > 1 && b.type != ElementType::Point) return static_cast<std::uint8_t>(vtk_cell_type(b.type));
  switch (b.type) {
    case ElementType::Point: return 1;
    case ElementType::Line: return 3;
    case ElementType::Triangle: return 5;
    case ElementType::Quadrilateral: return 9;
    case ElementType::Tetrahedron: return 10;
    case ElementType::Hexahedron: return 12;
    case ElementType::Prism: return 13;
    case ElementType::Pyramid: return 14;
  }
  return 0;
}

}  // namespace

void write_vtu(std::ostream& out, const Mesh& mesh, bool binary, const std::map<std::string, std::vector<double>>& cell_data,
               const std::map<std::string, Eigen::MatrixXd>& point_vectors) {
  for (const CellBlock& b : mesh.cells)
    if (b.type == ElementType::Pyramid && b.order > 1)
      throw InputError("VTU cannot hold pyramids of order " + std::to_string(b.order) +
                       ": VTK 9.1 has no cell class for VTK_LAGRANGE_PYRAMID (74); write .msh instead");
  const std::size_t n_cells = mesh.n_cells();
  for (const auto& [name, values] : cell_data)
    MESHMORPH_CHECK(values.size() == n_cells, "write_vtu: cell_data '" + name + "' has " + std::to_string(values.size()) +
                                                  " values for " + std::to_string(n_cells) + " cells");
  for (const auto& [name, values] : mesh.node_fields)
    MESHMORPH_CHECK(static_cast<std::size_t>(values.size()) == mesh.n_nodes(),
                    "write_vtu: node field '" + name + "' has " + std::to_string(values.size()) + " values for " +
                        std::to_string(mesh.n_nodes()) + " nodes");
  for (const auto& [name, values] : point_vectors)
    MESHMORPH_CHECK(values.rows() == mesh.dim && static_cast<std::size_t>(values.cols()) == mesh.n_nodes(),
                    "write_vtu: point vectors '" + name + "' are not dim × n_nodes");
  std::vector<double> points(3 * mesh.n_nodes(), 0.0);
  for (std::size_t j = 0; j < mesh.n_nodes(); ++j)
    for (int k = 0; k < mesh.dim; ++k) points[3 * j + static_cast<std::size_t>(k)] = mesh.x(k, static_cast<Eigen::Index>(j));
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::uint8_t> types;
  std::vector<std::int32_t> group, entity;
  bool lagrange_hexahedra = false;
  for (const auto* list : {&mesh.cells, &mesh.facets})
    for (const CellBlock& b : *list) {
      const std::uint8_t code = cell_type_code(b);
      const std::vector<int>& perm = vtk_cell_permutation(code, b.type, b.type == ElementType::Point ? 1 : b.order);
      const std::size_t n = b.n_cells();
      lagrange_hexahedra |= code == 72 && n > 0;
      for (std::size_t c = 0; c < n; ++c) {
        const std::int32_t* nodes = b.cell(c);
        for (const int g : perm) connectivity.push_back(nodes[g]);
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
        types.push_back(code);
        group.push_back(c < b.physical.size() ? b.physical[c] : 0);
        entity.push_back(c < b.entity.size() ? b.entity[c] : 0);
      }
    }
  detail::OutBuffer o(out);
  // Version 2.2 marks the VTK ≥ 9.0 numbering of Lagrange hexahedra; VTK itself writes it only
  // when such cells are present, and older readers (meshio 5) reject it, so do the same.
  o << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"" << (lagrange_hexahedra ? "2.2" : "1.0")
    << "\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <UnstructuredGrid>\n";
  bool any_named = false;
  for (const PhysicalGroup& g : mesh.groups) any_named |= !g.name.empty();
  if (any_named) {
    o << "    <FieldData>\n";
    for (const PhysicalGroup& g : mesh.groups)
      if (!g.name.empty())
        o << "      <DataArray type=\"Int32\" Name=\"" << xml_escape(g.name)
          << "\" NumberOfTuples=\"1\" NumberOfComponents=\"2\" format=\"ascii\">" << g.tag << ' ' << g.dim
          << "</DataArray>\n";
    o << "    </FieldData>\n";
  }
  o << "    <Piece NumberOfPoints=\"" << mesh.n_nodes() << "\" NumberOfCells=\"" << types.size() << "\">\n";
  o << "      <Points>\n";
  data_array(o, "Points", 3, points, binary, "        ");
  o << "      </Points>\n      <Cells>\n";
  data_array(o, "connectivity", 1, connectivity, binary, "        ");
  data_array(o, "offsets", 1, offsets, binary, "        ");
  data_array(o, "types", 1, types, binary, "        ");
  o << "      </Cells>\n";
  if (!mesh.node_fields.empty() || !point_vectors.empty()) {
    o << "      <PointData>\n";
    for (const auto& [name, values] : mesh.node_fields)
      data_array(o, name, 1, std::vector<double>(values.data(), values.data() + values.size()), binary, "        ");
    for (const auto& [name, values] : point_vectors) {
      std::vector<double> v(3 * mesh.n_nodes(), 0.0);
      for (std::size_t j = 0; j < mesh.n_nodes(); ++j)
        for (int k = 0; k < mesh.dim; ++k) v[3 * j + static_cast<std::size_t>(k)] = values(k, static_cast<Eigen::Index>(j));
      data_array(o, name, 3, v, binary, "        ");
    }
    o << "      </PointData>\n";
  }
  o << "      <CellData Scalars=\"group\">\n";
  data_array(o, "group", 1, group, binary, "        ");
  data_array(o, "entity", 1, entity, binary, "        ");
  for (const auto& [name, values] : cell_data) {
    std::vector<double> all(values);
    all.resize(types.size(), std::numeric_limits<double>::quiet_NaN());
    data_array(o, name, 1, all, binary, "        ");
  }
  o << "      </CellData>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  o.flush();
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include <string>
#include <vector>

#include "io/detail/linear_only.h"
#include "io/detail/out_buffer.h"
#include "io/detail/su2_types.h"
#include "meshmorph/error.h"
#include "meshmorph/io/su2.h"
#include "meshmorph/io/vtk_ordering.h"

namespace meshmorph {
namespace {

// One element line in VTK's order: type id, node ids.
void put_element(detail::OutBuffer& o, const CellBlock& b, std::size_t c) {
  const int id = detail::su2_id(b.type);
  const std::vector<int>& perm = vtk_cell_permutation(id, b.type, 1);
  o << id;
  for (const int p : perm) o << ' ' << b.cell(c)[p];
}

}  // namespace

void write_su2(std::ostream& out, const Mesh& mesh) {
  detail::require_linear(mesh, "SU2 .su2");
  struct Marker {
    std::string name;
    std::int32_t tag;
    std::size_t n = 0;
  };
  std::vector<Marker> markers;
  for (const PhysicalGroup& g : mesh.groups) {
    if (g.dim != mesh.dim - 1) continue;
    Marker m{g.name.empty() ? "group_" + std::to_string(g.tag) : g.name, g.tag};
    for (const CellBlock& b : mesh.facets)
      if (topological_dim(b.type) == g.dim)
        for (const std::int32_t t : b.physical) m.n += t == g.tag ? 1 : 0;
    if (m.n == 0) continue;
    if (m.name.find_first_of(" \t%") != std::string::npos)
      throw InputError("SU2's MARKER_TAG holds no white space or '%': group " + std::to_string(g.tag) + " is named \"" +
                       m.name + "\"");
    markers.push_back(std::move(m));
  }
  detail::OutBuffer o(out);
  o << "NDIME= " << mesh.dim << "\nNELEM= " << mesh.n_cells() << '\n';
  std::size_t index = 0;
  for (const CellBlock& b : mesh.cells)
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      put_element(o, b, c);
      o << ' ' << index++ << '\n';
    }
  o << "NPOIN= " << mesh.n_nodes() << '\n';
  for (std::size_t j = 0; j < mesh.n_nodes(); ++j) {
    for (int k = 0; k < mesh.dim; ++k) o << mesh.x(k, static_cast<Eigen::Index>(j)) << ' ';
    o << j << '\n';
  }
  o << "NMARK= " << markers.size() << '\n';
  for (const Marker& m : markers) {
    o << "MARKER_TAG= " << m.name << "\nMARKER_ELEMS= " << m.n << '\n';
    for (const CellBlock& b : mesh.facets) {
      if (topological_dim(b.type) != mesh.dim - 1) continue;
      for (std::size_t c = 0; c < b.n_cells(); ++c)
        if (b.physical[c] == m.tag) {
          put_element(o, b, c);
          o << '\n';
        }
    }
  }
  o.flush();
}

}  // namespace meshmorph

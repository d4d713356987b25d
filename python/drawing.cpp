// SPDX-License-Identifier: MIT
// What meshmorph.plot draws, from the library's reference elements and topology: the outline
// of each 2D cell through its edge nodes, and the boundary faces of a 3D mesh.
#include "drawing.h"

#include <algorithm>
#include <array>
#include <vector>

#include <pybind11/numpy.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {
namespace {

// Per block of a 2D mesh, (n_cells, k) node loops: each edge's first corner, then the nodes
// inside it (curved cells are drawn through them), counterclockwise in the reference cell.
py::list cell_outlines(const Mesh& mesh) {
  if (mesh.dim != 2) throw InputError("plot: cell outlines are drawn for 2D meshes");
  py::list blocks;
  for (const CellBlock& b : mesh.cells) {
    const ReferenceElement& ref = reference_element(b.type, b.order);
    std::vector<int> loop;
    for (const std::vector<int>& edge : ref.facet_nodes) {
      loop.push_back(edge[0]);
      loop.insert(loop.end(), edge.begin() + 2, edge.end());
    }
    py::array_t<std::int32_t> a({static_cast<py::ssize_t>(b.n_cells()), static_cast<py::ssize_t>(loop.size())});
    std::int32_t* out = a.mutable_data();
    for (std::size_t c = 0; c < b.n_cells(); ++c)
      for (const int k : loop) *out++ = b.cell(c)[k];
    blocks.append(a);
  }
  return blocks;
}

// The boundary faces of a 3D mesh: (cells (F,), corners (F, 4), −1 after a triangle's three).
py::tuple boundary_faces(const Mesh& mesh) {
  if (mesh.dim != 3) throw InputError("plot: boundary faces are drawn for 3D meshes");
  const Topology topo = build_topology(mesh, TopologyParts::Facets);
  const auto n = static_cast<py::ssize_t>(topo.boundary_facets.size());
  py::array_t<std::int32_t> cells(n), corners({n, py::ssize_t{4}});
  std::int32_t* c = cells.mutable_data();
  std::int32_t* out = corners.mutable_data();
  for (const std::int32_t f : topo.boundary_facets) {
    const CellFacet& cf = topo.facets[static_cast<std::size_t>(f)][0];
    const auto [block, index] = topo.locate(cf.cell);
    const CellBlock& b = mesh.cells[block];
    const std::vector<int>& local = corner_facets(b.type)[static_cast<std::size_t>(cf.local)];
    *c++ = cf.cell;
    for (std::size_t k = 0; k < 4; ++k) *out++ = k < local.size() ? b.cell(index)[local[k]] : -1;
  }
  return py::make_tuple(cells, corners);
}

}  // namespace

void add_drawing(py::module_& m) {
  m.def("_cell_outlines", &cell_outlines, py::arg("mesh"),
        "Per cell block of a 2D mesh, (n_cells, k) node loops around each cell through its edge nodes.");
  m.def("_boundary_faces", &boundary_faces, py::arg("mesh"),
        "(cells, corners) of the boundary faces of a 3D mesh: the cell of each face (blocks concatenated) "
        "and its corner nodes, -1 after a triangle's three.");
}

}  // namespace meshmorph

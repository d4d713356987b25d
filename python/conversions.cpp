// SPDX-License-Identifier: MIT
// The node orders and cell families the package's meshio conversion (meshmorph/_meshio.py)
// takes from the library, so that Python holds no permutation table of its own.
#include "conversions.h"

#include <algorithm>
#include <map>
#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include "io/detail/promote.h"
#include "meshmorph/error.h"
#include "meshmorph/io/vtk_ordering.h"

namespace meshmorph {
namespace {

ElementType family_of(const std::string& name) {
  for (ElementType t : {ElementType::Point, ElementType::Line, ElementType::Triangle, ElementType::Quadrilateral,
                        ElementType::Tetrahedron, ElementType::Hexahedron, ElementType::Prism, ElementType::Pyramid})
    if (name_of(t) == name) return t;
  throw InputError("no cell family \"" + name + "\"");
}

// The order of a complete cell of `n` nodes of `type` (0: none; a Point has order 1).
int order_of(ElementType type, int n) {
  if (type == ElementType::Point) return n == 1 ? 1 : 0;
  for (int p = 1; p <= max_order_of(type); ++p)
    if (n_nodes_of(type, p) == n) return p;
  return 0;
}

// Cells whose nodes past the listed ones are −1, completed by promote_incomplete: the new
// points (n × 3) and the blocks' node arrays.
py::tuple complete_cells(const py::array_t<double, py::array::c_style | py::array::forcecast>& points, const py::list& blocks) {
  std::vector<double> xyz(points.data(), points.data() + points.size());
  std::vector<std::int64_t> tags(xyz.size() / 3);
  for (std::size_t i = 0; i < tags.size(); ++i) tags[i] = static_cast<std::int64_t>(i) + 1;
  std::vector<CellBlock> cells;
  for (const py::handle& item : blocks) {
    const auto t = item.cast<py::tuple>();
    CellBlock b;
    b.type = family_of(t[0].cast<std::string>());
    b.order = t[1].cast<int>();
    const auto nodes = t[2].cast<py::array_t<std::int32_t, py::array::c_style | py::array::forcecast>>();
    b.nodes.assign(nodes.data(), nodes.data() + nodes.size());
    b.physical.assign(b.n_cells(), 0);
    b.entity.assign(b.n_cells(), 0);
    cells.push_back(std::move(b));
  }
  std::map<std::string, std::vector<double>, std::less<>> fields;
  detail::promote_incomplete(cells, xyz, tags, fields);
  py::array_t<double> out({static_cast<py::ssize_t>(xyz.size() / 3), py::ssize_t{3}});
  std::copy(xyz.begin(), xyz.end(), out.mutable_data());
  py::list nodes;
  for (const CellBlock& b : cells) {
    py::array_t<std::int32_t> a({static_cast<py::ssize_t>(b.n_cells()), static_cast<py::ssize_t>(b.n_nodes_per_cell())});
    std::copy(b.nodes.begin(), b.nodes.end(), a.mutable_data());
    nodes.append(a);
  }
  return py::make_tuple(out, nodes);
}

}  // namespace

void add_conversions(py::module_& m) {
  m.def("_cell_order", [](const std::string& family, int n) {
    const ElementType t = family_of(family);
    if (const int p = order_of(t, n)) return py::make_tuple(p, false);
    if (n > 0 && n == detail::incomplete_nodes_of(t)) return py::make_tuple(2, true);
    return py::make_tuple(0, false);
  }, py::arg("family"), py::arg("n_nodes"),
        "(order, incomplete) of a cell of `n_nodes` nodes of `family`: (0, False) for none; the serendipity "
        "cells (8-node quadrilateral, 20-node hexahedron, 15-node prism, 13-node pyramid) are (2, True).");
  m.def("_cell_nodes", [](const std::string& family, int order) { return n_nodes_of(family_of(family), order); },
        py::arg("family"), py::arg("order"), "Nodes of the complete cell of `family` and `order`.");
  m.def("_vtk_permutation", [](int vtk_type, const std::string& family, int order) {
    return vtk_cell_permutation(vtk_type, family_of(family), order);
  }, py::arg("vtk_type"), py::arg("family"), py::arg("order"),
        "perm with vtk_nodes[i] = gmsh_nodes[perm[i]] for a cell of VTK type `vtk_type` (io/vtk_ordering.h).");
  m.def("_complete_cells", &complete_cells, py::arg("points"), py::arg("blocks"),
        "(points, node arrays): the serendipity cells of `blocks` ((family, 2, nodes in Gmsh's order with -1 "
        "for the nodes they lack)) completed, as the readers complete them (io/detail/promote.h).");
}

}  // namespace meshmorph

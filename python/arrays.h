// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

namespace py = pybind11;

/// A float64 array as the module takes one: C-contiguous, other dtypes converted.
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

/// `a`, no longer writeable.
template <class T>
py::array_t<T> read_only(py::array_t<T> a) {
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

/// A read-only n × d view of the d × n matrix `x`, which `owner` holds (kept alive by the view).
py::array_t<double> points_view(const Eigen::MatrixXd& x, const py::object& owner);
/// The n × d array of a d × n matrix.
py::array_t<double> rows_of(const Eigen::MatrixXd& x);
/// The d × n matrix of an n × d array; InputError naming `what` for another shape or a
/// coordinate that is not finite.
Eigen::MatrixXd matrix_of(const Array& a, int dim, std::size_t n, const std::string& what);
/// matrix_of for a mesh's coordinates, which must also be in the range the methods compute in.
Eigen::MatrixXd points_of(const Array& a, int dim, std::size_t n, const std::string& what);

/// A 1-D array holding `v`.
template <class T>
py::array_t<T> array_of(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

/// Mesh.cell_blocks and Mesh.facet_blocks: dicts of type, order, nodes, physical.
py::list block_dicts(const std::vector<CellBlock>& blocks);
/// A mesh from arrays (Mesh(points, cells, facets, groups)): the blocks as Mesh.cell_blocks
/// and Mesh.facet_blocks give them, the groups as Mesh.groups. InputError naming the block or
/// group and the key for anything else.
Mesh mesh_of(const Array& points, const py::list& cells, const py::list& facets, const py::list& groups);

}  // namespace meshmorph

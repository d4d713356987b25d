// SPDX-License-Identifier: MIT
#pragma once
#include <pybind11/pybind11.h>

namespace meshmorph {

namespace py = pybind11;

/// The module's private helpers of the meshio conversion (_cell_order, _cell_nodes,
/// _vtk_permutation, _complete_cells; python/meshmorph/_meshio.py).
void add_conversions(py::module_& m);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <pybind11/pybind11.h>

namespace meshmorph {

namespace py = pybind11;

/// The module's private helpers of meshmorph.plot (_cell_outlines, _boundary_faces).
void add_drawing(py::module_& m);

}  // namespace meshmorph

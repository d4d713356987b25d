// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

/// The fields `meshmorph plot` colours cells by (docs/cli.md, "plot"), as Python's meshmorph.plot names them.
inline constexpr std::array<std::string_view, 4> kPlotFields = {"quality", "shape_quality", "scaled_jacobian",
                                                                "displacement"};

/// One value per cell (the blocks of Mesh::cells concatenated) and the words beside its colour bar.
struct CellField {
  std::vector<double> values;
  std::string label;
};

/// `field` (one of kPlotFields) of each cell of `mesh`: "shape_quality" and "scaled_jacobian"
/// of the mesh alone (quality_report), "quality" 1/η against `reference`, "displacement" the
/// mean over a cell's nodes of their distance to the same nodes of `reference`. `reference`
/// must have the same nodes and cells; InputError where a field needs it and it is null.
CellField cell_field(const Mesh& mesh, std::string_view field, const Mesh* reference);

/// The cells to outline: those with a value at or below the `fraction` quantile of the finite
/// values (NumPy's linear interpolation, as meshmorph.plot) and below their maximum (by more
/// than 1e-9 of it), at or below 0, or not finite.
std::vector<bool> worst_cells(const std::vector<double>& values, double fraction);

/// A polygon to fill in the colour of `cell`: a 2D cell, or a boundary face of a 3D one, in
/// drawing coordinates (x right, y up), through the nodes on its edges.
struct Face {
  std::vector<Eigen::Vector2d> outline;
  std::int32_t cell = 0;
};

/// What is drawn of `mesh`, back to front. 2D: every cell as it lies. 3D: the boundary faces
/// of the cells whose centres (the mean of their nodes) lie at or below the middle of the y
/// range, so the cut shows the inside as meshmorph.plot's does; seen without perspective
/// from above the +x+y side (elevation 20°, azimuth 60°, matplotlib's angles), where the cut's
/// faces look towards, and painted far to near by the depth of their nodes' mean.
std::vector<Face> mesh_faces(const Mesh& mesh);

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// How the cells of a mesh are oriented against their neighbours. Two cells that share a
/// facet are alike when they induce opposite orientations on it; in each connected part the
/// cells fall into two classes, and the class whose orientation gives the part the larger
/// signed volume (then the more cells, then the lower first index) is the mesh's. The
/// orientation is combinatorial: a tangled mesh is still oriented alike, while a cell listed
/// mirrored (clockwise among counter-clockwise ones) is flipped whatever its shape.
struct CellOrientation {
  std::vector<std::int32_t> flipped;  ///< global cell indices (Topology order), ascending
  /// A cell that cannot be oriented alike with all its neighbours (a non-orientable mesh,
  /// which no valid placement has), or −1.
  std::int32_t twisted_cell = -1;
  bool consistent() const { return flipped.empty() && twisted_cell < 0; }
};
/// `volumes`: signed_volumes(mesh).
CellOrientation cell_orientation(const Mesh& mesh, const Topology& topology, const std::vector<double>& volumes);

/// ∫ det A over a cell (X: dim × n nodal coordinates): its signed volume, exact (the
/// quadrature integrates the polynomial det A exactly).
double signed_volume(ElementType type, int order, const Eigen::MatrixXd& X);
/// signed_volume of every cell, in Topology order (parallel over cells).
std::vector<double> signed_volumes(const Mesh& mesh);

/// The cells' signed volumes as listed, added up, against the volume the boundary encloses:
/// (1/d)∮ x·n over the boundary facets oriented as the mesh's orientation class has them
/// (the facets of flipped cells reversed); both exact for curved cells. They agree to
/// rounding when no cell is flipped, whatever the shape, and differ by twice the volume of
/// the flipped cells otherwise: a mesh whose cells, each positive, add up to more than the
/// boundary encloses overlaps itself. Sums do not depend on the thread count.
struct VolumeBalance {
  double cells = 0.0;
  double enclosed = 0.0;
  double scale = 0.0;  ///< Σ|cell volume| + Σ|facet term|: the size of the rounding
  bool balanced() const;
};
/// `volumes`: signed_volumes(mesh); `orientation`: cell_orientation of the same.
VolumeBalance volume_balance(const Mesh& mesh, const Topology& topology, const std::vector<double>& volumes,
                             const CellOrientation& orientation);

/// Lists the given cells (global indices, Topology order) mirrored: their nodes permuted so
/// that each is the same point set with the opposite orientation (the first two reference
/// coordinates swapped). The topology's local facet numbers of those cells change with it.
void mirror_cells(Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& cells);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <functional>

#include <Eigen/Core>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// The background mesh of a distance field (paper 003 §3.1) and how it is refined.
struct DistanceFieldOptions {
  Eigen::VectorXd lower, upper;  ///< opposite corners of the box the background mesh covers
  int cells = 8;                 ///< root cells along the box's longest side (cubic cells)
  int levels = 4;                ///< refinements (halving the cell size) around the zero set
  int order = 2;                 ///< Lagrange order of the background cells, 1–3
};

/// A signed distance on a background mesh.
struct DistanceField {
  Mesh background;        ///< quadrilaterals / hexahedra of `order`, refined near the zero set
  Eigen::VectorXd values; ///< signed distance at each background node (< 0 inside)
  std::size_t surface_facets = 0;  ///< segments / triangles of the reconstructed zero set
  double finest_size = 0;          ///< edge length of the finest cells
};

/// The signed distance to the boundary of the set {inside(x)} (a ±1 indicator), sampled on
/// a background mesh refined around that boundary: paper 003 §3.1, with the exact distance
/// to a reconstructed surface in place of the p-Laplacian approximation it cites.
/// - Background: a root grid of cubic cells over the box, each cell refined `levels` times
///   into 2^d children while the indicator changes sign on a 9^d lattice over the cell
///   grown by half its size on every side (the finest cells form a band about four cells
///   wide around the zero set). Cells of different sizes meet nonconformingly: the field is
///   continuous within the band, where every cell has the finest size.
/// - Zero set: each finest cell is split into Kuhn simplices (2 triangles / 6 tetrahedra,
///   conforming between neighbours); on each simplex edge whose ends the indicator tells
///   apart, the crossing is found by bisection of the indicator to 1e-13 of the cell size;
///   marching simplices join the crossings into segments / triangles.
/// - Values: the exact distance of each node to those facets (a box tree), negative where
///   inside(x). The surface is within O(h²κ) of the true one (h the finest size, κ its
///   curvature); features thinner than h/2 may be missed.
/// Throws std::invalid_argument for a dimension other than 2 or 3, an empty box, cells < 1,
/// levels outside 0–12, order outside 1–3, or a box whose indicator has no sign change.
DistanceField distance_field(const std::function<bool(const Eigen::VectorXd&)>& inside, int dim,
                             const DistanceFieldOptions& options);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/fem/shape_table.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// The points at which validity is sampled for (type, order): the metric quadrature
/// points, the Lagrange nodes and, for order ≥ 2, the nodes of the order-2p lattice (the
/// determinant of A is a polynomial of degree d(p−1) on simplices, so this dense set
/// catches sign changes between nodes). Shared table.
const ShapeTable& validity_samples(ElementType type, int order);

/// min over validity_samples of det A for one element (X: dim × n nodal coordinates), or,
/// where every sample is positive but the Bernstein expansion of det A finds it ≤ 0 between
/// them (curved cells, hexahedra; docs/metrics.md, Validity), the value ≤ 0 it found there.
/// An element is valid when this is > 0 (DESIGN §2). On quadrilaterals and hexahedra the
/// samples are tensor grids, taken by sum factorization (grid_gradients).
double min_jacobian_det(ElementType type, int order, const Eigen::MatrixXd& X);
/// The same over the samples whose flag in `skip` (one per validity sample) is 0, sample by
/// sample, without the Bernstein expansion (the skipped samples are meant to be ≤ 0).
double min_jacobian_det(ElementType type, int order, const Eigen::MatrixXd& X, const std::vector<std::uint8_t>& skip);

/// Where the Bernstein bounds of det A find it ≤ 0 in one curved cell or hexahedron (X: dim ×
/// n nodes; simplices and tensor cells): the lattice, of the degree of det A, of the piece of
/// the reference cell where the bisection of min_jacobian_det found it (dim × N reference
/// points, the whole cell's lattice where a lattice value of the cell is ≤ 0). Sampling there
/// sees the fold that the validity samples miss. Empty (dim × 0) where the bounds find none,
/// and on prisms, pyramids and cells that need no bounds.
Eigen::MatrixXd fold_samples(ElementType type, int order, const Eigen::MatrixXd& X);

/// Number of cells of `mesh` whose min_jacobian_det is ≤ 0 (or not finite).
std::size_t count_invalid_cells(const Mesh& mesh);
/// One flag per cell of `mesh` (blocks in order): 1 where min_jacobian_det is ≤ 0 (or not
/// finite), so that callers who need both the count and the cells pass over the mesh once.
std::vector<std::uint8_t> invalid_cells(const Mesh& mesh);

}  // namespace meshmorph

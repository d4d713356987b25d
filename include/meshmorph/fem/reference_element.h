// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// The reference element of a family and order, with its Lagrange nodes in the internal
/// (Gmsh) ordering. Simplices live on the unit simplex (corners 0, e₁, e₂, e₃); tensor
/// cells on [−1, 1]^d; prisms on the unit triangle × [−1, 1]; pyramids on the base [−1, 1]²
/// at w = 0 with the apex at (0, 0, 1): all as in Gmsh. Built once per (type, order) and shared.
struct ReferenceElement {
  ElementType type;
  int order = 1;
  int dim = 0;                 ///< topological dimension
  Eigen::MatrixXd nodes;       ///< dim × n_nodes reference coordinates
  /// Trace: for each local facet (mesh/topology.h corner_facets order), the cell-local
  /// indices of its nodes, listed in the facet element's own ordering.
  std::vector<std::vector<int>> facet_nodes;

  int n_nodes() const { return static_cast<int>(nodes.cols()); }
};

/// The shared reference element of (type, order); throws std::invalid_argument outside
/// orders 1–4 (simplices, lines, complete prisms: Gmsh's 6, 18, 40 and 75 nodes) / 1–3
/// (tensor cells; order 4 is also available) / 1–2 (pyramids: Gmsh's 14-node P2 pyramid).
const ReferenceElement& reference_element(ElementType type, int order);

/// Weights of the corner (linear/multilinear) shape functions at reference point `xi`:
/// barycentric coordinates on simplices, products of (1 ± ξ)/2 on tensor cells, their products
/// on prisms, the rational P1 basis on pyramids (lagrange_basis.h).
Eigen::VectorXd corner_weights(ElementType type, const Eigen::VectorXd& xi);

/// Measure of the reference cell: 1/d! (simplices), 2^d (tensor cells), 1 (prism: ½ × 2),
/// 4/3 (pyramid).
double reference_measure(ElementType type);

}  // namespace meshmorph

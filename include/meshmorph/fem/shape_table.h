// SPDX-License-Identifier: MIT
#pragma once
#include <memory>

#include <Eigen/Core>

#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/tensor_basis.h"

namespace meshmorph {

/// Basis values and reference gradients of (type, order) tabulated at a point set —
/// the quadrature points of a rule, or any other samples. Precomputed once and shared,
/// so element loops never evaluate a basis.
struct ShapeTable {
  ElementType type;
  int order = 1;
  int dim = 0;
  Eigen::MatrixXd points;   ///< dim × n_points (reference)
  Eigen::VectorXd weights;  ///< quadrature weights (empty for sample sets)
  Eigen::MatrixXd N;        ///< n_nodes × n_points
  /// n_nodes × (dim · n_points); columns [q·dim, q·dim + dim) hold ∂N_a/∂ξ at point q.
  Eigen::MatrixXd dN;
  /// The 1D factors of dN where the points are a tensor grid (x fastest) of a quadrilateral
  /// or hexahedron: grid_gradients then gives X dN by sum factorization. Null elsewhere.
  std::shared_ptr<const TensorGrid> tensor;

  int n_nodes() const { return static_cast<int>(N.rows()); }
  int n_points() const { return static_cast<int>(N.cols()); }
  auto grad(int q) const { return dN.middleCols(q * dim, dim); }
};

/// Shared table of (type, order) at the points of quadrature_rule(type, degree, family).
const ShapeTable& shape_table(ElementType type, int order, int degree, QuadratureFamily family = QuadratureFamily::Gauss);
/// Table of (type, order) at arbitrary reference points (not cached).
ShapeTable tabulate(ElementType type, int order, const Eigen::MatrixXd& points);

}  // namespace meshmorph

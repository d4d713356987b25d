// SPDX-License-Identifier: MIT
#include "meshmorph/quality/element_quality.h"

#include <cmath>
#include <limits>

#include <Eigen/LU>

#include "meshmorph/error.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/shape_table.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/quality/distortion.h"

namespace meshmorph {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

template <int d>
double distortion_integral(ElementType type, int order, const Eigen::MatrixXd& X, const Eigen::MatrixXd* X_input) {
  const ShapeTable& table = shape_table(type, order, metric_quadrature_degree(type, order));
  MESHMORPH_CHECK(X.rows() == d && X.cols() == table.n_nodes(), "element_distortion: X has the wrong shape");
  MESHMORPH_CHECK(!X_input || (X_input->rows() == d && X_input->cols() == table.n_nodes()),
                  "element_distortion: X_input has the wrong shape");
  const MatT<d> W_ideal = ideal_jacobian(type);
  const DistortionSquared<d> eta2;
  double num = 0.0, den = 0.0;
  for (int q = 0; q < table.n_points(); ++q) {
    const MatT<d> A = jacobian(X, table, q);
    const MatT<d> W = X_input ? MatT<d>(jacobian(*X_input, table, q)) : W_ideal;
    const double det_W = W.determinant();
    if (!(det_W > 0.0)) return kInf;
    const double e = eta2.eval(A * W.inverse(), Want::Value).mu;
    if (!std::isfinite(e)) return kInf;
    const double w = det_W * table.weights(q);
    num += e * w;
    den += w;
  }
  return std::sqrt(num / den);
}

}  // namespace

Eigen::MatrixXd ideal_jacobian(ElementType type) {
  switch (type) {
    case ElementType::Triangle: return (Eigen::Matrix2d() << 1.0, 0.5, 0.0, std::sqrt(3.0) / 2.0).finished();
    case ElementType::Tetrahedron:
      return (Eigen::Matrix3d() << 1.0, 0.5, 0.5, 0.0, std::sqrt(3.0) / 2.0, std::sqrt(3.0) / 6.0, 0.0, 0.0,
              std::sqrt(2.0 / 3.0))
          .finished();
    case ElementType::Quadrilateral: return Eigen::Matrix2d::Identity();
    case ElementType::Hexahedron: return Eigen::Matrix3d::Identity();
    case ElementType::Prism:  // the equilateral triangle of unit edge × a unit height (ζ ∈ [−1, 1])
      return (Eigen::Matrix3d() << 1.0, 0.5, 0.0, 0.0, std::sqrt(3.0) / 2.0, 0.0, 0.0, 0.0, 0.5).finished();
    case ElementType::Pyramid:  // the unit square base at ζ = 0, the apex 1/√2 above: unit edges
      return Eigen::Vector3d(0.5, 0.5, std::sqrt(0.5)).asDiagonal();
    default: MESHMORPH_CHECK(false, "ideal_jacobian: not a cell family");
  }
  return {};
}

double element_distortion(ElementType type, int order, const Eigen::MatrixXd& X, const Eigen::MatrixXd* X_input) {
  MESHMORPH_CHECK(topological_dim(type) >= 2, "element_distortion: not a cell family");
  return topological_dim(type) == 2 ? distortion_integral<2>(type, order, X, X_input)
                                    : distortion_integral<3>(type, order, X, X_input);
}

double element_quality(ElementType type, int order, const Eigen::MatrixXd& X, const Eigen::MatrixXd* X_input) {
  if (!X.allFinite()) return 0.0;
  const double det = min_jacobian_det(type, order, X);
  if (!(det > 0.0)) return 0.0;
  const double eta = element_distortion(type, order, X, X_input);
  return std::isfinite(eta) ? 1.0 / eta : 0.0;
}

}  // namespace meshmorph

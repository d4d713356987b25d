// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <random>
#include <string>

#include <Eigen/Core>

#include "meshmorph/energy/target.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/quality/metric_registry.h"

namespace meshmorph::test {

/// The metric the energy tests use in dimension d: the morphing integrand η² (paper 000 eq. 7).
template <int d>
std::unique_ptr<Metric<d>> test_metric(const std::string& name = "distortion2") {
  return make_metric<d>(name);
}

/// A mesh of one cell whose nodes are the columns of X (d × n).
inline Mesh one_cell_mesh(ElementType type, int order, const Eigen::MatrixXd& X) {
  Mesh mesh;
  mesh.dim = static_cast<int>(X.rows());
  mesh.x = X;
  for (Eigen::Index i = 0; i < X.cols(); ++i) mesh.node_tags.push_back(i + 1);
  CellBlock block;
  block.type = type;
  block.order = order;
  std::vector<std::int32_t> nodes(static_cast<std::size_t>(X.cols()));
  for (std::size_t i = 0; i < nodes.size(); ++i) nodes[i] = static_cast<std::int32_t>(i);
  block.push_back(nodes.data(), 1);
  mesh.cells.push_back(block);
  return mesh;
}

/// A valid element of size about 1: the reference nodes under a random affine map near the
/// identity, each node then moved at random by up to `amplitude`/order (retried until
/// min det A > 0 on the validity samples).
inline Eigen::MatrixXd random_element(ElementType type, int order, unsigned seed, double amplitude = 0.08) {
  const ReferenceElement& ref = reference_element(type, order);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const int d = ref.dim;
  const double size = is_simplex(type) ? 1.0 : 0.5;  // tensor references span [−1, 1]
  // Prisms above order 2: the nodes move by `amplitude`/order of their unit triangle, not of
  // the half-size one (at 0.2/4 of the half-size triangle no random quartic prism is valid).
  const double step = type == ElementType::Prism && order > 2 ? size * amplitude / order : amplitude / order;
  for (;;) {
    Eigen::MatrixXd M(d, d);
    for (int i = 0; i < d * d; ++i) M(i) = (i % (d + 1) == 0 ? 1.0 : 0.0) + 0.25 * u(rng);
    Eigen::MatrixXd X = size * M * ref.nodes;
    for (Eigen::Index i = 0; i < X.size(); ++i) X(i) += step * u(rng);
    for (int k = 0; k < d; ++k) X.row(k).array() += u(rng);
    if (min_jacobian_det(type, order, X) > 0.0) return X;
  }
}

/// structured_mesh(type, order, n) with its non-boundary nodes moved at random by up to
/// `amplitude` cell sizes / order; still valid.
inline Mesh perturbed_mesh(ElementType type, int order, int n, unsigned seed, double amplitude = 0.15) {
  Mesh mesh = structured_mesh(type, order, n);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double h = amplitude / (n * order);
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j) {
    bool inside = true;
    for (Eigen::Index k = 0; k < mesh.x.rows(); ++k)
      inside = inside && mesh.x(k, j) > 1e-12 && mesh.x(k, j) < 1.0 - 1e-12;
    if (!inside) continue;
    for (Eigen::Index k = 0; k < mesh.x.rows(); ++k) mesh.x(k, j) += h * u(rng);
  }
  return mesh;
}

}  // namespace meshmorph::test

// SPDX-License-Identifier: MIT
#include "meshmorph/energy/element_energy.h"

#include <limits>

#include "energy/detail/element_kernel.h"
#include "meshmorph/error.h"

namespace meshmorph {

template <int d>
ElementEnergy element_energy(const Metric<d>& metric, const ShapeTable& table,
                             std::span<const QuadratureTarget<d>> targets,
                             const Eigen::Matrix<double, d, Eigen::Dynamic>& X, Want want, HessianMode mode) {
  const int n = table.n_nodes();
  MESHMORPH_CHECK(table.dim == d, "element_energy: the shape table's dimension differs from the metric's");
  MESHMORPH_CHECK(X.cols() == n, "element_energy: X must have one column per node of the element");
  MESHMORPH_CHECK(n <= detail::k_max_nodes, "element_energy: too many nodes per element");
  MESHMORPH_CHECK(static_cast<int>(targets.size()) == table.n_points(),
                  "element_energy: one target per quadrature point is needed");
  detail::ElementScratch<d> scratch;
  const detail::NodalMatrix<d> Xe = X;
  ElementEnergy out;
  out.value = detail::element_kernel<d>(metric, table, targets.data(), Xe, want, mode, scratch);
  if (want == Want::Value || !(out.value < std::numeric_limits<double>::infinity())) return out;
  // Kernel order is component-major (k·n + a); the public order is interleaved (d·a + k).
  out.gradient = Eigen::Map<const Eigen::VectorXd>(scratch.g.data(), d * n);
  if (want == Want::Hessian) {
    out.hessian.resize(d * n, d * n);
    for (int b = 0; b < n; ++b)
      for (int l = 0; l < d; ++l)
        for (int a = 0; a < n; ++a)
          for (int k = 0; k < d; ++k) out.hessian(d * a + k, d * b + l) = scratch.H(k * n + a, l * n + b);
  }
  return out;
}

template ElementEnergy element_energy<2>(const Metric<2>&, const ShapeTable&, std::span<const QuadratureTarget<2>>,
                                         const Eigen::Matrix<double, 2, Eigen::Dynamic>&, Want, HessianMode);
template ElementEnergy element_energy<3>(const Metric<3>&, const ShapeTable&, std::span<const QuadratureTarget<3>>,
                                         const Eigen::Matrix<double, 3, Eigen::Dynamic>&, Want, HessianMode);

}  // namespace meshmorph

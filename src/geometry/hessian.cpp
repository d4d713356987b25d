// SPDX-License-Identifier: MIT
#include <Eigen/Core>

#include "geometry/detail/level_set_node.h"

namespace meshmorph::detail {

Eigen::MatrixXd hessian_by_differences(const std::function<Vec(const Vec&)>& gradient, const Vec& x, double h) {
  const Eigen::Index d = x.size();
  Eigen::MatrixXd D(d, d);
  Vec y = x;
  for (Eigen::Index k = 0; k < d; ++k) {
    auto at = [&](double t) {
      y(k) = x(k) + t;
      return gradient(y);
    };
    D.col(k) = (-at(2 * h) + 8 * at(h) - 8 * at(-h) + at(-2 * h)) / (12 * h);
    y(k) = x(k);
  }
  return (D + D.transpose()) / 2;
}

}  // namespace meshmorph::detail

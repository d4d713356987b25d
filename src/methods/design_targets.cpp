// SPDX-License-Identifier: MIT
#include "meshmorph/methods/design_targets.h"

#include <algorithm>
#include <cmath>

namespace meshmorph {

void ExactDesignTargets::add(LevelSetFunction sigma, const std::vector<std::int32_t>& nodes) {
  level_sets_.push_back(std::move(sigma));
  for (std::int32_t v : nodes)
    if (owner_[static_cast<std::size_t>(v)] < 0) owner_[static_cast<std::size_t>(v)] = static_cast<int>(level_sets_.size()) - 1;
}

std::optional<Eigen::VectorXd> ExactDesignTargets::project(std::int32_t node, const Eigen::VectorXd& x) const {
  const int k = owner_[static_cast<std::size_t>(node)];
  if (k < 0) return std::nullopt;
  return level_sets_[static_cast<std::size_t>(k)].closest_point(x);
}

std::pair<double, double> design_errors(const DesignSurface& surface, const Eigen::MatrixXd& target,
                                        const ExactDesignTargets& exact, const std::vector<std::uint8_t>& on_design,
                                        const Eigen::MatrixXd& x) {
  double max = 0.0, sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < on_design.size(); ++i) {
    if (!on_design[i]) continue;
    const Eigen::VectorXd p = x.col(static_cast<Eigen::Index>(i));
    double e = distance_to_surface(surface, target, p);
    if (const auto q = exact.project(static_cast<std::int32_t>(i), p)) e = (*q - p).norm();
    max = std::max(max, e);
    sum += e * e;
    ++count;
  }
  return {max, std::sqrt(sum / static_cast<double>(count))};
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <optional>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/geometry/level_set_function.h"
#include "meshmorph/methods/surface_cvt.h"

namespace meshmorph {

/// The exact surfaces of design nodes that a level set moves (a `project` entry of deform):
/// the last increment snaps them onto it, and their boundary error is measured to it.
class ExactDesignTargets {
 public:
  explicit ExactDesignTargets(std::size_t n_nodes) : owner_(n_nodes, -1) {}
  /// `sigma`'s zero level set becomes the surface of those `nodes` that have none yet.
  void add(LevelSetFunction sigma, const std::vector<std::int32_t>& nodes);
  /// The closest point of `x` on the surface of `node`; none where the node has no surface or
  /// the level set has no closest point.
  std::optional<Eigen::VectorXd> project(std::int32_t node, const Eigen::VectorXd& x) const;

 private:
  std::vector<LevelSetFunction> level_sets_;
  std::vector<int> owner_;  // per node: index into level_sets_, or −1
};

/// Max and root-mean-square distance of the design nodes (`on_design`, one flag per node) at
/// `x` (d × n) from the target surface: the exact one where `exact` has it, else the design's
/// facets at `target`. Design nodes slide tangentially on purpose, so this, not the distance
/// from their own targets, is their boundary error.
std::pair<double, double> design_errors(const DesignSurface& surface, const Eigen::MatrixXd& target,
                                        const ExactDesignTargets& exact, const std::vector<std::uint8_t>& on_design,
                                        const Eigen::MatrixXd& x);

}  // namespace meshmorph

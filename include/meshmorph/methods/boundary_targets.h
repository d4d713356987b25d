// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// What the boundary condition asks of one node.
enum class NodeRole : std::uint8_t {
  Free,        ///< interior node (or a boundary node no condition names and that is not fixed)
  Fixed,       ///< stays at its input position (hard-fixed: not an unknown)
  Prescribed,  ///< must reach `target` (a moving group: translate, rotate, scale, project, displace)
  Slide,       ///< may move tangentially on the plane through its input position with `normal`
};

/// The boundary condition of a run, resolved per node of the mesh (DESIGN §3.2): boundary nodes
/// in no listed group are Fixed, interior nodes Free. Built by the app from the case file; the
/// methods (morph, baselines) only read it.
struct BoundaryTargets {
  std::vector<NodeRole> role;  ///< per node
  Eigen::MatrixXd target;      ///< dim × n_nodes: final position (Prescribed), input position otherwise
  Eigen::MatrixXd normal;      ///< dim × n_nodes: unit normal of the slide plane (Slide), 0 otherwise

  std::size_t n_nodes() const { return role.size(); }
  /// Nodes with role `r`, in increasing order.
  std::vector<std::int32_t> nodes_with(NodeRole r) const {
    std::vector<std::int32_t> out;
    for (std::size_t i = 0; i < role.size(); ++i)
      if (role[i] == r) out.push_back(static_cast<std::int32_t>(i));
    return out;
  }
};

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/geometry/level_set.h"
#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// Nodal displacements read from a CSV file `node,dx,dy[,dz]` (node = tag in the mesh file).
struct DisplacementTable {
  std::filesystem::path file;
  std::vector<std::int64_t> node_tags;  ///< unique, in file order
  Eigen::MatrixXd displacement;         ///< (2 or 3) × node_tags.size()
  std::vector<int> line;                ///< line of each row in `file`, for later messages
};

struct FixedMotion {};
struct TranslateMotion { CaseVector displacement; };
/// Rotation by `degrees` (counter-clockwise about `axis`, right-hand rule) around `center`;
/// `axis` is absent in 2D.
struct RotateMotion { CaseVector center; std::optional<CaseVector> axis; double degrees = 0; };
struct ScaleMotion { CaseVector center; double factor = 1; };
/// Each node of the group moves to (morph, untangle) or along (fit) the zero level set.
struct ProjectMotion { LevelSet target; };
struct DisplaceMotion { DisplacementTable table; };
/// Tangential motion on the group's initial plane.
struct SlideMotion {};

using Motion = std::variant<FixedMotion, TranslateMotion, RotateMotion, ScaleMotion, ProjectMotion,
                            DisplaceMotion, SlideMotion>;

/// One entry of "boundary": a physical group (name, or number as decimal digits) and its motion.
struct BoundaryCondition {
  std::string group;
  Motion motion;
  std::string key_path;  ///< "boundary[i]"
};

/// The "boundary" entries of a case resolved on its mesh (DESIGN §3.2): a role per node and
/// the prescribed motion as a path x(t), t ∈ [0, 1], for time series (`steps`).
///
/// Roles: nodes of a moving group (translate, rotate, scale, project, displace) are
/// Prescribed; nodes of a `slide` group slide on the group's plane, unless they are in a
/// moving group, in a `fixed` group, or on a second slide plane at an angle to the first
/// (then Fixed: the planes' intersection is a point in 2D, and a line, not held, in 3D);
/// every other boundary node (listed as `fixed` or not listed) is Fixed; interior nodes are
/// Free, also when a listed group contains them. A node in two moving groups must get the same
/// target from both (within 1e-12 of the mesh size), else InputError.
/// Paths: translations and displacements linear in t, rotations by t·angle, scaling by
/// 1 + t(factor − 1), projections along the straight segment to the closest point.
class BoundaryMotion {
 public:
  /// The entries of a case's "boundary" (checked against `mesh`: their groups exist). Throws
  /// InputError naming `file` (the case file) and the key path when a projection finds no
  /// closest point, a slide group is not planar, or two groups prescribe different targets.
  BoundaryMotion(const std::vector<BoundaryCondition>& boundary, const std::string& file, const Mesh& mesh,
                 const Topology& topology);

  /// Roles, final targets (t = 1) and slide normals.
  const BoundaryTargets& targets() const { return targets_; }
  /// Node positions at fraction t of the motion (d × n; input positions where not Prescribed).
  Eigen::MatrixXd at(double t) const;

 private:
  const Mesh* mesh_;
  std::vector<Motion> motions_;             // per boundary entry
  std::vector<std::int32_t> owner_;         // per node: the entry that prescribes it, or −1
  Eigen::MatrixXd end_;                     // d × n: final targets of prescribed nodes
  BoundaryTargets targets_;
};

}  // namespace meshmorph

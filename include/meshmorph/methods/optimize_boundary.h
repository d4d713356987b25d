// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/geometry/level_set.h"
#include "meshmorph/methods/fit.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// How optimize treats the boundary nodes that no entry names (docs/optimize.md, Boundary).
enum class BoundaryTreatment {
  Fixed,        ///< every boundary node stays where it is
  Slide,        ///< on the boundary's own planes and curved facets (boundary_slides, curved)
  SlidePlanes,  ///< on its planes only (MFEM's -bnd)
};

/// A boundary entry of an optimize case, as the method takes it.
struct OptimizeEntry {
  enum class Kind { Fixed, Slide, Project };
  Kind kind = Kind::Fixed;
  std::vector<std::int32_t> nodes;    ///< the nodes of its group
  std::optional<LevelSet> level_set;  ///< Project: the surface its nodes slide on
  std::string key_path;               ///< "boundary[2]": names the entry in messages
};

/// What optimize's nodes may do: a fixed flag per DOF and the surfaces of the sliding nodes.
struct OptimizeConstraints {
  std::vector<std::uint8_t> fixed;  ///< one per DOF (d·node + k)
  std::vector<FitTerm> slides;      ///< no entry empty
  std::size_t slide_nodes = 0;      ///< nodes that slide, each counted once
};

/// The constraints of an optimize run on `start` (the input, untangled where it was tangled).
/// Nodes no entry names follow `treatment` (`feature_angle` in degrees splits sliding patches,
/// boundary_slides). Entries: Project slides the group on its level set, after moving its
/// nodes onto it in `start` (the new nodes of an elevated mesh); Slide on the group's plane
/// or, where its nodes are not on one plane, on the smooth patches of its boundary facets;
/// Fixed holds the group, whatever other entries say. A node on d or more surfaces (a corner)
/// is fixed. Throws InputError, starting with `file` and the entry's key, when a node has no
/// closest point on its level set, moving nodes onto it inverts cells, or a curved slide
/// group holds no boundary facet.
OptimizeConstraints optimize_constraints(Mesh& start, const Topology& topology, const std::vector<OptimizeEntry>& entries,
                                         BoundaryTreatment treatment, double feature_angle, const std::string& file);

/// A valid start for TMOP from a tangled mesh: untangled (paper 001, regular reference) with
/// its boundary fixed, on `threads` threads; where inverted cells have all their corners on the
/// boundary (boundary_bound_inverted), first in patches around them with the boundary sliding
/// along itself (untangle_locally). `newton` (0 on entry) receives the Newton steps taken.
/// Throws InputError starting with `where` when untangling does not reach a valid mesh.
Eigen::MatrixXd untangled_start(const Mesh& mesh, const Topology& topology, int threads, const std::string& where,
                                long long& newton);

}  // namespace meshmorph

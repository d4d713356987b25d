// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/geometry/level_set.h"
#include "meshmorph/geometry/level_set_function.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// The smooth pieces whose zero sets make up the zero set of `ls` (docs/fit.md, Sharp
/// features): the leaves of its sharp CSG operators, a box as its 2d face planes, a
/// `distance` level set through to its operand. A blended CSG, a mesh field, an expression
/// and a torus are one piece each.
std::vector<LevelSet> smooth_pieces(const LevelSet& ls, int dim);

/// `ls` with its `distance` wrapper taken off: the exact level set whose zero set the
/// distance samples (ls itself for the other kinds).
const LevelSet& exact_level_set(const LevelSet& ls);

/// The nodes of the fitted surface that lie on its edges (two pieces meet) or corners (three
/// in 3D, two in 2D), and the pieces each follows.
struct FitFeatures {
  std::vector<std::int32_t> nodes;      ///< sorted
  std::vector<std::vector<int>> pieces;  ///< per entry of `nodes`: its pieces (indices), sorted
  std::size_t on_edges = 0, on_corners = 0;
  /// Nodes of a feature that the mesh cannot follow (turns of a staircase: find_features),
  /// left on the surface, and their pieces.
  std::vector<std::int32_t> unplaced;
  std::vector<std::vector<int>> unplaced_pieces;
};

/// Each fitted facet (`facets`: its nodes in the facet element's ordering, corners first,
/// then each edge's nodes) takes the piece nearest its centroid among those active at the
/// closest point of `surface` (the exact level set). Where facets of different pieces meet
/// (a mesh edge in 3D, a vertex in 2D), the nodes there follow both pieces; a vertex where
/// three or more meet in 3D is a corner and follows three of them (the three nearest).
/// A node whose pieces have no common zero set within `reach` of it, or meet there off the
/// surface (cut away by another piece), stays a surface node.
/// In 3D a vertex where one facet has both its edges on one feature (two pieces) is a turn
/// of the staircase: that facet would be flat there with both edges on the feature, so the
/// vertex and the inner nodes of its feature edges are `unplaced` (the feature crosses the
/// facet).
FitFeatures find_features(const Mesh& mesh, const std::vector<std::vector<std::int32_t>>& facets,
                          const LevelSetFunction& surface, const std::vector<LevelSetFunction>& pieces, double reach);

/// The point of the common zero set of `pieces` that a Gauss–Newton projection (least-norm
/// steps) reaches from x: the closest one to first order; nullopt when it does not converge.
std::optional<Eigen::VectorXd> project_to_feature(const Eigen::VectorXd& x, const std::vector<const LevelSetFunction*>& pieces);

/// |project_to_feature(x, pieces) − x|; +inf when the projection does not converge.
double distance_to_feature(const Eigen::VectorXd& x, const std::vector<const LevelSetFunction*>& pieces);

/// The largest distance_to_feature over `nodes` (with their pieces, as FitFeatures lists
/// them) at x (d × n_nodes); 0 without nodes.
double max_feature_distance(const std::vector<std::int32_t>& nodes, const std::vector<std::vector<int>>& node_pieces,
                            const std::vector<LevelSetFunction>& pieces, const Eigen::MatrixXd& x);

}  // namespace meshmorph

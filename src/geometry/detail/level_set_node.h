// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/geometry/level_set.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

using Vec = Eigen::VectorXd;

/// A node's answers at one point x (LevelSetNode::at), sharing the work they have in common.
class NodePoint {
 public:
  virtual ~NodePoint() = default;
  virtual double value() const = 0;
  virtual Vec gradient() const = 0;
  virtual Eigen::MatrixXd hessian() const = 0;
  virtual double stationarity(const Vec& g) const = 0;
  virtual Eigen::MatrixXd step_normals(const Vec& g) const = 0;
};

/// One node of a compiled level-set tree. Immutable; safe to evaluate from several threads.
class LevelSetNode {
 public:
  virtual ~LevelSetNode() = default;
  virtual double value(const Vec& x) const = 0;
  /// σ(x), and ∇σ(x) in `g` (resized by the callee).
  virtual double value_gradient(const Vec& x, Vec& g) const = 0;
  /// ∇²σ(x), d×d and symmetric; NaN entries where σ has no second derivative from any side.
  virtual Eigen::MatrixXd hessian(const Vec& x) const = 0;
  /// Closest point of the zero set. Default: the general iteration (closest_point.cpp).
  virtual std::optional<Vec> closest_point(const Vec& x) const;
  /// The first-order descent of a function of gradient g along the zero set at x (on it).
  /// Default: |g − (g·n)n| with n = ∇σ/|∇σ|, for a zero set smooth at x.
  virtual double stationarity(const Vec& x, const Vec& g) const {
    Vec n;
    value_gradient(x, n);
    n.normalize();
    return (g - n * n.dot(g)).norm();
  }
  /// The normals (d × k, orthonormal) that a step of a node at x on the zero set must stay
  /// orthogonal to, given the gradient g of the energy there. Default: ∇σ/|∇σ|.
  virtual Eigen::MatrixXd step_normals(const Vec& x, const Vec& /*g*/) const {
    Vec n;
    value_gradient(x, n);
    return n.normalized();
  }
  /// The answers at x, equal to this node's functions there. Default: each one calls its
  /// function at x; a facet surface answers them all from one search.
  virtual std::unique_ptr<const NodePoint> at(const Vec& x) const;
  /// The smooth pieces whose zero sets make up this one's (itself, for a leaf).
  virtual void collect_leaves(std::vector<const LevelSetNode*>& leaves) const { leaves.push_back(this); }
};

using NodePtr = std::shared_ptr<const LevelSetNode>;

/// Error context of a compile: "source: key_path.kind" prefixes every message.
struct CompileContext {
  std::string source;
  double length_scale = 1.0;
  int dim = 0;
};

/// The step of the numerical derivatives (expression gradients, difference Hessians):
/// h = 2e-4·max(‖x‖, ℓ).
inline double difference_step(const Vec& x, double length_scale) { return 2e-4 * std::max(x.norm(), length_scale); }

/// ∇²σ from five-point central differences of `gradient` with step h, symmetrized:
/// D(:, k) = (−g(x+2h e_k) + 8g(x+h e_k) − 8g(x−h e_k) + g(x−2h e_k)) / 12h, H = (D + Dᵀ)/2.
Eigen::MatrixXd hessian_by_differences(const std::function<Vec(const Vec&)>& gradient, const Vec& x, double h);

/// A d×d matrix of NaN: the Hessian where σ is not twice differentiable from any side.
inline Eigen::MatrixXd undefined_hessian(Eigen::Index d) {
  return Eigen::MatrixXd::Constant(d, d, std::numeric_limits<double>::quiet_NaN());
}

/// Compiles a tree (level_set_function.cpp dispatches here by kind).
NodePtr compile_node(const LevelSet& ls, const CompileContext& ctx);
NodePtr make_sphere(const SphereLevelSet& s);
NodePtr make_cylinder(const CylinderLevelSet& s);
NodePtr make_plane(const PlaneLevelSet& s);
NodePtr make_box(const BoxLevelSet& s);
NodePtr make_torus(const TorusLevelSet& s);
/// Throws InputError(`where` + ": invalid expression ...") when it does not compile.
NodePtr make_expression(const std::string& expression, double length_scale, const std::string& where);
enum class CsgOp { Union, Intersection, Difference };
/// `blend` > 0: smooth min/max of each pair closer than it (UnionLevelSet's note).
NodePtr make_csg(CsgOp op, std::vector<NodePtr> operands, double blend = 0.0);
/// Throws InputError(`where` + ": ...") for a mesh without cells, a size mismatch or a
/// non-finite value (naming the node).
NodePtr make_background_field(Mesh mesh, Eigen::VectorXd values, const std::string& where);
/// A `mesh` level set from a file: reads s.file (io's read_mesh) and takes its nodal field
/// s.field. Errors (InputError) start with `where` ("source: key_path.mesh"): a malformed
/// or unreadable file, a mesh of another dimension than `dim`, a missing field (listing the
/// available ones), a non-finite value.
NodePtr load_background_field(const MeshLevelSet& s, int dim, const std::string& where);

/// Closest point of {σ_i = 0 for every i} to x0, starting from `start`: Gauss–Newton
/// projection onto the constraints alternated with a damped tangential correction until
/// x0 − p lies in the span of the ∇σ_i(p). nullopt on failure (closest_point.cpp).
std::optional<Vec> constrained_closest_point(const Vec& x0, const std::vector<const LevelSetNode*>& constraints,
                                             const Vec& start);

}  // namespace meshmorph::detail

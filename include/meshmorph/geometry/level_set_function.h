// SPDX-License-Identifier: MIT
#pragma once
#include <memory>
#include <optional>
#include <string>

#include <Eigen/Core>

#include "meshmorph/geometry/level_set.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

namespace detail {
class LevelSetNode;
class NodePoint;
}  // namespace detail

/// How a LevelSet is compiled.
struct LevelSetOptions {
  /// Named first in error messages (usually the case file), e.g. "case.json".
  std::string source;
  /// Length below which coordinates count as "near the origin": the difference step of
  /// expression gradients is h = 2e-4·max(‖x‖, length_scale). Pass the size of the mesh
  /// when it is far from 1 (e.g. a geometry in metres of size 1e-4).
  double length_scale = 1.0;
};

/// A level set's answers at one point x (LevelSetFunction::at): equal to the
/// LevelSetFunction member functions of the same names at x, from one evaluation where they
/// share one: a facet surface (facet_surface.h) searches its facets once for all of them,
/// where each of those member functions searches again. A value of its caller's (one per
/// thread, no state shared); it keeps its level set alive.
class LevelSetPoint {
 public:
  double value() const;
  Eigen::VectorXd gradient() const;
  Eigen::MatrixXd hessian() const;
  double stationarity(const Eigen::Ref<const Eigen::VectorXd>& g) const;
  Eigen::MatrixXd step_normals(const Eigen::Ref<const Eigen::VectorXd>& g) const;

 private:
  friend class LevelSetFunction;
  LevelSetPoint(std::shared_ptr<const detail::LevelSetNode> root, std::shared_ptr<const detail::NodePoint> point, int dim)
      : root_(std::move(root)), point_(std::move(point)), dim_(dim) {}
  std::shared_ptr<const detail::LevelSetNode> root_;
  std::shared_ptr<const detail::NodePoint> point_;
  int dim_;
};

/// A compiled, evaluable level set σ: ℝ^d → ℝ (σ < 0 inside the solid, σ = 0 on its
/// surface; DESIGN §3.2), with its gradient ∇σ and closest points of its zero set.
/// docs/level-sets.md describes every kind, the closest-point iterations, their accuracy
/// and their failure modes.
///
/// - sphere, cylinder, plane, box, torus: σ is the exact signed distance; value, gradient
///   and closest point are closed forms (exact to rounding).
/// - expr: muparser in x, y, z (constant pi); ∇σ by fourth-order central differences with
///   step h = 2e-4·max(‖x‖, length_scale) (relative gradient error ≈ 1e-12 for smooth σ).
/// - union / intersection / difference: σ = min / max / max(a, −b), ∇σ of the active
///   operand (the first one on ties).
/// - mesh: a nodal field on a background mesh, interpolated with the cell's Lagrange basis;
///   from a file, the mesh is read with read_mesh (io/mesh_io.h) and the field is one of its
///   Mesh::node_fields (VTU PointData, MSH $NodeData).
/// - distance: the signed distance to the zero set of its operand's sign, sampled on a
///   background mesh refined around it (geometry/distance_field.h) and interpolated as a
///   mesh field; built here, once.
///
/// Immutable once built; copies share the compiled tree. Every member function may be
/// called from several threads at once (expressions keep a locked pool of parsers, one
/// per concurrent caller).
class LevelSetFunction {
 public:
  /// Compiles `ls` for points of dimension `dim` (2 or 3); a `mesh` kind reads its file
  /// here. Throws InputError whose message names options.source and ls.key_path (of the
  /// operand at fault) when a vector has the wrong length, a direction or size is zero, a
  /// 3D-only kind is used in 2D, an expression does not compile, or a background mesh
  /// cannot be used: malformed file (with the reader's file and position), dimension other
  /// than `dim`, no nodal field of that name (the message lists those there are), a
  /// non-finite value (naming the node). IoError when the file cannot be read.
  LevelSetFunction(const LevelSet& ls, int dim, const LevelSetOptions& options = {});

  /// A `mesh` level set from memory: `values` (one per node of `background`) interpolated
  /// with the Lagrange basis of each cell. Throws InputError when sizes do not match, a
  /// value is not finite (naming the node) or the mesh has no cells.
  LevelSetFunction(Mesh background, Eigen::VectorXd values);

  /// A level set from a compiled node: for the builders of geometry/ (facet_surface.h).
  LevelSetFunction(std::shared_ptr<const detail::LevelSetNode> root, int dim) : dim_(dim), root_(std::move(root)) {}

  int dim() const { return dim_; }

  /// σ(x); x has dim() entries.
  double value(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// ∇σ(x). Where σ is not differentiable (a sphere's centre, a box's medial planes) it is
  /// one of the one-sided gradients.
  Eigen::VectorXd gradient(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// ∇²σ(x), dim() × dim(), symmetric.
  /// - sphere (circle) (I − n nᵀ)/‖x − c‖ with n = ∇σ; cylinder (I − a aᵀ − n nᵀ)/‖v⊥‖;
  ///   plane 0; box 0 inside, (P_A − n nᵀ)/σ outside with P_A the projector on the axes
  ///   beyond the box (0 beside a face); torus (I − n nᵀ − (R/ρ) t tᵀ)/‖x − k‖ with ρ the
  ///   distance from the axis and t the core circle's tangent. Exact to rounding.
  /// - expr and mesh: five-point central differences of ∇σ with the step of expression
  ///   gradients, h = 2e-4·max(‖x‖, ℓ) (ℓ = length_scale; for a mesh field, the diagonal
  ///   of the background's bounding box), symmetrized. A mesh field differences the
  ///   gradient of the polynomial of the cell holding x (0 for P1 simplices).
  /// - union / intersection / difference: the active operand's (the gradient's tie rule).
  /// NaN entries where σ has no second derivative from any side: a sphere's centre, a
  /// cylinder's axis, the torus's axis and core circle.
  Eigen::MatrixXd hessian(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// For x on the zero set, the steepest first-order descent of a function of gradient g
  /// (dim() entries) along it: |g − (g·n)n| with n = ∇σ/|∇σ| where the zero set is smooth at
  /// x; at a crease of a facet surface (facet_surface.h), the largest norm of the projection
  /// of −g onto the tangent cone of one facet through x. 0 at a crease that g pushes x into
  /// from every side: a minimum of the function on the zero set, though g is not normal.
  double stationarity(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& g) const;

  /// For x on the zero set, an orthonormal basis (dim() × k) of the normals that a step of a
  /// node at x minimising a function of gradient g must stay orthogonal to: ∇σ/|∇σ| (k = 1),
  /// except at a crease of a facet surface that g pushes x into from every side (stationarity
  /// no larger than the descent along the crease), where the normals of every facet through x
  /// (k = 2 on an edge in 3D: the step follows it; k = dim() at a corner: no step).
  Eigen::MatrixXd step_normals(const Eigen::Ref<const Eigen::VectorXd>& x, const Eigen::Ref<const Eigen::VectorXd>& g) const;

  /// The answers at x (LevelSetPoint), for a caller that asks several of them there.
  LevelSetPoint at(const Eigen::Ref<const Eigen::VectorXd>& x) const;

  /// The closest point p of the zero level set to x: σ(p) = 0 and x − p ∥ ∇σ(p) (or, at
  /// an edge or corner of a CSG, x − p in the span of the active operands' normals).
  /// Where several points are equally close (x at a sphere's centre) one of them.
  /// std::nullopt when none is found: σ has no zero set near x, ∇σ vanishes, or the
  /// iteration does not converge.
  std::optional<Eigen::VectorXd> closest_point(const Eigen::Ref<const Eigen::VectorXd>& x) const;

 private:
  int dim_ = 0;
  std::shared_ptr<const detail::LevelSetNode> root_;
};

}  // namespace meshmorph

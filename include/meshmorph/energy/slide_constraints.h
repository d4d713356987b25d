// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/energy/dof_map.h"
#include "meshmorph/energy/level_set_penalty.h"

namespace meshmorph {

/// An orthonormal basis of the plane with unit normal n (d × (d − 1), d = 2 or 3): the
/// tangent half of a slide node's frame, T Tᵀ = I − n nᵀ.
Eigen::MatrixXd tangent_basis(const Eigen::VectorXd& n);

/// Nodes held on zero level sets while they move along them (docs/energy.md, Sliding nodes).
/// The nodes of each `slides` entry stay on its zero level set (a node in two entries on
/// their intersection; all its DOFs must be free). Each slide node has a frame at the
/// current iterate: N, an orthonormal basis of the constraint normals ∇σ_i, and P = I − N Nᵀ.
/// The gradient there is P g, the Hessian's rows and columns of the node are multiplied by
/// P, and its diagonal block gets c N Nᵀ (c its mean tangential diagonal, so the normal step
/// is exactly 0) plus the constraint curvature −Σ λ_i P ∇²σ_i P with g = Σ λ_i ∇σ_i + P g
/// (the Hessian of the Lagrangian on the tangent space; PSD-projected in
/// HessianMode::Projected). After a step the nodes return to their level sets by
/// Gauss–Newton (minimal-norm corrections), which makes σ_i(x) = 0 to the accuracy of σ. A
/// node on one level set takes N and its share of |∇F| from it (step_normals, stationarity):
/// ∇σ and |P g| but at the creases of a facet surface (geometry/facet_surface.h).
template <int d>
class SlideConstraints {
 public:
  /// A slide node's step constraints: N (the normals that bind its step), P = I − N Nᵀ and
  /// the addition to its diagonal block.
  struct Frame {
    Eigen::Matrix<double, d, Eigen::Dynamic> N;
    Eigen::Matrix<double, d, d> P, add;
  };

  SlideConstraints() = default;
  /// Copies the level sets of `slides` and keeps a reference to `dofs`, the unknowns of the
  /// Hessians and gradients it constrains, which must outlive it. Throws
  /// std::invalid_argument for a node on d level sets or with a fixed DOF.
  SlideConstraints(const std::vector<FitTerm>& slides, const DofMap& dofs);

  bool empty() const { return nodes_.empty(); }
  std::size_t size() const { return nodes_.size(); }
  /// The nodes, in slot order.
  std::vector<std::int32_t> nodes() const;

  /// Moves every slide node of x (d × n_nodes) back onto its level sets; false when one
  /// does not converge (its Gauss–Newton steps not finite, or not settled in 50 steps).
  bool project(Eigen::MatrixXd& x, int threads) const;

  /// Constrains an assembled Hessian and gradient at x (Hessian in an assembler's pattern:
  /// the offsets of the nodes' diagonal blocks are found on the first call and kept) and
  /// keeps the frames for frame_of_row().
  void constrain(const Eigen::MatrixXd& x, HessianMode mode, Assembly& out, int threads);
  /// Matrix-free: the frames at x from the unconstrained d×d diagonal blocks of every node
  /// (`node_blocks`, node-major, column-major blocks: EnergyAssembler::hessian_blocks), and
  /// the gradient constrained.
  void constrain(const Eigen::MatrixXd& x, const std::vector<double>& node_blocks, HessianMode mode,
                 Eigen::VectorXd& gradient);
  /// The constrained Hessian's action from the unconstrained one: tangential(v) gives P v
  /// at the slide nodes (v elsewhere), to which the caller applies H; finish_action(v, y)
  /// turns y = H P v into P H P v + add v.
  void tangential(const Eigen::VectorXd& v, Eigen::VectorXd& out) const;
  void finish_action(const Eigen::VectorXd& v, Eigen::VectorXd& y) const;
  /// The frame (of the last constrain()) of the slide node whose first free DOF has reduced
  /// index `row`; null for any other row.
  const Frame* frame_of_row(std::int32_t row) const;

  /// The gradient's free entries at x that count towards |∇F|: at a node on one level set
  /// its entries are zeroed and the return value gets stationarity² (the descent the surface
  /// allows), at a node on two the normals are removed. Returns the sum of those squares.
  double tangential_gradient(const Eigen::MatrixXd& x, Eigen::VectorXd& gradient) const;

 private:
  // The level sets one node lies on (1 or 2, < d).
  struct Node {
    std::int32_t node = 0, first = 0;  // node, reduced index of its first DOF
    int m = 0;
    std::array<std::int32_t, 2> sigma{};  // into sigma_
  };
  Eigen::Matrix<double, d, Eigen::Dynamic> normals(const Node& s, const Eigen::MatrixXd& x) const;
  Frame frame(const Node& s, const Eigen::MatrixXd& x, const Eigen::Matrix<double, d, d>& B,
              const Eigen::Matrix<double, d, 1>& g, HessianMode mode) const;

  const DofMap* dofs_ = nullptr;
  std::vector<LevelSetFunction> sigma_;
  std::vector<Node> nodes_;
  std::vector<std::int32_t> slot_of_row_;   // reduced index of a slide node's first DOF → slot, else −1
  std::vector<std::int64_t> block_offsets_;  // the d×d diagonal block of each node (block_offsets.h)
  std::vector<Frame> frames_;                // at the last constrain()
};

}  // namespace meshmorph

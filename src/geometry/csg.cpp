// SPDX-License-Identifier: MIT
// CSG level sets. The zero set of a CSG tree lies in the union of its leaves' zero sets,
// and its closest point p lies on the intersection of the leaves active at p (one leaf on
// a face, two on an edge, three at a 3D corner), where it is a closest point of that
// intersection. So the candidates are: each leaf's own closest point, and the closest
// points of each pair (and, in 3D, triple) of leaves' common zero set; those on the
// combined zero set compete and the nearest wins. A blended tree rounds those edges: its
// closest point is the projection onto its own zero set from the sharp tree's one.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "geometry/detail/level_set_node.h"

namespace meshmorph::detail {

namespace {

class Csg final : public LevelSetNode {
 public:
  Csg(CsgOp op, std::vector<NodePtr> operands, double blend) : op_(op), operands_(std::move(operands)), blend_(blend) {
    for (const auto& o : operands_) o->collect_leaves(leaves_);
    if (blend_ > 0.0) sharp_ = std::make_unique<Csg>(op_, operands_, 0.0);
  }

  double value(const Vec& x) const override {
    double v = operand_value(0, x);
    for (std::size_t i = 1; i < operands_.size(); ++i) v = combine(v, operand_value(i, x));
    return v;
  }

  double value_gradient(const Vec& x, Vec& g) const override {
    if (blend_ > 0.0) return blended(x, &g, nullptr);
    const std::size_t k = active(x);
    double v = operands_[k]->value_gradient(x, g);
    if (op_ == CsgOp::Difference && k == 1) {
      v = -v;
      g = -g;
    }
    return v;
  }

  // The active operand's Hessian, with the gradient's tie rule.
  Eigen::MatrixXd hessian(const Vec& x) const override {
    if (blend_ > 0.0) {
      Vec g;
      Eigen::MatrixXd H;
      blended(x, &g, &H);
      return H;
    }
    const std::size_t k = active(x);
    Eigen::MatrixXd H = operands_[k]->hessian(x);
    if (op_ == CsgOp::Difference && k == 1) H = -H;
    return H;
  }

  std::optional<Vec> closest_point(const Vec& x) const override {
    if (sharp_) {
      const std::optional<Vec> start = sharp_->closest_point(x);
      return constrained_closest_point(x, {this}, start ? *start : x);
    }
    const Eigen::Index dim = x.size();
    std::vector<std::optional<Vec>> own(leaves_.size());
    for (std::size_t i = 0; i < leaves_.size(); ++i) own[i] = leaves_[i]->closest_point(x);

    std::optional<Vec> best;
    double best_distance = std::numeric_limits<double>::infinity();
    auto offer = [&](const std::optional<Vec>& p) {
      if (!p || !on_zero_set(*p, x)) return false;
      const double d = (*p - x).norm();
      if (d < best_distance) best_distance = d, best = p;
      return true;
    };
    for (const auto& p : own) offer(p);

    // Common zero sets of 2 (and 3 in 3D) leaves, started from x and from the members'
    // own closest points.
    const std::size_t n = leaves_.size();
    auto solve = [&](const std::vector<std::size_t>& members) {
      // A point of Z_i ∩ Z_j is no closer than either leaf's closest point: skip subsets
      // that cannot beat the best candidate (exact for the analytic leaves).
      double bound = 0;
      for (std::size_t m : members)
        if (own[m]) bound = std::max(bound, (*own[m] - x).norm());
      if (bound > best_distance * (1 + 1e-12)) return;
      std::vector<const LevelSetNode*> constraints;
      for (std::size_t m : members) constraints.push_back(leaves_[m]);
      std::vector<Vec> starts{x};
      for (std::size_t m : members)
        if (own[m]) starts.push_back(*own[m]);
      bool found = false;
      for (const Vec& s : starts) found |= offer(constrained_closest_point(x, constraints, s));
      // On a symmetry axis (x midway between two equal circles) the leaves' normals are
      // parallel at every start and Gauss–Newton cannot leave the axis: break the tie with
      // fixed offsets of a tenth of the distance to the nearest own closest point.
      if (!found) {
        const Vec offset = Vec::LinSpaced(dim, 0.6180339887, 0.2360679775) * (0.1 * bound);
        offer(constrained_closest_point(x, constraints, x + offset));
        offer(constrained_closest_point(x, constraints, x - offset));
      }
    };
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j) {
        solve({i, j});
        if (dim == 3)
          for (std::size_t k = j + 1; k < n; ++k) solve({i, j, k});
      }
    return best;
  }

  void collect_leaves(std::vector<const LevelSetNode*>& leaves) const override {
    leaves.insert(leaves.end(), leaves_.begin(), leaves_.end());
  }

 private:
  double operand_value(std::size_t i, const Vec& x) const {
    const double v = operands_[i]->value(x);
    return op_ == CsgOp::Difference && i == 1 ? -v : v;
  }
  // min (union) or max of two values; blended within `blend_` of each other.
  double combine(double a, double b) const {
    const double sign = op_ == CsgOp::Union ? 1.0 : -1.0, t = a - b;
    if (std::abs(t) < blend_) return 0.5 * (a + b) - sign * (0.25 * blend_ + t * t / (4.0 * blend_));
    return op_ == CsgOp::Union ? std::min(a, b) : std::max(a, b);
  }

  // σ, ∇σ and (when H is given) ∇²σ of the blended tree, folding the operands left to right
  // by the chain rule: the blend of a and b has ∂/∂a = ½ − s·t/2k, ∂/∂b = ½ + s·t/2k (t =
  // a − b, s = +1 for min, −1 for max) and adds −s/2k (∇a − ∇b)(∇a − ∇b)ᵀ to the Hessian.
  double blended(const Vec& x, Vec* g, Eigen::MatrixXd* H) const {
    const double sign = op_ == CsgOp::Union ? 1.0 : -1.0;
    const auto operand = [&](std::size_t i, Vec& gi, Eigen::MatrixXd* Hi) {
      double v = operands_[i]->value_gradient(x, gi);
      if (Hi) *Hi = operands_[i]->hessian(x);
      if (op_ == CsgOp::Difference && i == 1) {
        v = -v;
        gi = -gi;
        if (Hi) *Hi = -*Hi;
      }
      return v;
    };
    Eigen::MatrixXd Hv, Hb;
    double v = operand(0, *g, H ? &Hv : nullptr);
    Vec gb;
    for (std::size_t i = 1; i < operands_.size(); ++i) {
      const double b = operand(i, gb, H ? &Hb : nullptr);
      const double t = v - b;
      if (std::abs(t) >= blend_) {
        if (op_ == CsgOp::Union ? b < v : b > v) {
          v = b;
          *g = gb;
          if (H) Hv = Hb;
        }
        continue;
      }
      const double da = 0.5 - sign * t / (2.0 * blend_), db = 0.5 + sign * t / (2.0 * blend_);
      if (H) {
        const Vec dg = *g - gb;
        Hv = da * Hv + db * Hb - (sign / (2.0 * blend_)) * dg * dg.transpose();
      }
      *g = da * *g + db * gb;
      v = combine(v, b);
    }
    if (H) *H = 0.5 * (Hv + Hv.transpose());
    return v;
  }

  // The operand that sets σ (the first one on ties).
  std::size_t active(const Vec& x) const {
    std::size_t k = 0;
    double v = operand_value(0, x);
    for (std::size_t i = 1; i < operands_.size(); ++i) {
      const double w = operand_value(i, x);
      if (op_ == CsgOp::Union ? w < v : w > v) v = w, k = i;
    }
    return k;
  }

  // |σ(p)|/|∇σ(p)| (the distance to the zero set to first order) is at rounding level.
  bool on_zero_set(const Vec& p, const Vec& x) const {
    Vec g;
    const double v = value_gradient(p, g);
    const double scale = std::max({x.norm(), p.norm(), (x - p).norm()});
    return std::isfinite(v) && std::abs(v) <= 1e-11 * scale * g.norm();
  }

  CsgOp op_;
  std::vector<NodePtr> operands_;
  double blend_ = 0.0;
  std::vector<const LevelSetNode*> leaves_;  // owned by operands_
  std::unique_ptr<const Csg> sharp_;         // a blended tree's sharp copy, its closest points' start
};

}  // namespace

NodePtr make_csg(CsgOp op, std::vector<NodePtr> operands, double blend) {
  return std::make_shared<Csg>(op, std::move(operands), blend);
}

}  // namespace meshmorph::detail

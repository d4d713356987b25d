// SPDX-License-Identifier: MIT
#pragma once
#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

namespace meshmorph::detail {

/// A bounding-box tree over items given by their boxes [lo, hi] and key points (3 × n
/// each, z = 0 in 2D): a node splits its items at the median key along the longest side
/// of its box, down to leaves of at most 4 items. Built once; a query keeps its state on
/// its own stack, so any number of threads may query one tree at once.
class BoxTree {
 public:
  BoxTree(const Eigen::Matrix3Xd& lo, const Eigen::Matrix3Xd& hi, const Eigen::Matrix3Xd& keys);

  /// The squared distance from x to the box [lo, hi] (0 inside).
  static double box_distance2(const Eigen::Vector3d& x, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return (x - x.cwiseMax(lo).cwiseMin(hi)).squaredNorm();
  }

  /// Depth-first search from the root, the nearer child of a node first: a node whose box
  /// lies at squared distance d2 from x is entered when keep(d2), asked as the node is
  /// reached (so it sees every bound that visit tightened before), and visit(item) is
  /// called for each item of an entered leaf, in the leaf's order. The order depends on x
  /// and the tree only.
  template <class Keep, class Visit>
  void nearest_first(const Eigen::Vector3d& x, Keep&& keep, Visit&& visit) const {
    std::array<int, 128> stack{0};  // one pending sibling per level of a median-split tree
    for (std::size_t top = 1; top > 0;) {
      const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
      if (!keep(box_distance2(x, n.lo, n.hi))) continue;
      if (n.left < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) visit(items_[static_cast<std::size_t>(i)]);
        continue;
      }
      const Node &l = nodes_[static_cast<std::size_t>(n.left)], &r = nodes_[static_cast<std::size_t>(n.left) + 1];
      const bool left_first = box_distance2(x, l.lo, l.hi) <= box_distance2(x, r.lo, r.hi);
      stack[top++] = left_first ? n.left + 1 : n.left;
      stack[top++] = left_first ? n.left : n.left + 1;
    }
  }

  /// Calls visit(item) for each item of a leaf whose box meets [lo, hi] (closed boxes): the
  /// candidates of a box query, each item's own box still to be tested by the caller.
  template <class Visit>
  void overlapping(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, Visit&& visit) const {
    std::array<int, 128> stack{0};
    for (std::size_t top = 1; top > 0;) {
      const Node& n = nodes_[static_cast<std::size_t>(stack[--top])];
      if ((n.lo.array() > hi.array()).any() || (n.hi.array() < lo.array()).any()) continue;
      if (n.left < 0) {
        for (int i = n.first; i < n.first + n.count; ++i) visit(items_[static_cast<std::size_t>(i)]);
        continue;
      }
      stack[top++] = n.left + 1;
      stack[top++] = n.left;
    }
  }

 private:
  struct Node {
    Eigen::Vector3d lo, hi;
    int left = -1;              // children at left and left + 1; -1 for a leaf
    int first = 0, count = 0;   // leaf: items_[first, first + count)
  };

  void build(std::size_t id, const Eigen::Matrix3Xd& lo, const Eigen::Matrix3Xd& hi, const Eigen::Matrix3Xd& keys,
             int begin, int end);

  std::vector<Node> nodes_;
  std::vector<int> items_;  // item indices, each leaf's a contiguous range
};

}  // namespace meshmorph::detail

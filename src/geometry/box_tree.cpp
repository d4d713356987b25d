// SPDX-License-Identifier: MIT
#include "geometry/detail/box_tree.h"

#include <algorithm>
#include <limits>
#include <numeric>

#include "meshmorph/error.h"

namespace meshmorph::detail {

BoxTree::BoxTree(const Eigen::Matrix3Xd& lo, const Eigen::Matrix3Xd& hi, const Eigen::Matrix3Xd& keys) {
  MESHMORPH_CHECK(lo.cols() > 0 && hi.cols() == lo.cols() && keys.cols() == lo.cols(),
                  "BoxTree: one box and one key per item, at least one item");
  items_.resize(static_cast<std::size_t>(lo.cols()));
  std::iota(items_.begin(), items_.end(), 0);
  nodes_.resize(1);
  build(0, lo, hi, keys, 0, static_cast<int>(items_.size()));
}

// Fills node `id` with the items items_[begin, end); the two children of a node are stored
// next to each other.
void BoxTree::build(std::size_t id, const Eigen::Matrix3Xd& lo, const Eigen::Matrix3Xd& hi, const Eigen::Matrix3Xd& keys,
                    int begin, int end) {
  Eigen::Vector3d box_lo = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()), box_hi = -box_lo;
  for (int i = begin; i < end; ++i) {
    const Eigen::Index item = items_[static_cast<std::size_t>(i)];
    box_lo = box_lo.cwiseMin(lo.col(item));
    box_hi = box_hi.cwiseMax(hi.col(item));
  }
  nodes_[id].lo = box_lo;
  nodes_[id].hi = box_hi;
  if (end - begin <= 4) {
    nodes_[id].first = begin;
    nodes_[id].count = end - begin;
    return;
  }
  Eigen::Index axis = 0;
  (box_hi - box_lo).maxCoeff(&axis);
  const int mid = (begin + end) / 2;
  std::nth_element(items_.begin() + begin, items_.begin() + mid, items_.begin() + end,
                   [&](int a, int b) { return keys(axis, a) < keys(axis, b); });
  const std::size_t left = nodes_.size();
  nodes_.resize(left + 2);
  nodes_[id].left = static_cast<int>(left);
  build(left, lo, hi, keys, begin, mid);
  build(left + 1, lo, hi, keys, mid, end);
}

}  // namespace meshmorph::detail

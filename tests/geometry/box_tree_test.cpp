// SPDX-License-Identifier: MIT
// BoxTree: the nearest of random triangles and segments found through the tree equals the
// brute-force nearest; every item sits in exactly one leaf; trees of 1 to 5 items.
#include "geometry/detail/box_tree.h"

#include <algorithm>
#include <array>
#include <limits>
#include <utility>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/geometry/closest_on_simplex.h"

namespace meshmorph::detail {
namespace {

using V = Eigen::Vector3d;

struct Triangles {
  std::vector<std::array<V, 3>> corners;
  Eigen::Matrix3Xd lo, hi, centroid;
};

// n small random triangles in the unit cube (flat ones with z = 0 for `flat`).
Triangles random_triangles(int n, bool flat, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0), e(-0.05, 0.05);
  Triangles t{{}, Eigen::Matrix3Xd(3, n), Eigen::Matrix3Xd(3, n), Eigen::Matrix3Xd(3, n)};
  for (int i = 0; i < n; ++i) {
    const V o(u(rng), u(rng), flat ? 0.0 : u(rng));
    std::array<V, 3> c;
    for (V& y : c) y = o + V(e(rng), e(rng), flat ? 0.0 : e(rng));
    t.corners.push_back(c);
    t.lo.col(i) = c[0].cwiseMin(c[1]).cwiseMin(c[2]);
    t.hi.col(i) = c[0].cwiseMax(c[1]).cwiseMax(c[2]);
    t.centroid.col(i) = (c[0] + c[1] + c[2]) / 3;
  }
  return t;
}

double distance2(const std::array<V, 3>& c, const V& p) { return (closest_on_triangle(p, c[0], c[1], c[2]) - p).squaredNorm(); }

// The nearest triangle by the tree (the first of equally near ones in the tree's order) and
// its squared distance.
std::pair<int, double> nearest(const BoxTree& tree, const Triangles& t, const V& p) {
  std::pair<int, double> best{-1, std::numeric_limits<double>::infinity()};
  tree.nearest_first(
      p, [&](double box2) { return box2 < best.second; },
      [&](int i) {
        if (const double d2 = distance2(t.corners[static_cast<std::size_t>(i)], p); d2 < best.second) best = {i, d2};
      });
  return best;
}

TEST(BoxTree, NearestEqualsBruteForce) {
  for (const bool flat : {false, true}) {
    const Triangles t = random_triangles(500, flat, flat ? 2 : 1);
    const BoxTree tree(t.lo, t.hi, t.centroid);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-0.2, 1.2);
    for (int q = 0; q < 300; ++q) {
      const V p(u(rng), u(rng), u(rng));
      double brute = std::numeric_limits<double>::infinity();
      for (const auto& c : t.corners) brute = std::min(brute, distance2(c, p));
      const auto [i, d2] = nearest(tree, t, p);
      EXPECT_EQ(d2, brute) << "p = " << p.transpose();
      EXPECT_EQ(distance2(t.corners[static_cast<std::size_t>(i)], p), brute);
    }
  }
}

// A search that keeps every node visits every item once, whatever the point.
TEST(BoxTree, EveryItemInOneLeaf) {
  for (const int n : {1, 4, 5, 9, 200}) {
    const Triangles t = random_triangles(n, false, static_cast<unsigned>(n));
    const BoxTree tree(t.lo, t.hi, t.centroid);
    for (const V& p : {V(0.5, 0.5, 0.5), V(-3, 2, 9)}) {
      std::vector<int> seen(static_cast<std::size_t>(n), 0);
      tree.nearest_first(p, [](double) { return true; }, [&](int i) { ++seen[static_cast<std::size_t>(i)]; });
      for (int i = 0; i < n; ++i) EXPECT_EQ(seen[static_cast<std::size_t>(i)], 1) << "n = " << n << ", item " << i;
    }
  }
}

// keep() decides which nodes are entered: refusing everything visits nothing; keeping the
// nodes within r visits every item whose box is within r.
TEST(BoxTree, KeepDecidesWhatIsEntered) {
  const Triangles t = random_triangles(300, false, 9);
  const BoxTree tree(t.lo, t.hi, t.centroid);
  const V p(0.5, 0.4, 0.6);
  int visits = 0;
  tree.nearest_first(p, [](double) { return false; }, [&](int) { ++visits; });
  EXPECT_EQ(visits, 0);
  const double r2 = 0.01;
  std::vector<int> seen(300, 0);
  tree.nearest_first(p, [&](double box2) { return box2 <= r2; }, [&](int i) { seen[static_cast<std::size_t>(i)] = 1; });
  int within = 0;
  for (Eigen::Index i = 0; i < 300; ++i)
    if (BoxTree::box_distance2(p, t.lo.col(i), t.hi.col(i)) <= r2) {
      ++within;
      EXPECT_EQ(seen[static_cast<std::size_t>(i)], 1) << "item " << i;
    }
  EXPECT_GT(within, 0);
}

TEST(BoxTree, BoxDistance) {
  const V lo(0, 0, 0), hi(1, 2, 3);
  EXPECT_EQ(BoxTree::box_distance2(V(0.5, 1, 1), lo, hi), 0.0);
  EXPECT_EQ(BoxTree::box_distance2(V(-1, 1, 1), lo, hi), 1.0);
  EXPECT_EQ(BoxTree::box_distance2(V(2, 4, -3), lo, hi), 1.0 + 4.0 + 9.0);
}

// A box query visits every item whose box meets the query box (and the caller's own test
// keeps exactly the brute-force set).
TEST(BoxTree, OverlappingVisitsEveryItemWhoseBoxMeetsTheQuery) {
  const Triangles t = random_triangles(500, false, 11);
  const BoxTree tree(t.lo, t.hi, t.centroid);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int q = 0; q < 50; ++q) {
    const V lo(u(rng), u(rng), u(rng)), hi = lo + V::Constant(0.1 * u(rng));
    const auto meets = [&](int i) { return !(t.lo.col(i).array() > hi.array()).any() && !(t.hi.col(i).array() < lo.array()).any(); };
    std::vector<int> found, expected;
    tree.overlapping(lo, hi, [&](int i) {
      if (meets(i)) found.push_back(i);
    });
    for (int i = 0; i < 500; ++i)
      if (meets(i)) expected.push_back(i);
    std::sort(found.begin(), found.end());
    EXPECT_EQ(found, expected);
  }
}

}  // namespace
}  // namespace meshmorph::detail

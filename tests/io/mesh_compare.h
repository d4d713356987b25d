// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph::test {

struct CompareOptions {
  bool node_tags = true;
  bool entities = true;
  bool node_fields = true;  ///< same names and bit-identical values (NaN equals NaN)
  double tolerance = 0.0;  ///< max |Δx|; 0 = bit for bit
};

inline std::vector<std::tuple<int, int, std::string>> sorted_groups(const Mesh& m) {
  std::vector<std::tuple<int, int, std::string>> g;
  for (const PhysicalGroup& p : m.groups) g.emplace_back(p.dim, p.tag, p.name);
  std::sort(g.begin(), g.end());
  return g;
}

/// Same field names, and values bit for bit (NaN matches NaN).
inline void expect_node_fields_equal(const Mesh& a, const Mesh& b) {
  ASSERT_EQ(a.node_fields.size(), b.node_fields.size());
  for (auto ia = a.node_fields.begin(), ib = b.node_fields.begin(); ia != a.node_fields.end(); ++ia, ++ib) {
    SCOPED_TRACE("node field " + ia->first);
    EXPECT_EQ(ia->first, ib->first);
    ASSERT_EQ(ia->second.size(), ib->second.size());
    for (Eigen::Index i = 0; i < ia->second.size(); ++i) {
      const double u = ia->second(i), v = ib->second(i);
      EXPECT_TRUE(u == v || (std::isnan(u) && std::isnan(v))) << "node " << i << ": " << u << " vs " << v;
    }
  }
}

inline void expect_blocks_equal(const std::vector<CellBlock>& a, const std::vector<CellBlock>& b, bool entities) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    SCOPED_TRACE("block " + std::to_string(i));
    EXPECT_EQ(a[i].type, b[i].type);
    EXPECT_EQ(a[i].order, b[i].order);
    EXPECT_EQ(a[i].nodes, b[i].nodes);
    EXPECT_EQ(a[i].physical, b[i].physical);
    if (entities) {
      EXPECT_EQ(a[i].entity, b[i].entity);
    }
  }
}

/// Bit-for-bit comparison of coordinates, connectivity, tags, groups and node fields.
inline void expect_meshes_equal(const Mesh& a, const Mesh& b, CompareOptions opt = {}) {
  ASSERT_EQ(a.dim, b.dim);
  ASSERT_EQ(a.x.rows(), b.x.rows());
  ASSERT_EQ(a.x.cols(), b.x.cols());
  if (a.x.size() > 0) {
    const double diff = (a.x - b.x).cwiseAbs().maxCoeff();
    if (opt.tolerance == 0.0) {
      EXPECT_TRUE(a.x == b.x) << "coordinates differ; max |diff| = " << diff;
    } else {
      EXPECT_LE(diff, opt.tolerance);
    }
  }
  if (opt.node_tags) {
    EXPECT_EQ(a.node_tags, b.node_tags);
  }
  {
    SCOPED_TRACE("cells");
    expect_blocks_equal(a.cells, b.cells, opt.entities);
  }
  {
    SCOPED_TRACE("facets");
    expect_blocks_equal(a.facets, b.facets, opt.entities);
  }
  EXPECT_EQ(sorted_groups(a), sorted_groups(b));
  if (opt.node_fields) {
    expect_node_fields_equal(a, b);
  }
}

}  // namespace meshmorph::test

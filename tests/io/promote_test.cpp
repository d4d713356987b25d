// SPDX-License-Identifier: MIT
// The incomplete (serendipity) cells read as complete ones: the complete cell has the
// serendipity cell's geometry on every face and inside (Gmsh 4.8.4's basis of types 16-19 at
// points on the faces and inside, tests/data/io/gmsh_serendipity_basis.json); the nodes
// added are shared by the cells and facets of a face; fields take the same weights.
#include "io/detail/promote.h"

#include <cstdint>
#include <fstream>
#include <map>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "meshmorph/fem/lagrange_basis.h"

namespace meshmorph {
namespace {

using Fields = std::map<std::string, std::vector<double>, std::less<>>;

ElementType type_of_gmsh(int code) {
  switch (code) {
    case 16: return ElementType::Quadrilateral;
    case 17: return ElementType::Hexahedron;
    case 18: return ElementType::Prism;
    default: return ElementType::Pyramid;
  }
}

// The serendipity cell's geometry Σ N_i(ξ) X_i, with Gmsh's values N_i(ξ), and the complete
// cell's, at ξ.
Eigen::Vector3d serendipity_at(const nlohmann::json& values, const Eigen::MatrixXd& X) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(values.size()); ++i) x += values[static_cast<std::size_t>(i)].get<double>() * X.col(i);
  return x;
}
Eigen::Vector3d complete_at(ElementType type, const nlohmann::json& point, const Eigen::MatrixXd& X) {
  const int d = topological_dim(type);
  Eigen::VectorXd xi(d);
  for (int k = 0; k < d; ++k) xi(k) = point[static_cast<std::size_t>(k)].get<double>();
  return X * lagrange_basis(type, 2).values(xi);
}

TEST(Promote, CompleteCellsHaveTheSerendipityGeometry) {
  std::ifstream in(std::string(MESHMORPH_TEST_DATA) + "/io/gmsh_serendipity_basis.json");
  ASSERT_TRUE(in) << "missing tests/data/io/gmsh_serendipity_basis.json";
  const nlohmann::json table = nlohmann::json::parse(in);
  std::mt19937 rng(35);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  for (const int code : {16, 17, 18, 19}) {
    SCOPED_TRACE("Gmsh type " + std::to_string(code));
    const ElementType type = type_of_gmsh(code);
    const int n = detail::incomplete_nodes_of(type);
    const Eigen::MatrixXd& ref = lagrange_basis(type, 2).reference().nodes;
    // A curved cell: the reference nodes moved at random, in 3D (quadrilaterals too).
    Eigen::MatrixXd X = Eigen::MatrixXd::Zero(3, n);
    for (int i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) X(k, i) = (k < ref.rows() ? ref(k, i) : 0.0) + jitter(rng);
    std::vector<CellBlock> blocks(1);
    blocks[0].type = type;
    blocks[0].order = 2;
    std::vector<std::int32_t> nodes(static_cast<std::size_t>(n_nodes_of(type, 2)), -1);
    for (int i = 0; i < n; ++i) nodes[static_cast<std::size_t>(i)] = i;
    blocks[0].push_back(nodes.data(), 0);
    std::vector<double> xyz(X.data(), X.data() + X.size());
    std::vector<std::int64_t> tags;
    for (int i = 0; i < n; ++i) tags.push_back(i + 1);
    Fields fields;
    EXPECT_FALSE(detail::promote_incomplete(blocks, xyz, tags, fields).empty());
    const int m = n_nodes_of(type, 2);
    ASSERT_EQ(static_cast<int>(tags.size()), m);
    Eigen::MatrixXd Y(3, m);
    for (int i = 0; i < m; ++i)
      for (int k = 0; k < 3; ++k) Y(k, i) = xyz[3 * static_cast<std::size_t>(blocks[0].cell(0)[i]) + static_cast<std::size_t>(k)];
    const nlohmann::json& t = table[std::to_string(code)];
    ASSERT_GE(t["points"].size(), 3u);
    for (std::size_t p = 0; p < t["points"].size(); ++p) {
      SCOPED_TRACE("face point " + std::to_string(p));
      EXPECT_LE((serendipity_at(t["values"][p], X) - complete_at(type, t["points"][p], Y)).norm(), 1e-14);
    }
    // Inside too: Gmsh's serendipity spaces lie in the complete ones, so the complete cell whose
    // added nodes take the serendipity cell's values is the same map.
    for (std::size_t p = 0; p < t["inside"]["points"].size(); ++p) {
      SCOPED_TRACE("inside point " + std::to_string(p));
      EXPECT_LE((serendipity_at(t["inside"]["values"][p], X) - complete_at(type, t["inside"]["points"][p], Y)).norm(), 1e-14);
    }
  }
}

// Two 15-node prisms on a shared quadrilateral face (corners 1 2 5 4 of the first, listed
// the other way round in the second), an 8-node facet on it, a complete 18-node prism on the
// second's other face with its own centre there, and a 20-node hexahedron listed twice.
TEST(Promote, FaceCentresAreSharedAndFieldsFollowTheNodes) {
  std::vector<double> xyz;
  std::vector<std::int64_t> tags;
  Fields fields{{"phi", {}}};
  const auto node = [&](double x, double y, double z) {
    xyz.insert(xyz.end(), {x, y, z});
    tags.push_back(10 + 2 * static_cast<std::int64_t>(tags.size()));
    fields["phi"].push_back(x + 2 * y + 3 * z);
    return static_cast<std::int32_t>(tags.size() - 1);
  };
  for (int i = 0; i < 30; ++i) node(0.1 * i, 0.01 * i * i, 0.5 + 0.02 * (i % 7));
  std::vector<CellBlock> blocks(3);
  blocks[0].type = ElementType::Quadrilateral;
  blocks[1].type = ElementType::Prism;
  blocks[2].type = ElementType::Hexahedron;
  for (CellBlock& b : blocks) b.order = 2;
  const auto add = [](CellBlock& b, std::vector<std::int32_t> nodes) {
    nodes.resize(static_cast<std::size_t>(b.n_nodes_per_cell()), -1);
    b.push_back(nodes.data(), 0);
  };
  add(blocks[1], {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14});
  // Corners 2 1 16 5 4 17, so that its face (0 1 4 3) is the first's (1 2 5 4).
  add(blocks[1], {2, 1, 16, 5, 4, 17, 9, 18, 11, 19, 10, 20, 14, 21, 22});
  add(blocks[1], {1, 16, 23, 4, 17, 24, 19, 25, 10, 26, 27, 28, 21, 29, 0, 6, 3, 7});  // complete: face (0 1 4 3) = (1 16 17 4), centre 6
  add(blocks[0], {1, 2, 5, 4, 9, 11, 14, 10});
  add(blocks[2], {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19});
  add(blocks[2], {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19});
  const std::string note = detail::promote_incomplete(blocks, xyz, tags, fields);
  EXPECT_EQ(note, "read 1 8-node quadrilateral as 9-node one, 2 15-node prisms as 18-node ones, 2 20-node hexahedra as "
                  "27-node ones (the nodes they lack placed where the serendipity cells put them)");
  const std::int32_t* first = blocks[1].cell(0);
  const std::int32_t* second = blocks[1].cell(1);
  EXPECT_EQ(first[17], second[15]);     // the shared face's centre
  EXPECT_EQ(blocks[0].cell(0)[8], first[17]);  // and the facet's
  EXPECT_EQ(second[17], 6);  // the complete prism's own centre of the face they share
  EXPECT_EQ(blocks[2].cell(0)[26], blocks[2].cell(1)[26]);  // a cell listed twice has one centre
  // 3 faces of the first prism, 1 of the second; 6 faces and the centre of the hexahedron.
  ASSERT_EQ(tags.size(), 30u + 4u + 7u);
  EXPECT_EQ(tags[30], 10 + 2 * 29 + 1);  // after the largest tag
  EXPECT_EQ(tags.back(), tags[30] + 10);
  EXPECT_EQ(fields["phi"].size(), tags.size());
  for (std::size_t j = 30; j < tags.size(); ++j) {  // phi is linear: the weights sum to 1 and reproduce it
    const double x = xyz[3 * j], y = xyz[3 * j + 1], z = xyz[3 * j + 2];
    EXPECT_NEAR(fields["phi"][j], x + 2 * y + 3 * z, 1e-14);
  }
  // The face centre −¼ Σ corners + ½ Σ mid-edge nodes, the hexahedron's −¼ Σ corners + ¼ Σ edge nodes.
  const auto x_of = [&](std::int32_t j) { return Eigen::Vector3d(xyz[3 * static_cast<std::size_t>(j)], xyz[3 * static_cast<std::size_t>(j) + 1], xyz[3 * static_cast<std::size_t>(j) + 2]); };
  EXPECT_LE((x_of(first[17]) - (-0.25 * (x_of(1) + x_of(2) + x_of(5) + x_of(4)) + 0.5 * (x_of(9) + x_of(11) + x_of(14) + x_of(10)))).norm(), 1e-15);
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (int i = 0; i < 20; ++i) centre += (i < 8 ? -0.25 : 0.25) * x_of(i);
  EXPECT_LE((x_of(blocks[2].cell(0)[26]) - centre).norm(), 1e-15);
}

TEST(Promote, NothingToPromoteLeavesEverything) {
  std::vector<CellBlock> blocks(1);
  blocks[0].type = ElementType::Prism;
  blocks[0].order = 2;
  std::vector<std::int32_t> nodes(18);
  for (int i = 0; i < 18; ++i) nodes[static_cast<std::size_t>(i)] = i;
  blocks[0].push_back(nodes.data(), 0);
  std::vector<double> xyz(54, 0.5);
  std::vector<std::int64_t> tags(18, 1);
  Fields fields;
  EXPECT_EQ(detail::promote_incomplete(blocks, xyz, tags, fields), "");
  EXPECT_EQ(tags.size(), 18u);
  EXPECT_EQ(blocks[0].nodes, nodes);
}

}  // namespace
}  // namespace meshmorph

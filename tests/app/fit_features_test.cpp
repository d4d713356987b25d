// SPDX-License-Identifier: MIT
// Sharp features of a CSG trim (docs/fit.md, Sharp features): the nodes on an edge or a
// corner of the CSG's zero set land on it, checked against the exact locations.
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "meshmorph/app/fit_case.h"
#include "meshmorph/fem/structured.h"

namespace meshmorph {
namespace {

RunOutput fit_case(const Mesh& mesh, const std::string& json, FitSetup* setup = nullptr) {
  const CaseFile c = parse_case_file(json, "case.json", false);
  const FitRunner runner(c, mesh, 1);
  if (setup) *setup = runner.setup();
  return runner.run();
}

// The distance from p to the nearest node of x.
double nearest_node(const Eigen::MatrixXd& x, const Eigen::VectorXd& p) {
  return (x.colwise() - p).colwise().norm().minCoeff();
}

// The unit square trimmed to a disk cut by the line y = 0.55: the two corners where circle
// and line meet, (0.5 ± √(0.35² − 0.05²), 0.55), get a node each, to rounding.
TEST(FitFeatures, TwoCornersInTwoDimensions) {
  FitSetup setup;
  const RunOutput o = fit_case(structured_mesh(ElementType::Quadrilateral, 1, 16), R"({"order": 2, "trim": {"intersection": [
      {"sphere": {"center": [0.5, 0.5], "radius": 0.35}}, {"plane": {"point": [0.5, 0.55], "normal": [0, 1]}}]}})", &setup);
  ASSERT_TRUE(o.report.converged) << o.report.message;
  EXPECT_TRUE(o.report.valid);
  const auto& f = o.extra["features"];
  EXPECT_EQ(f["nodes_on_corners"], 2);
  EXPECT_EQ(f["nodes_on_edges"], 0);
  EXPECT_EQ(f["unplaced_nodes"], 0);
  EXPECT_LT(f["max_distance"].get<double>(), 1e-8);
  EXPECT_LE(f["fit_error_surface"].get<double>(), setup.fit.eps_sigma);
  EXPECT_EQ(o.extra["choices"]["features"]["pieces"], 2);
  ASSERT_EQ(setup.features.size(), 1u);
  EXPECT_EQ(setup.features[0].found.pieces, (std::vector<std::vector<int>>{{0, 1}, {0, 1}}));
  const double half = std::sqrt(0.35 * 0.35 - 0.05 * 0.05);
  for (const double side : {-1.0, 1.0}) EXPECT_LT(nearest_node(o.moved.x, Eigen::Vector2d(0.5 + side * half, 0.55)), 1e-8);

  // Without features no node need sit on a corner.
  const RunOutput plain = fit_case(structured_mesh(ElementType::Quadrilateral, 1, 16), R"({"order": 2, "trim": {"intersection": [
      {"sphere": {"center": [0.5, 0.5], "radius": 0.35}}, {"plane": {"point": [0.5, 0.55], "normal": [0, 1]}}]},
      "options": {"features": false}})");
  EXPECT_FALSE(plain.extra.contains("features"));
  EXPECT_GT(nearest_node(plain.moved.x, Eigen::Vector2d(0.5 + half, 0.55)), 1e-3);
}

// The cube [0.22, 0.78]³ (a box: six planes) cut by x + y + z ≤ 2 in 8³ hexahedra: its seven
// remaining corners and the three where the cut meets the box's edges, (0.78, 0.78, 0.44) and
// its permutations, each get a node, and the straight edges their nodes. The cut's lines
// across the box's faces run diagonally to the grid: their staircase turns stay surface nodes
// (unplaced), at a reported distance.
TEST(FitFeatures, CornersAndEdgesOfACutBox) {
  FitSetup setup;
  const RunOutput o = fit_case(structured_mesh(ElementType::Hexahedron, 1, 8), R"({"trim": {"intersection": [
      {"box": {"center": [0.5, 0.5, 0.5], "size": [0.56, 0.56, 0.56]}},
      {"plane": {"point": [0.6666666666666666, 0.6666666666666666, 0.6666666666666666], "normal": [1, 1, 1]}}]}})", &setup);
  ASSERT_TRUE(o.report.converged) << o.report.message;
  EXPECT_TRUE(o.report.valid);
  EXPECT_GT(setup.pillowed_cells, 0u);
  EXPECT_EQ(setup.fit.target, TargetKind::Ideal);  // a pillowed trim (docs/fit.md, Choices)
  const auto& f = o.extra["features"];
  EXPECT_EQ(f["nodes_on_corners"], 10);
  EXPECT_GT(f["nodes_on_edges"].get<int>(), 0);
  EXPECT_LT(f["max_distance"].get<double>(), 1e-8);
  EXPECT_GT(f["unplaced_nodes"].get<int>(), 0);
  EXPECT_GT(f["unplaced_max_distance"].get<double>(), 1e-3);
  EXPECT_LT(f["unplaced_max_distance"].get<double>(), 0.125);
  EXPECT_EQ(o.extra["choices"]["features"]["pieces"], 7);
  const double lo = 0.22, hi = 0.78;
  for (int k = 0; k < 3; ++k) {
    Eigen::Vector3d cut = Eigen::Vector3d::Constant(hi);
    cut[k] = 2.0 - 2 * hi;
    EXPECT_LT(nearest_node(o.moved.x, cut), 1e-8) << k;
  }
  for (int corner = 0; corner < 7; ++corner) {  // all but (hi, hi, hi), which the cut removes
    const Eigen::Vector3d p(corner & 1 ? hi : lo, corner & 2 ? hi : lo, corner & 4 ? hi : lo);
    EXPECT_LT(nearest_node(o.moved.x, p), 1e-8) << corner;
  }
}

}  // namespace
}  // namespace meshmorph

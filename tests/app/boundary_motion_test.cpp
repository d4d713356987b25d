// SPDX-License-Identifier: MIT
// BoundaryMotion: the role of nodes that two boundary groups share.
#include "meshmorph/methods/boundary_motion.h"

#include <cmath>

#include <gtest/gtest.h>

#include "meshmorph/app/case_file.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {
namespace {

std::int32_t node_at(const Mesh& m, double x, double y) {
  for (std::size_t i = 0; i < m.n_nodes(); ++i)
    if ((m.x.col(static_cast<Eigen::Index>(i)) - Eigen::Vector2d(x, y)).norm() < 1e-12) return static_cast<std::int32_t>(i);
  return -1;
}

BoundaryCondition entry(const std::string& group, Motion motion) {
  BoundaryCondition bc;
  bc.group = group;
  bc.motion = std::move(motion);
  bc.key_path = "boundary[" + group + "]";
  return bc;
}

TEST(BoundaryMotion, SharedNodesKeepEveryPlaneTheyAreOn) {
  const Mesh m = structured_mesh(ElementType::Quadrilateral, 1, 4);  // sides: groups left, right, bottom, top
  const Topology topo = build_topology(m);
  CaseFile c;
  c.file = "case.json";
  for (const char* slide : {"bottom", "left"}) c.boundary.push_back(entry(slide, SlideMotion{}));
  c.boundary.push_back(entry("right", FixedMotion{}));
  c.boundary.push_back(entry("top", TranslateMotion{Eigen::Vector2d(0.1, 0)}));
  const BoundaryMotion motion(c.boundary, c.file.string(), m, topo);
  const BoundaryTargets& bc = motion.targets();
  // Bottom and left slide at an angle: their corner is their only common point.
  EXPECT_EQ(bc.role[node_at(m, 0, 0)], NodeRole::Fixed);
  EXPECT_EQ(bc.normal.col(node_at(m, 0, 0)).norm(), 0.0);
  // Bottom slides, right is fixed: the rim of the fixed wall stays on it.
  EXPECT_EQ(bc.role[node_at(m, 1, 0)], NodeRole::Fixed);
  // The moving top wins over the sliding left and the fixed right.
  EXPECT_EQ(bc.role[node_at(m, 0, 1)], NodeRole::Prescribed);
  EXPECT_EQ(bc.role[node_at(m, 1, 1)], NodeRole::Prescribed);
  // Nodes of one slide group only slide on its plane.
  const std::int32_t b = node_at(m, 0.5, 0), l = node_at(m, 0, 0.5);
  EXPECT_EQ(bc.role[b], NodeRole::Slide);
  EXPECT_NEAR(std::abs(bc.normal(1, b)), 1.0, 1e-12);
  EXPECT_EQ(bc.role[l], NodeRole::Slide);
  EXPECT_NEAR(std::abs(bc.normal(0, l)), 1.0, 1e-12);
  EXPECT_EQ(bc.role[node_at(m, 0.5, 0.5)], NodeRole::Free);
}

TEST(BoundaryMotion, TwoSlideGroupsOnOnePlaneShareItsNodes) {
  Mesh m = structured_mesh(ElementType::Quadrilateral, 1, 4);
  m.groups.push_back({1, m.find_group("bottom")->tag, "floor"});  // the bottom again, by another name
  const Topology topo = build_topology(m);
  CaseFile c;
  c.file = "case.json";
  for (const char* slide : {"bottom", "floor"}) c.boundary.push_back(entry(slide, SlideMotion{}));
  c.boundary.push_back(entry("top", TranslateMotion{Eigen::Vector2d(0.1, 0)}));
  const BoundaryMotion motion(c.boundary, c.file.string(), m, topo);
  const BoundaryTargets& bc = motion.targets();
  EXPECT_EQ(bc.role[node_at(m, 0.25, 0)], NodeRole::Slide);
  // The bottom's corners are on no other listed group: they slide with it.
  EXPECT_EQ(bc.role[node_at(m, 0, 0)], NodeRole::Slide);
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/methods/fit_features.h"

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

namespace meshmorph {
namespace {

LevelSet sphere(double r) { return {SphereLevelSet{Eigen::Vector3d::Constant(0.5), r}, "s"}; }
LevelSet box() { return {BoxLevelSet{Eigen::Vector3d::Constant(0.5), Eigen::Vector3d(0.2, 0.4, 0.6)}, "b"}; }

// A box is its six planes; a sharp CSG its leaves; a blended one and a distance's operand as
// they are.
TEST(FitFeatures, SmoothPieces) {
  const LevelSet sharp{DifferenceLevelSet{{box(), sphere(0.3)}}, "d"};
  const std::vector<LevelSet> pieces = smooth_pieces(sharp, 3);
  ASSERT_EQ(pieces.size(), 7u);
  // The planes hold the box's faces: σ = 0 at the face centres, negative inside.
  const LevelSetFunction px(pieces[1], 3);  // x = 0.6, normal +x
  EXPECT_DOUBLE_EQ(px.value(Eigen::Vector3d(0.6, 0.1, 0.9)), 0.0);
  EXPECT_LT(px.value(Eigen::Vector3d(0.5, 0.5, 0.5)), 0.0);
  const LevelSetFunction pz(pieces[4], 3);  // z = 0.2, normal −z
  EXPECT_NEAR(pz.value(Eigen::Vector3d(0.0, 0.0, 0.2)), 0.0, 1e-15);
  EXPECT_GT(pz.value(Eigen::Vector3d(0.5, 0.5, 0.1)), 0.0);
  EXPECT_TRUE(std::holds_alternative<SphereLevelSet>(pieces[6].shape));

  const LevelSet blended{DifferenceLevelSet{{box(), sphere(0.3)}, 0.05}, "d"};
  EXPECT_EQ(smooth_pieces(blended, 3).size(), 1u);
  DistanceLevelSet distance;
  distance.operands = {sharp};
  const LevelSet wrapped{distance, "w"};
  EXPECT_EQ(smooth_pieces(wrapped, 3).size(), 7u);
  EXPECT_EQ(&exact_level_set(wrapped), &std::get<DistanceLevelSet>(wrapped.shape).operands.front());
}

// The projection onto the circle where a sphere meets a plane, and onto a corner of three
// planes, against their exact closest points.
TEST(FitFeatures, ProjectionOntoEdgesAndCorners) {
  const LevelSetFunction s(sphere(0.3), 3);
  const LevelSetFunction z({PlaneLevelSet{Eigen::Vector3d(0, 0, 0.6), Eigen::Vector3d(0, 0, 1)}, "z"}, 3);
  const Eigen::Vector3d x(0.9, 0.5, 0.62);
  const double rho = std::sqrt(0.3 * 0.3 - 0.1 * 0.1);  // the circle's radius
  const double exact = std::hypot(0.4 - rho, 0.02);
  // x lies in the circle's normal plane y = 0.5, which the projection keeps to: exact.
  EXPECT_NEAR(distance_to_feature(x, {&s, &z}), exact, 1e-13);
  const std::optional<Eigen::VectorXd> p = project_to_feature(x, {&s, &z});
  ASSERT_TRUE(p);
  EXPECT_NEAR(s.value(*p), 0.0, 1e-13);
  EXPECT_NEAR((*p)[2], 0.6, 1e-13);

  const LevelSetFunction px({PlaneLevelSet{Eigen::Vector3d(0.7, 0, 0), Eigen::Vector3d(1, 0, 0)}, "x"}, 3);
  const LevelSetFunction py({PlaneLevelSet{Eigen::Vector3d(0, 0.3, 0), Eigen::Vector3d(0, -1, 0)}, "y"}, 3);
  EXPECT_NEAR(distance_to_feature(Eigen::Vector3d(0.75, 0.2, 0.5), {&px, &py, &z}), std::sqrt(0.05 * 0.05 + 0.01 + 0.01), 1e-14);
  // Parallel planes never meet.
  const LevelSetFunction z2({PlaneLevelSet{Eigen::Vector3d(0, 0, 0.2), Eigen::Vector3d(0, 0, -1)}, "z2"}, 3);
  EXPECT_TRUE(std::isinf(distance_to_feature(x, {&z, &z2})));
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <filesystem>
#include <string>
#include <variant>
#include <vector>

#include <Eigen/Core>

namespace meshmorph {

/// A point or vector of a case file: 2 entries in 2D, 3 in 3D. The parser accepts either;
/// check_case_against_mesh() checks that the length matches the mesh.
using CaseVector = Eigen::VectorXd;

struct LevelSet;

/// σ = |x − center| − radius (a circle in 2D).
struct SphereLevelSet { CaseVector center; double radius = 0; };
/// σ = distance from the (infinite) axis line through `center` − radius; 3D only.
struct CylinderLevelSet { CaseVector center, axis; double radius = 0; };
/// σ = (x − point)·n/|n|: negative on the side opposite the normal.
struct PlaneLevelSet { CaseVector point, normal; };
/// Axis-aligned box of edge lengths `size` centred at `center`.
struct BoxLevelSet { CaseVector center, size; };
/// Torus around `axis` through `center`, radii `major` (R) and `minor` (r); 3D only.
struct TorusLevelSet { CaseVector center, axis; double major = 0, minor = 0; };
/// A muparser expression in x, y, z (constant pi), compiled once by the parser to check it.
struct ExprLevelSet { std::string expression; };
/// min over the operands (≥ 1 operand). With `blend` k > 0 (all three CSG kinds), each min
/// (max) of two values a, b closer than k is smoothed to the quadratic (a + b)/2 ∓ k/4 ∓
/// (a − b)²/(4k): the edges where operands meet are rounded, the surface moving by at most
/// k/4 there and nowhere else.
struct UnionLevelSet { std::vector<LevelSet> operands; double blend = 0; };
/// max over the operands (≥ 1 operand).
struct IntersectionLevelSet { std::vector<LevelSet> operands; double blend = 0; };
/// operands[0] minus operands[1]: max(a, −b) (exactly 2 operands).
struct DifferenceLevelSet { std::vector<LevelSet> operands; double blend = 0; };
/// A nodal field `field` of a background mesh `file` (paper 003 §3.1); path resolved.
struct MeshLevelSet { std::filesystem::path file; std::string field; };
/// The signed distance to the boundary of {σ < 0} of operands[0] (only its sign is used),
/// sampled on a background mesh of the box [lower, upper] refined `levels` times around it
/// (paper 003 §3.1; geometry/distance_field.h).
struct DistanceLevelSet {
  std::vector<LevelSet> operands;  ///< exactly one: the indicator's level set ("of")
  CaseVector lower, upper;
  int cells = 8, levels = 4, order = 2;
};

/// A level set of DESIGN §3.2 (σ < 0 inside the solid) as a typed tree.
struct LevelSet {
  std::variant<SphereLevelSet, CylinderLevelSet, PlaneLevelSet, BoxLevelSet, TorusLevelSet,
               ExprLevelSet, UnionLevelSet, IntersectionLevelSet, DifferenceLevelSet, MeshLevelSet,
               DistanceLevelSet>
      shape;
  std::string key_path;  ///< where it was given, e.g. "boundary[3].project"
};

}  // namespace meshmorph

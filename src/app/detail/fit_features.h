// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <vector>

#include "meshmorph/app/fit_case.h"
#include "meshmorph/geometry/level_set.h"
#include "meshmorph/geometry/level_set_function.h"

namespace meshmorph::detail {

/// Sharp features of the surface of s.terms[term] (level set `ls`, fitted facets `facets`;
/// docs/fit.md, Sharp features): its feature nodes leave that term for one term per piece
/// they follow, appended to s.terms, and s.features gets them. Nothing when `ls` is one
/// smooth piece.
void follow_features(FitSetup& s, std::size_t term, const LevelSet& ls, const std::vector<std::vector<std::int32_t>>& facets,
                     const LevelSetOptions& options);

/// The features' figures for the report at x: nodes on edges and corners, their largest
/// distance from them, and max |σ| at the other fitted nodes; null without features.
nlohmann::ordered_json feature_report(const FitSetup& s, const Eigen::MatrixXd& x);

}  // namespace meshmorph::detail

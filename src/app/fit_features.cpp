// SPDX-License-Identifier: MIT
#include "app/detail/fit_features.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace meshmorph::detail {

void follow_features(FitSetup& s, std::size_t term, const LevelSet& ls, const std::vector<std::vector<std::int32_t>>& facets,
                     const LevelSetOptions& options) {
  const int d = s.mesh.dim;
  const std::vector<LevelSet> pieces = smooth_pieces(ls, d);
  if (pieces.size() < 2) return;
  FitSetup::Features f;
  for (const LevelSet& p : pieces) f.pieces.emplace_back(p, d, options);
  // A feature's pieces must meet within a cell of the node: the longest first edge of a facet.
  double reach = 0.0;
  for (const std::vector<std::int32_t>& facet : facets) reach = std::max(reach, (s.mesh.x.col(facet[1]) - s.mesh.x.col(facet[0])).norm());
  const LevelSetFunction exact(exact_level_set(ls), d, options);
  FitFeatures all = find_features(s.mesh, facets, exact, f.pieces, reach);

  // Only the term's own (free) nodes follow features.
  std::vector<std::int32_t>& surface = s.terms[term].nodes;
  std::vector<std::vector<std::int32_t>> of_piece(f.pieces.size());
  for (std::size_t k = 0; k < all.nodes.size(); ++k) {
    const std::int32_t node = all.nodes[k];
    if (!std::binary_search(surface.begin(), surface.end(), node)) continue;
    f.found.nodes.push_back(node);
    f.found.pieces.push_back(all.pieces[k]);
    ++(all.pieces[k].size() == static_cast<std::size_t>(d) ? f.found.on_corners : f.found.on_edges);
    for (int p : all.pieces[k]) of_piece[static_cast<std::size_t>(p)].push_back(node);
  }
  for (std::size_t k = 0; k < all.unplaced.size(); ++k)
    if (std::binary_search(surface.begin(), surface.end(), all.unplaced[k])) {
      f.found.unplaced.push_back(all.unplaced[k]);
      f.found.unplaced_pieces.push_back(all.unplaced_pieces[k]);
    }
  s.choices["features"] = {{"value", !f.found.nodes.empty()},
                           {"pieces", f.pieces.size()},
                           {"why", "the level set is a sharp CSG of " + std::to_string(f.pieces.size()) +
                                       " smooth pieces; the nodes where facets of two pieces meet follow both"}};
  if (f.found.nodes.empty()) return;
  std::erase_if(surface, [&](std::int32_t node) { return std::binary_search(f.found.nodes.begin(), f.found.nodes.end(), node); });
  for (std::size_t p = 0; p < f.pieces.size(); ++p)
    if (!of_piece[p].empty()) s.terms.push_back({f.pieces[p], std::move(of_piece[p])});
  s.features.push_back(std::move(f));
}

nlohmann::ordered_json feature_report(const FitSetup& s, const Eigen::MatrixXd& x) {
  if (s.features.empty()) return nullptr;
  std::size_t edges = 0, corners = 0, unplaced = 0;
  double distance = 0.0, unplaced_distance = 0.0;
  for (const FitSetup::Features& f : s.features) {
    edges += f.found.on_edges;
    corners += f.found.on_corners;
    unplaced += f.found.unplaced.size();
    distance = std::max(distance, max_feature_distance(f.found.nodes, f.found.pieces, f.pieces, x));
    unplaced_distance = std::max(unplaced_distance, max_feature_distance(f.found.unplaced, f.found.unplaced_pieces, f.pieces, x));
  }
  const std::vector<FitTerm> surfaces(s.terms.begin(), s.terms.begin() + static_cast<std::ptrdiff_t>(s.surface_terms));
  return {{"nodes_on_edges", edges},
          {"nodes_on_corners", corners},
          {"max_distance", distance},
          {"unplaced_nodes", unplaced},
          {"unplaced_max_distance", unplaced_distance},
          {"fit_error_surface", fit_error(surfaces, x)}};
}

}  // namespace meshmorph::detail

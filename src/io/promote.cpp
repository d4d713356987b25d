// SPDX-License-Identifier: MIT
#include "io/detail/promote.h"

#include <algorithm>
#include <array>
#include <climits>
#include <span>

namespace meshmorph::detail {
namespace {

// A node of a complete cell that its incomplete cell lacks, in Gmsh's numbering: the centre
// of the quadrilateral face of corners `corners` and mid-edge nodes `mids` (checked against
// Gmsh's PRI_15, PYR_13, QUA_8 and HEX_20 bases at those points, tests/io/promote_test.cpp).
struct FaceCentre {
  int node;
  std::array<int, 4> corners;
  std::array<int, 4> mids;
};

constexpr std::array<FaceCentre, 1> k_quadrilateral{{{8, {0, 1, 2, 3}, {4, 5, 6, 7}}}};
constexpr std::array<FaceCentre, 6> k_hexahedron{{{20, {0, 1, 2, 3}, {8, 11, 13, 9}},
                                                  {21, {0, 1, 5, 4}, {8, 12, 16, 10}},
                                                  {22, {0, 3, 7, 4}, {9, 15, 17, 10}},
                                                  {23, {1, 2, 6, 5}, {11, 14, 18, 12}},
                                                  {24, {2, 3, 7, 6}, {13, 15, 19, 14}},
                                                  {25, {4, 5, 6, 7}, {16, 18, 19, 17}}}};
constexpr std::array<FaceCentre, 3> k_prism{{{15, {0, 1, 4, 3}, {6, 10, 12, 8}},
                                             {16, {0, 2, 5, 3}, {7, 11, 13, 8}},
                                             {17, {1, 2, 5, 4}, {9, 11, 14, 10}}}};
constexpr std::array<FaceCentre, 1> k_pyramid{{{13, {0, 1, 2, 3}, {5, 8, 10, 6}}}};
constexpr int k_hexahedron_centre = 26;

std::span<const FaceCentre> face_centres(ElementType type) {
  switch (type) {
    case ElementType::Quadrilateral: return k_quadrilateral;
    case ElementType::Hexahedron: return k_hexahedron;
    case ElementType::Prism: return k_prism;
    case ElementType::Pyramid: return k_pyramid;
    default: return {};
  }
}

// A face or a hexahedron, by its sorted corner nodes (faces padded with INT_MAX).
using Key = std::array<std::int32_t, 8>;

template <std::size_t N>
Key key_of(const std::int32_t* cell, const std::array<int, N>& corners) {
  Key k;
  k.fill(INT_MAX);
  for (std::size_t i = 0; i < N; ++i) k[i] = cell[corners[i]];
  std::sort(k.begin(), k.begin() + N);
  return k;
}

std::string noun(ElementType type, std::size_t count) {
  const bool one = count == 1;
  switch (type) {
    case ElementType::Quadrilateral: return one ? "quadrilateral" : "quadrilaterals";
    case ElementType::Hexahedron: return one ? "hexahedron" : "hexahedra";
    case ElementType::Prism: return one ? "prism" : "prisms";
    case ElementType::Pyramid: return one ? "pyramid" : "pyramids";
    default: return one ? "cell" : "cells";
  }
}

}  // namespace

int incomplete_nodes_of(ElementType type) {
  switch (type) {
    case ElementType::Quadrilateral: return 8;
    case ElementType::Hexahedron: return 20;
    case ElementType::Prism: return 15;
    case ElementType::Pyramid: return 13;
    default: return 0;
  }
}

std::string promote_incomplete(std::vector<CellBlock>& blocks, std::vector<double>& xyz, std::vector<std::int64_t>& tags,
                               std::map<std::string, std::vector<double>, std::less<>>& fields) {
  const auto lacks_nodes = [](const CellBlock& b, std::size_t c) {
    const int n = incomplete_nodes_of(b.type);
    return b.order == 2 && n > 0 && b.cell(c)[n] < 0;
  };
  bool any = false;
  for (const CellBlock& b : blocks)
    for (std::size_t c = 0; c < b.n_cells() && !any; ++c) any = lacks_nodes(b, c);
  if (!any) return {};

  std::map<Key, std::int32_t> added;  // face (or hexahedron) → its centre node
  for (const CellBlock& b : blocks)   // complete cells keep their own face centres
    if (b.order == 2)
      for (std::size_t c = 0; c < b.n_cells(); ++c)
        if (!lacks_nodes(b, c))
          for (const FaceCentre& f : face_centres(b.type)) added.emplace(key_of(b.cell(c), f.corners), b.cell(c)[f.node]);

  std::int64_t next_tag = tags.empty() ? 1 : *std::max_element(tags.begin(), tags.end()) + 1;
  // The node −¼ Σ x(corners) + w Σ x(mids), with its field values.
  const auto add_node = [&](const std::int32_t* cell, std::span<const int> corners, std::span<const int> mids, double w) {
    const auto n = static_cast<std::int32_t>(tags.size());
    const auto combine = [&](auto value) {
      double s = 0, t = 0;
      for (const int i : corners) s += value(cell[i]);
      for (const int i : mids) t += value(cell[i]);
      return -0.25 * s + w * t;
    };
    for (std::size_t k = 0; k < 3; ++k) {
      const double v = combine([&](std::int32_t j) { return xyz[3 * static_cast<std::size_t>(j) + k]; });
      xyz.push_back(v);
    }
    for (auto& field : fields) {
      std::vector<double>& values = field.second;  // a lambda may not capture a structured binding (clang 14)
      const double v = combine([&](std::int32_t j) { return values[static_cast<std::size_t>(j)]; });
      values.push_back(v);
    }
    tags.push_back(next_tag++);
    return n;
  };

  std::string note;
  for (CellBlock& b : blocks) {
    std::size_t promoted = 0;
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      if (!lacks_nodes(b, c)) continue;
      ++promoted;
      std::int32_t* cell = b.cell(c);
      for (const FaceCentre& f : face_centres(b.type)) {
        const auto [it, is_new] = added.emplace(key_of(cell, f.corners), -1);
        if (is_new) it->second = add_node(cell, f.corners, f.mids, 0.5);
        cell[f.node] = it->second;
      }
      if (b.type == ElementType::Hexahedron) {
        static constexpr std::array<int, 8> corners{0, 1, 2, 3, 4, 5, 6, 7};
        static constexpr std::array<int, 12> edges{8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19};
        const auto [it, is_new] = added.emplace(key_of(cell, corners), -1);
        if (is_new) it->second = add_node(cell, corners, edges, 0.25);
        cell[k_hexahedron_centre] = it->second;
      }
    }
    if (promoted == 0) continue;
    note += std::string(note.empty() ? "read " : ", ") + std::to_string(promoted) + " " +
            std::to_string(incomplete_nodes_of(b.type)) + "-node " + noun(b.type, promoted) + " as " +
            std::to_string(b.n_nodes_per_cell()) + "-node " + (promoted == 1 ? "one" : "ones");
  }
  return note + " (the nodes they lack placed where the serendipity cells put them)";
}

}  // namespace meshmorph::detail

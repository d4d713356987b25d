// SPDX-License-Identifier: MIT
#include "meshmorph/mesh/mesh.h"

#include <algorithm>
#include <array>
#include <charconv>
#include <cstdio>
#include <system_error>

namespace meshmorph {

void CellBlock::push_back(const std::int32_t* cell_nodes, std::int32_t physical_tag, std::int32_t entity_tag) {
  nodes.insert(nodes.end(), cell_nodes, cell_nodes + n_nodes_per_cell());
  physical.push_back(physical_tag);
  entity.push_back(entity_tag);
}

std::size_t Mesh::n_cells() const {
  std::size_t n = 0;
  for (const auto& b : cells) n += b.n_cells();
  return n;
}

int Mesh::order() const {
  int p = 1;
  for (const auto& b : cells) p = std::max(p, b.order);
  return p;
}

int Mesh::max_cell_nodes() const {
  int n = 0;
  for (const auto& b : cells)
    if (topological_dim(b.type) == dim) n = std::max(n, b.n_nodes_per_cell());
  return n;
}

std::optional<PhysicalGroup> Mesh::find_group(const std::string& key) const {
  const bool numeric = !key.empty() && std::all_of(key.begin(), key.end(), [](char c) { return c >= '0' && c <= '9'; });
  // A number may name groups of several dimensions: prefer facets, then cells, then lower.
  const std::array<int, 4> preference{dim - 1, dim, dim - 2, dim - 3};
  for (int d : preference) {
    for (const auto& g : groups) {
      if (g.dim != d) continue;
      if (numeric ? std::to_string(g.tag) == key : g.name == key) return g;
    }
  }
  // A tag used by elements but without a $PhysicalNames entry (a number past int: none).
  int tag = 0;
  if (numeric && std::from_chars(key.data(), key.data() + key.size(), tag).ec == std::errc()) {
    for (int d : preference) {
      const auto& blocks = d == dim ? cells : facets;
      for (const auto& b : blocks) {
        if (topological_dim(b.type) != d) continue;
        if (std::find(b.physical.begin(), b.physical.end(), tag) != b.physical.end()) return PhysicalGroup{d, tag, {}};
      }
    }
  }
  return std::nullopt;
}

std::vector<std::int32_t> Mesh::group_nodes(const PhysicalGroup& group) const {
  std::vector<std::int32_t> out;
  const auto& blocks = group.dim == dim ? cells : facets;
  for (const auto& b : blocks) {
    if (topological_dim(b.type) != group.dim) continue;
    const int n = b.n_nodes_per_cell();
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      if (b.physical[c] != group.tag) continue;
      out.insert(out.end(), b.cell(c), b.cell(c) + n);
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::unordered_map<std::int64_t, std::int32_t> Mesh::node_index_of_tag() const {
  std::unordered_map<std::int64_t, std::int32_t> index;
  index.reserve(node_tags.size());
  for (std::size_t i = 0; i < node_tags.size(); ++i)
    if (node_tags[i] > 0) index.emplace(node_tags[i], static_cast<std::int32_t>(i));
  return index;
}

std::optional<CoordinateRangeProblem> coordinate_range_problem(const Eigen::MatrixXd& x) {
  char text[96];
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const double v = x.col(j).cwiseAbs().maxCoeff();
    if (v > kMaxCoordinate) {
      std::snprintf(text, sizeof text, "coordinate %.3g is beyond +-%.0e, where cell volumes overflow", v, kMaxCoordinate);
      return CoordinateRangeProblem{j, text};
    }
  }
  if (x.cols() > 0) {
    const double extent = (x.rowwise().maxCoeff() - x.rowwise().minCoeff()).norm();
    if (extent < kMinExtent) {
      std::snprintf(text, sizeof text, "the mesh's extent %.3g is below %.0e, where cell volumes underflow", extent,
                    kMinExtent);
      return CoordinateRangeProblem{-1, text};
    }
  }
  return std::nullopt;
}

}  // namespace meshmorph

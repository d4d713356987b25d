// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string_view>

#include "meshmorph/error.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph::fuzz {

/// Aborts (a crash to the fuzzer) unless a mesh a reader returned holds what the readers
/// promise: dimension 2 or 3, one tag per node, at least one cell, whole cells whose node
/// indices are in range and distinct, a physical and an entity tag per element, coordinates
/// within ±kMaxCoordinate, and one value per node in each node field.
inline void check_mesh(const Mesh& m) {
  const auto fail = [](const char* what) {
    std::fprintf(stderr, "fuzz: the reader returned a mesh that %s\n", what);
    std::abort();
  };
  if (m.dim != 2 && m.dim != 3) fail("is neither 2D nor 3D");
  if (m.x.rows() != m.dim) fail("has coordinates of another dimension");
  if (m.node_tags.size() != m.n_nodes()) fail("has not one tag per node");
  if (m.n_cells() == 0) fail("has no cells");
  for (const auto* blocks : {&m.cells, &m.facets})
    for (const CellBlock& b : *blocks) {
      const std::size_t k = static_cast<std::size_t>(b.n_nodes_per_cell());
      if (k == 0 || b.nodes.size() % k != 0) fail("has a block of partial cells");
      if (b.physical.size() != b.n_cells() || b.entity.size() != b.n_cells()) fail("has not one tag per element");
      for (std::size_t c = 0; c < b.n_cells(); ++c)
        for (std::size_t i = 0; i < k; ++i) {
          const std::int32_t n = b.cell(c)[i];
          if (n < 0 || static_cast<std::size_t>(n) >= m.n_nodes()) fail("references a node out of range");
          for (std::size_t j = 0; j < i; ++j)
            if (b.cell(c)[j] == n) fail("has an element listing a node twice");
        }
    }
  for (Eigen::Index j = 0; j < m.x.size(); ++j)
    if (!(std::abs(m.x.data()[j]) <= kMaxCoordinate)) fail("has a coordinate beyond kMaxCoordinate");
  for (const auto& [name, values] : m.node_fields)
    if (static_cast<std::size_t>(values.size()) != m.n_nodes()) fail("has a node field without one value per node");
}

/// The body of a reader's fuzz target: `parse` reads the bytes as `file`. Bad input must end
/// in InputError; any other exception, a sanitizer report or a mesh that breaks check_mesh is
/// a crash.
inline int read_bytes(Mesh (*parse)(std::string_view, const std::filesystem::path&), const std::uint8_t* data,
                      std::size_t size, const char* file) {
  try {
    check_mesh(parse(std::string_view(reinterpret_cast<const char*>(data), size), file));
  } catch (const InputError&) {
  }
  return 0;
}

}  // namespace meshmorph::fuzz

// SPDX-License-Identifier: MIT
#include "io/detail/mesh_builder.h"

#include <algorithm>
#include <set>
#include <string>
#include <utility>

#include "io/detail/promote.h"
#include "meshmorph/error.h"
#include "meshmorph/log.h"

namespace meshmorph::detail {

int repeated_node(const std::int32_t* nodes, int n) {
  for (int k = 1; k < n; ++k)
    if (std::find(nodes, nodes + k, nodes[k]) != nodes + k) return k;
  return -1;
}

std::ptrdiff_t TagIndex::build(const std::vector<std::int64_t>& tags) {
  dense_ = true;
  table_.clear();
  map_.clear();
  if (tags.empty()) return -1;
  const auto [lo, hi] = std::minmax_element(tags.begin(), tags.end());
  min_ = *lo;
  // Dense when the table is at most ~4x the number of nodes (typical Gmsh output is 1..n).
  const auto span = static_cast<std::uint64_t>(*hi) - static_cast<std::uint64_t>(*lo);
  dense_ = span < 4 * tags.size() + 1024;
  if (dense_) {
    table_.assign(static_cast<std::size_t>(span) + 1, -1);
    for (std::size_t i = 0; i < tags.size(); ++i) {
      std::int32_t& slot = table_[static_cast<std::size_t>(tags[i] - min_)];
      if (slot >= 0) return static_cast<std::ptrdiff_t>(i);
      slot = static_cast<std::int32_t>(i);
    }
  } else {
    map_.reserve(tags.size());
    for (std::size_t i = 0; i < tags.size(); ++i)
      if (!map_.emplace(tags[i], static_cast<std::int32_t>(i)).second) return static_cast<std::ptrdiff_t>(i);
  }
  return -1;
}

CellBlock& MeshBuilder::block(ElementType type, int order) {
  for (CellBlock& b : blocks_)
    if (b.type == type && b.order == order) return b;
  CellBlock b;
  b.type = type;
  b.order = order;
  blocks_.push_back(std::move(b));
  return blocks_.back();
}

namespace {

// MSH 2.2 holds a cell of several physical groups once per group, with the same nodes: the
// mesh keeps it once, with its first tag (a cell has one), where its repeats would overlap it.
// The kept cells are found by open addressing on their node lists, one int per slot (a hash
// set of the lists as strings took about 100 bytes a cell: 0.7 GB for 6M tetrahedra).
void drop_repeated_cells(CellBlock& b) {
  const std::size_t k = static_cast<std::size_t>(b.n_nodes_per_cell());
  const std::size_t n = b.n_cells();
  std::size_t mask = 15;
  while (mask < 2 * n) mask = 2 * mask + 1;
  std::vector<std::int32_t> slots(mask + 1, -1);  // kept cells (their new positions), by hash
  std::size_t kept = 0;
  for (std::size_t c = 0; c < n; ++c) {
    const std::int32_t* nodes = b.cell(c);
    std::uint64_t h = 0xcbf29ce484222325u;
    for (std::size_t j = 0; j < k; ++j) h = (h ^ static_cast<std::uint32_t>(nodes[j])) * 0x100000001b3u;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdu;
    h ^= h >> 33;
    std::size_t s = static_cast<std::size_t>(h) & mask;
    bool repeat = false;
    for (; slots[s] >= 0 && !repeat; s = (s + 1) & mask)
      repeat = std::equal(nodes, nodes + k, b.cell(static_cast<std::size_t>(slots[s])));
    if (repeat) continue;
    // Kept cells move down to `kept` (≤ c), so the slots always point at final positions.
    slots[s] = static_cast<std::int32_t>(kept);
    if (kept != c) {
      std::copy_n(nodes, k, b.cell(kept));
      b.physical[kept] = b.physical[c];
      b.entity[kept] = b.entity[c];
    }
    ++kept;
  }
  b.nodes.resize(kept * k);
  b.physical.resize(kept);
  b.entity.resize(kept);
}

}  // namespace

Mesh MeshBuilder::finish(const std::string& where, const std::filesystem::path& file) {
  if (const std::string note = promote_incomplete(blocks_, xyz, tags, node_fields); !note.empty())
    log_info(file.string() + ": " + note);
  Mesh mesh;
  int top = 0;
  // A block declared with no element holds no cell: a mesh of only such blocks has none.
  for (const CellBlock& b : blocks_)
    if (!b.nodes.empty()) top = std::max(top, topological_dim(b.type));
  if (top < 2) throw InputError(where + ": no triangle, quadrilateral, tetrahedron or hexahedron cells");
  mesh.dim = top;
  if (mesh.dim == 2 && !first_nonzero_z.empty())
    throw InputError(first_nonzero_z + ": node has z != 0 but the mesh has no 3D cells "
                     "(surface meshes embedded in 3D are not supported)");
  const std::size_t n = tags.size();
  mesh.x.resize(mesh.dim, static_cast<Eigen::Index>(n));
  for (std::size_t j = 0; j < n; ++j)
    for (int k = 0; k < mesh.dim; ++k) mesh.x(k, static_cast<Eigen::Index>(j)) = xyz[3 * j + static_cast<std::size_t>(k)];
  mesh.node_tags = std::move(tags);
  if (const auto bad = coordinate_range_problem(mesh.x))
    throw InputError(where + ": " +
                     (bad->node >= 0 ? "node " + std::to_string(mesh.node_tags[static_cast<std::size_t>(bad->node)]) + ": "
                                     : std::string()) +
                     bad->what);
  for (auto& [name, values] : node_fields) {
    MESHMORPH_CHECK(values.size() == n, "node field \"" + name + "\" does not cover every node");
    mesh.node_fields.emplace(name, Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<Eigen::Index>(n)));
  }
  node_fields.clear();
  for (const ExtraPhysical& e : extra_physical) {
    if (topological_dim(e.type) == mesh.dim) continue;
    CellBlock& b = block(e.type, e.order);
    const std::vector<std::int32_t> nodes(b.cell(e.cell), b.cell(e.cell) + b.n_nodes_per_cell());
    b.push_back(nodes.data(), e.tag, b.entity[e.cell]);
  }
  extra_physical.clear();
  for (CellBlock& b : blocks_) {
    if (b.nodes.empty()) continue;
    if (topological_dim(b.type) == mesh.dim) drop_repeated_cells(b);
    (topological_dim(b.type) == mesh.dim ? mesh.cells : mesh.facets).push_back(std::move(b));
  }
  blocks_.clear();
  // Groups: the named ones as in the file, then tags used by elements without a name.
  mesh.groups = std::move(named_groups);
  std::set<std::pair<int, std::int32_t>> known;
  for (const PhysicalGroup& g : mesh.groups) known.insert({g.dim, g.tag});
  std::set<std::pair<int, std::int32_t>> unnamed;
  for (const auto* list : {&mesh.facets, &mesh.cells})
    for (const CellBlock& b : *list)
      for (const std::int32_t t : b.physical)
        if (t != 0 && !known.count({topological_dim(b.type), t})) unnamed.insert({topological_dim(b.type), t});
  for (const auto& [d, t] : unnamed) mesh.groups.push_back(PhysicalGroup{d, t, ""});
  return mesh;
}

}  // namespace meshmorph::detail

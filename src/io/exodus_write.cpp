// SPDX-License-Identifier: MIT
#include <exodusII.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "io/detail/exodus_writer.h"
#include "io/detail/library_file.h"
#include "meshmorph/error.h"
#include "meshmorph/io/exodus.h"
#include "meshmorph/io/solver_ordering.h"

namespace meshmorph {
namespace {

// Sorted corners of a facet or cell side, as a hash key.
std::string corner_key(std::vector<std::int32_t> corners) {
  std::sort(corners.begin(), corners.end());
  return {reinterpret_cast<const char*>(corners.data()), corners.size() * sizeof(std::int32_t)};
}

std::string checked_name(const std::string& name) {
  if (name.size() > MAX_STR_LENGTH)
    throw InputError("group name '" + name + "' is longer than the 32 characters an Exodus II name holds");
  return name;
}

// Puts the names of `n` entities of `type`, looked up by their ids.
void put_names(const detail::ExodusFile& f, ex_entity_type type, const std::vector<std::string>& names, const std::string& where) {
  if (names.empty()) return;
  detail::ExodusNames c(names);
  f.check(ex_put_names(f.id(), type, c.ptrs.data()), where);
}

}  // namespace

detail::ExodusNames::ExodusNames(const std::vector<std::string>& names) {
  for (const std::string& n : names) {
    buffers.emplace_back(n.begin(), n.end());
    buffers.back().push_back('\0');
  }
  for (auto& b : buffers) ptrs.push_back(b.data());
}

std::vector<detail::ExodusBlock> detail::write_exodus_mesh(const ExodusFile& f, const Mesh& mesh) {
  std::map<std::pair<int, std::int32_t>, std::string> group_name;
  for (const PhysicalGroup& g : mesh.groups) group_name[{g.dim, g.tag}] = checked_name(g.name);
  const auto name_of_group = [&](int dim, std::int32_t tag) {
    const auto it = group_name.find({dim, tag});
    return it == group_name.end() ? std::string() : it->second;
  };
  // Element blocks: cells, then the lines of a 3D mesh, each split by group.
  std::vector<ExodusBlock> blocks;
  int n_elements = 0;
  std::ptrdiff_t offset = 0;  // of the block's first cell in Mesh::cells; −1: facets
  const auto add_blocks = [&](const CellBlock& b) {
    if (exodus_element_name(b.type, b.order).empty())
      throw InputError("Exodus II has no " + std::string(name_of(b.type)) + " of order " + std::to_string(b.order) +
                       " (orders 1 and 2 only)");
    std::vector<std::int32_t> tags;
    for (const std::int32_t t : b.physical)
      if (std::find(tags.begin(), tags.end(), t) == tags.end()) tags.push_back(t);
    for (const std::int32_t t : tags) {
      blocks.push_back({&b, t, n_elements + 1, offset});
      n_elements += static_cast<int>(std::count(b.physical.begin(), b.physical.end(), t));
    }
  };
  for (const CellBlock& b : mesh.cells) {
    add_blocks(b);
    offset += static_cast<std::ptrdiff_t>(b.n_cells());
  }
  offset = -1;
  for (const CellBlock& b : mesh.facets)
    if (b.type == ElementType::Line && mesh.dim == 3) add_blocks(b);
  // Side sets: each facet of a group of dimension dim − 1 as the first (element, side) whose
  // corners are its own.
  std::unordered_map<std::string, std::array<int, 2>> side_of;
  for (const CellBlock& b : mesh.facets)
    if (topological_dim(b.type) == mesh.dim - 1)
      for (std::size_t c = 0; c < b.n_cells(); ++c)
        if (b.physical[c] != 0) side_of.emplace(corner_key({b.cell(c), b.cell(c) + n_corners_of(b.type)}), std::array{0, 0});
  for (const ExodusBlock& blk : blocks) {
    const CellBlock& b = *blk.cells;
    if (topological_dim(b.type) != mesh.dim || side_of.empty()) continue;
    const auto& sides = exodus_sides(b.type);
    int number = blk.first;
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      if (b.physical[c] != blk.tag) continue;
      for (std::size_t s = 0; s < sides.size(); ++s) {
        std::vector<std::int32_t> corners;
        for (const int i : sides[s]) corners.push_back(b.cell(c)[i]);
        const auto it = side_of.find(corner_key(corners));
        if (it != side_of.end() && it->second[0] == 0) it->second = {number, static_cast<int>(s) + 1};
      }
      ++number;
    }
  }
  std::map<std::int32_t, std::array<std::vector<int>, 2>> side_sets;  // tag → elements, sides
  std::map<std::int32_t, std::vector<int>> node_sets;                  // tag → nodes
  for (const CellBlock& b : mesh.facets)
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      if (b.physical[c] == 0) continue;
      if (b.type == ElementType::Point) {
        node_sets[b.physical[c]].push_back(b.cell(c)[0] + 1);
      } else if (topological_dim(b.type) == mesh.dim - 1) {
        const auto& where = side_of.at(corner_key({b.cell(c), b.cell(c) + n_corners_of(b.type)}));
        if (where[0] == 0) continue;  // on no cell's side
        side_sets[b.physical[c]][0].push_back(where[0]);
        side_sets[b.physical[c]][1].push_back(where[1]);
      }
    }

  f.check(ex_put_init(f.id(), "meshmorph", mesh.dim, static_cast<int64_t>(mesh.n_nodes()), n_elements,
                      static_cast<int64_t>(blocks.size()), static_cast<int64_t>(node_sets.size()),
                      static_cast<int64_t>(side_sets.size())),
          "header");
  std::array<std::vector<double>, 3> xyz;
  for (int k = 0; k < mesh.dim; ++k) xyz[k].assign(mesh.x.row(k).begin(), mesh.x.row(k).end());
  f.check(ex_put_coord(f.id(), xyz[0].data(), xyz[1].data(), mesh.dim == 3 ? xyz[2].data() : nullptr), "coordinates");
  std::vector<std::string> names;
  for (std::size_t i = 0; i < blocks.size(); ++i) {
    const CellBlock& b = *blocks[i].cells;
    const int id = static_cast<int>(i) + 1;
    const std::string where = "element block " + std::to_string(id);
    const auto n = std::count(b.physical.begin(), b.physical.end(), blocks[i].tag);
    f.check(ex_put_block(f.id(), EX_ELEM_BLOCK, id, exodus_element_name(b.type, b.order).c_str(), n, b.n_nodes_per_cell(), 0, 0, 0),
            where);
    const std::vector<int>& perm = exodus_to_gmsh_permutation(b.type, b.order);
    std::vector<int> conn;
    for (std::size_t c = 0; c < b.n_cells(); ++c)
      if (b.physical[c] == blocks[i].tag)
        for (const int k : perm) conn.push_back(b.cell(c)[k] + 1);
    f.check(ex_put_conn(f.id(), EX_ELEM_BLOCK, id, conn.data(), nullptr, nullptr), where);
    names.push_back(name_of_group(topological_dim(b.type), blocks[i].tag));
  }
  if (!blocks.empty()) {
    char group[] = "GROUP";
    char* props[] = {group};
    f.check(ex_put_prop_names(f.id(), EX_ELEM_BLOCK, 1, props), "element block properties");
    for (std::size_t i = 0; i < blocks.size(); ++i)
      f.check(ex_put_prop(f.id(), EX_ELEM_BLOCK, static_cast<int>(i) + 1, "GROUP", blocks[i].tag),
              "element block " + std::to_string(i + 1));
  }
  put_names(f, EX_ELEM_BLOCK, names, "element block names");
  names.clear();
  for (const auto& [tag, lists] : side_sets) {
    const std::string where = "side set " + std::to_string(tag);
    f.check(ex_put_set_param(f.id(), EX_SIDE_SET, tag, static_cast<int64_t>(lists[0].size()), 0), where);
    f.check(ex_put_set(f.id(), EX_SIDE_SET, tag, lists[0].data(), lists[1].data()), where);
    names.push_back(name_of_group(mesh.dim - 1, tag));
  }
  put_names(f, EX_SIDE_SET, names, "side set names");
  names.clear();
  for (const auto& [tag, nodes] : node_sets) {
    const std::string where = "node set " + std::to_string(tag);
    f.check(ex_put_set_param(f.id(), EX_NODE_SET, tag, static_cast<int64_t>(nodes.size()), 0), where);
    f.check(ex_put_set(f.id(), EX_NODE_SET, tag, nodes.data(), nullptr), where);
    names.push_back(name_of_group(0, tag));
  }
  put_names(f, EX_NODE_SET, names, "node set names");
  return blocks;
}

void write_exodus(const std::filesystem::path& file, const Mesh& mesh, const std::filesystem::path& shown,
                  const std::map<std::string, std::vector<double>>& cell_data,
                  const std::map<std::string, Eigen::MatrixXd>& point_vectors) {
  const std::lock_guard lock(detail::library_mutex());
  const detail::ExodusFile f(file, true, shown.string());
  const std::vector<detail::ExodusBlock> blocks = detail::write_exodus_mesh(f, mesh);
  // The coordinates are the mesh's own: an Exodus displacement would be added to them again.
  MeshStep fields{0.0, {}, cell_data, point_vectors};
  fields.point_vectors.erase("displacement");
  if (!fields.cell_data.empty() || !fields.point_vectors.empty())
    detail::write_exodus_steps(f, mesh, blocks, 1, [&](int) { return fields; }, false);
}

}  // namespace meshmorph

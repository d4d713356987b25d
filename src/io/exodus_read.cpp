// SPDX-License-Identifier: MIT
#include <exodusII.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <set>
#include <string>
#include <vector>

#include "io/detail/exodus_file.h"
#include "io/detail/library_file.h"
#include "io/detail/mesh_builder.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/io/exodus.h"
#include "meshmorph/io/solver_ordering.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {
namespace {

using detail::ExodusFile;

struct Element {
  ElementType type;
  int order;
  std::size_t cell;  ///< in the builder's block of (type, order)
};

// Ids and names of the entities of `type`.
std::vector<std::pair<int, std::string>> ids_and_names(const ExodusFile& f, ex_entity_type type, int n, const std::string& what) {
  std::vector<int> ids(static_cast<std::size_t>(n));
  if (n == 0) return {};
  f.check(ex_get_ids(f.id(), type, ids.data()), what + " ids");
  std::vector<std::array<char, 257>> buffers(ids.size());
  std::vector<char*> ptrs;
  for (auto& b : buffers) {
    b.fill('\0');
    ptrs.push_back(b.data());
  }
  f.check(ex_get_names(f.id(), type, ptrs.data()), what + " names");
  std::vector<std::pair<int, std::string>> out;
  for (std::size_t i = 0; i < ids.size(); ++i) out.emplace_back(ids[i], std::string(buffers[i].data()));
  return out;
}

// The local facet (corner_facets order) of a cell family that holds Exodus side `s` (0-based).
int facet_of_side(ElementType type, int s) {
  std::vector<int> side = exodus_sides(type)[static_cast<std::size_t>(s)];
  std::sort(side.begin(), side.end());
  const auto facets = corner_facets(type);
  for (std::size_t k = 0; k < facets.size(); ++k) {
    std::vector<int> c = facets[k];
    std::sort(c.begin(), c.end());
    if (c == side) return static_cast<int>(k);
  }
  return -1;
}

// A moving mesh (write_exodus_series) at its last time step: the coordinates plus the nodal
// variables displacement_x/_y(/_z) there, as ParaView shows it.
void add_last_displacement(const ExodusFile& f, int dim, int n_nodes, std::array<std::vector<double>, 3>& xyz) {
  const auto n_steps = static_cast<int>(ex_inquire_int(f.id(), EX_INQ_TIME));
  int n_vars = 0;
  if (n_steps < 1) return;
  f.check(ex_get_variable_param(f.id(), EX_NODAL, &n_vars), "nodal variables");
  std::vector<std::array<char, 257>> buffers(static_cast<std::size_t>(std::max(n_vars, 0)));
  std::vector<char*> ptrs;
  for (auto& buf : buffers) {
    buf.fill('\0');
    ptrs.push_back(buf.data());
  }
  if (n_vars > 0) f.check(ex_get_variable_names(f.id(), EX_NODAL, n_vars, ptrs.data()), "nodal variable names");
  static const char* const names[] = {"displacement_x", "displacement_y", "displacement_z"};
  std::array<int, 3> index{};
  for (int k = 0; k < dim; ++k) {
    for (int i = 0; i < n_vars; ++i)
      if (std::string(buffers[static_cast<std::size_t>(i)].data()) == names[k]) index[k] = i + 1;
    if (index[k] == 0) return;
  }
  std::vector<double> d(static_cast<std::size_t>(n_nodes));
  for (int k = 0; k < dim; ++k) {
    f.check(ex_get_var(f.id(), n_steps, EX_NODAL, index[k], 1, n_nodes, d.data()),
            "time step " + std::to_string(n_steps) + ": nodal variable " + names[k]);
    for (std::size_t j = 0; j < d.size(); ++j) xyz[k][j] += d[j];
  }
}

void add_group(detail::MeshBuilder& b, std::set<std::pair<int, std::int32_t>>& named, int dim, std::int32_t tag,
               const std::string& name) {
  if (tag != 0 && !name.empty() && named.insert({dim, tag}).second) b.named_groups.push_back({dim, tag, name});
}

}  // namespace

Mesh read_exodus(const std::filesystem::path& path) {
  const std::lock_guard lock(detail::library_mutex());
  const ExodusFile f(path, false, path.string());
  char title[MAX_LINE_LENGTH + 1] = {};
  int dim = 0, n_nodes = 0, n_elements = 0, n_blocks = 0, n_node_sets = 0, n_side_sets = 0;
  f.check(ex_get_init(f.id(), title, &dim, &n_nodes, &n_elements, &n_blocks, &n_node_sets, &n_side_sets), "header");
  if (dim < 2 || dim > 3) throw InputError(f.name() + ": header: dimension " + std::to_string(dim) + " (meshmorph reads 2 and 3)");
  if (n_nodes < 1) throw InputError(f.name() + ": header: no nodes");
  detail::MeshBuilder b;
  std::array<std::vector<double>, 3> xyz;
  for (auto& c : xyz) c.assign(static_cast<std::size_t>(n_nodes), 0.0);
  f.check(ex_get_coord(f.id(), xyz[0].data(), xyz[1].data(), dim == 3 ? xyz[2].data() : nullptr), "coordinates");
  add_last_displacement(f, dim, n_nodes, xyz);
  for (int j = 0; j < n_nodes; ++j) {
    b.tags.push_back(j + 1);
    for (int k = 0; k < 3; ++k) {
      const double v = xyz[k][static_cast<std::size_t>(j)];
      if (!std::isfinite(v))
        throw InputError(f.name() + ": coordinates: node " + std::to_string(j + 1) + " has a non-finite coordinate");
      b.xyz.push_back(v);
    }
    if (xyz[2][static_cast<std::size_t>(j)] != 0.0 && b.first_nonzero_z.empty())
      b.first_nonzero_z = f.name() + ": coordinates: node " + std::to_string(j + 1);
  }
  std::set<std::pair<int, std::int32_t>> named;
  // Element blocks: a block's group is its GROUP property where the file has one, else its id.
  bool has_group = false;
  if (n_blocks > 0) {
    const auto n_props = static_cast<int>(ex_inquire_int(f.id(), EX_INQ_EB_PROP));
    std::vector<std::array<char, 257>> buffers(static_cast<std::size_t>(std::max(n_props, 0)));
    std::vector<char*> ptrs;
    for (auto& buf : buffers) ptrs.push_back(buf.data());
    if (n_props > 0) f.check(ex_get_prop_names(f.id(), EX_ELEM_BLOCK, ptrs.data()), "element block properties");
    for (const auto& buf : buffers) has_group |= std::string(buf.data()) == "GROUP";
  }
  std::vector<Element> elements;
  for (const auto& [id, name] : ids_and_names(f, EX_ELEM_BLOCK, n_blocks, "element block")) {
    const std::string where = f.name() + ": element block " + std::to_string(id);
    char type_name[MAX_STR_LENGTH + 1] = {};
    int n = 0, npe = 0, n_edges = 0, n_faces = 0, n_attr = 0;
    f.check(ex_get_block(f.id(), EX_ELEM_BLOCK, id, type_name, &n, &npe, &n_edges, &n_faces, &n_attr),
            "element block " + std::to_string(id));
    const auto to = exodus_type_order(type_name, npe);
    if (!to)
      throw InputError(where + ": unsupported element type '" + type_name + "' with " + std::to_string(npe) +
                       " nodes (linear and complete quadratic elements only)");
    const auto [type, order] = *to;
    int tag = id;
    if (has_group) f.check(ex_get_prop(f.id(), EX_ELEM_BLOCK, id, "GROUP", &tag), "element block " + std::to_string(id));
    add_group(b, named, topological_dim(type), tag, name);
    std::vector<int> conn(static_cast<std::size_t>(n) * static_cast<std::size_t>(npe));
    if (n > 0) f.check(ex_get_conn(f.id(), EX_ELEM_BLOCK, id, conn.data(), nullptr, nullptr), "element block " + std::to_string(id));
    const std::vector<int>& perm = exodus_to_gmsh_permutation(type, order);
    std::vector<std::int32_t> cell(perm.size());
    CellBlock* blk = &b.block(type, order);
    for (int e = 0; e < n; ++e) {
      for (std::size_t i = 0; i < perm.size(); ++i) {
        const int v = conn[static_cast<std::size_t>(e) * perm.size() + i];
        if (v < 1 || v > n_nodes)
          throw InputError(where + ": element " + std::to_string(e + 1) + " references node " + std::to_string(v) + ", outside 1.." +
                           std::to_string(n_nodes));
        cell[static_cast<std::size_t>(perm[i])] = v - 1;
      }
      if (const int k = detail::repeated_node(cell.data(), static_cast<int>(cell.size())); k >= 0)
        throw InputError(where + ": element " + std::to_string(e + 1) + " lists node " + std::to_string(cell[k] + 1) +
                         " twice (a degenerate element)");
      elements.push_back({type, order, blk->n_cells()});
      blk->push_back(cell.data(), tag);
    }
  }
  if (static_cast<int>(elements.size()) != n_elements)
    throw InputError(f.name() + ": header: announces " + std::to_string(n_elements) + " elements but the blocks hold " +
                     std::to_string(elements.size()));
  // Side sets: each (element, side) the side's nodes, as the cell's trace gives them.
  for (const auto& [id, name] : ids_and_names(f, EX_SIDE_SET, n_side_sets, "side set")) {
    const std::string where = f.name() + ": side set " + std::to_string(id);
    int n = 0, n_df = 0;
    f.check(ex_get_set_param(f.id(), EX_SIDE_SET, id, &n, &n_df), "side set " + std::to_string(id));
    std::vector<int> elems(static_cast<std::size_t>(n)), sides(static_cast<std::size_t>(n));
    if (n > 0) f.check(ex_get_set(f.id(), EX_SIDE_SET, id, elems.data(), sides.data()), "side set " + std::to_string(id));
    for (int i = 0; i < n; ++i) {
      const int e = elems[static_cast<std::size_t>(i)], s = sides[static_cast<std::size_t>(i)];
      if (e < 1 || e > n_elements)
        throw InputError(where + ": entry " + std::to_string(i + 1) + " names element " + std::to_string(e) + ", outside 1.." +
                         std::to_string(n_elements));
      const Element& el = elements[static_cast<std::size_t>(e - 1)];
      const int n_sides = static_cast<int>(exodus_sides(el.type).size());
      if (topological_dim(el.type) < 2 || s < 1 || s > n_sides)
        throw InputError(where + ": entry " + std::to_string(i + 1) + ": side " + std::to_string(s) + " of element " +
                         std::to_string(e) + " (a " + std::string(name_of(el.type)) + ") is not among its " +
                         std::to_string(n_sides) + " sides");
      const int local = facet_of_side(el.type, s - 1);
      const ReferenceElement& ref = reference_element(el.type, el.order);
      const std::vector<int>& trace = ref.facet_nodes[static_cast<std::size_t>(local)];
      std::vector<std::int32_t> facet;
      for (const int k : trace) facet.push_back(b.block(el.type, el.order).cell(el.cell)[k]);
      const ElementType ft = facet_type(el.type, local);
      b.block(ft, el.order).push_back(facet.data(), id);
      add_group(b, named, topological_dim(ft), id, name);
    }
  }
  for (const auto& [id, name] : ids_and_names(f, EX_NODE_SET, n_node_sets, "node set")) {
    int n = 0, n_df = 0;
    f.check(ex_get_set_param(f.id(), EX_NODE_SET, id, &n, &n_df), "node set " + std::to_string(id));
    std::vector<int> nodes(static_cast<std::size_t>(n));
    if (n > 0) f.check(ex_get_set(f.id(), EX_NODE_SET, id, nodes.data(), nullptr), "node set " + std::to_string(id));
    for (int i = 0; i < n; ++i) {
      const int v = nodes[static_cast<std::size_t>(i)];
      if (v < 1 || v > n_nodes)
        throw InputError(f.name() + ": node set " + std::to_string(id) + ": entry " + std::to_string(i + 1) + " names node " +
                         std::to_string(v) + ", outside 1.." + std::to_string(n_nodes));
      const std::int32_t node = v - 1;
      b.block(ElementType::Point, 1).push_back(&node, id);
    }
    add_group(b, named, 0, id, name);
  }
  return b.finish(f.name() + ": header");
}

}  // namespace meshmorph

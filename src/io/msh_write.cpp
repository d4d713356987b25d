// SPDX-License-Identifier: MIT
#include "meshmorph/io/msh.h"

#include <algorithm>
#include <array>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "io/detail/gmsh_types.h"
#include "io/detail/out_buffer.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

// A maximal run of consecutive cells of one block with the same (entity, physical) tags;
// it becomes one element block of the file.
struct Run {
  const CellBlock* block;
  std::size_t begin, end;
  int dim;
  std::int32_t entity;  // as written (possibly renumbered)
  std::int32_t physical;
};

struct Entity {
  int dim;
  std::int32_t tag;
  std::int32_t physical;
  std::array<double, 6> box{std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
                            std::numeric_limits<double>::max(), std::numeric_limits<double>::lowest(),
                            std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
};

std::int32_t tag_at(const std::vector<std::int32_t>& v, std::size_t i) { return i < v.size() ? v[i] : 0; }

double coord(const Mesh& mesh, std::int32_t node, int k) {
  return k < mesh.dim ? mesh.x(k, node) : 0.0;
}

struct Layout {
  std::vector<Run> runs;
  std::vector<Entity> entities;  // sorted by dim, in first-use order within a dim
  int node_entity_dim = 0;
  std::int32_t node_entity_tag = 0;
};

Layout layout_of(const Mesh& mesh) {
  Layout L;
  for (const auto* list : {&mesh.facets, &mesh.cells})
    for (const CellBlock& b : *list) {
      const std::size_t n = b.n_cells();
      for (std::size_t c = 0; c < n;) {
        std::size_t e = c + 1;
        while (e < n && tag_at(b.entity, e) == tag_at(b.entity, c) && tag_at(b.physical, e) == tag_at(b.physical, c)) ++e;
        L.runs.push_back(Run{&b, c, e, topological_dim(b.type), tag_at(b.entity, c), tag_at(b.physical, c)});
        c = e;
      }
    }
  // Per dimension: keep the entity tags when each one carries a single physical tag.
  for (int d = 0; d <= 3; ++d) {
    std::vector<std::pair<std::int32_t, std::int32_t>> pairs;  // (entity, physical), first use order
    for (const Run& r : L.runs)
      if (r.dim == d && std::find(pairs.begin(), pairs.end(), std::make_pair(r.entity, r.physical)) == pairs.end())
        pairs.emplace_back(r.entity, r.physical);
    bool keep = true;
    for (std::size_t i = 0; i < pairs.size() && keep; ++i) {
      keep = pairs[i].first > 0;
      for (std::size_t j = 0; j < i && keep; ++j) keep = pairs[j].first != pairs[i].first;
    }
    std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> tag_of;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const std::int32_t tag = keep ? pairs[i].first : static_cast<std::int32_t>(i + 1);
      tag_of[pairs[i]] = tag;
      L.entities.push_back(Entity{d, tag, pairs[i].second});
    }
    for (Run& r : L.runs)
      if (r.dim == d) r.entity = tag_of[{r.entity, r.physical}];
  }
  // Bounding boxes.
  for (const Run& r : L.runs) {
    Entity& ent = *std::find_if(L.entities.begin(), L.entities.end(),
                                [&](const Entity& e) { return e.dim == r.dim && e.tag == r.entity; });
    const int k = r.block->n_nodes_per_cell();
    for (std::size_t c = r.begin; c < r.end; ++c)
      for (int j = 0; j < k; ++j)
        for (int a = 0; a < 3; ++a) {
          const double v = coord(mesh, r.block->cell(c)[j], a);
          ent.box[a] = std::min(ent.box[a], v);
          ent.box[3 + a] = std::max(ent.box[3 + a], v);
        }
  }
  // All nodes go in one block on the first entity of the highest dimension.
  L.node_entity_dim = mesh.dim;
  for (const Entity& e : L.entities)
    if (e.dim == mesh.dim) {
      L.node_entity_tag = e.tag;
      break;
    }
  if (L.node_entity_tag == 0) {
    L.entities.push_back(Entity{mesh.dim, 1, 0, {0, 0, 0, 0, 0, 0}});
    L.node_entity_tag = 1;
  }
  for (Entity& e : L.entities)
    if (e.box[0] > e.box[3]) e.box = {0, 0, 0, 0, 0, 0};
  return L;
}

std::int64_t node_tag(const Mesh& mesh, std::size_t i) {
  return mesh.node_tags.size() == mesh.n_nodes() ? mesh.node_tags[i] : static_cast<std::int64_t>(i + 1);
}

void write_header(detail::OutBuffer& o, const Mesh& mesh, int version, bool binary) {
  o << "$MeshFormat\n" << (version == 41 ? "4.1" : "2.2") << (binary ? " 1 8\n" : " 0 8\n");
  if (binary) {
    o.raw(std::int32_t{1});
    o << '\n';
  }
  o << "$EndMeshFormat\n";
  std::size_t named = 0;
  for (const PhysicalGroup& g : mesh.groups) named += g.name.empty() ? 0 : 1;
  if (named == 0) return;
  o << "$PhysicalNames\n" << named << '\n';
  for (const PhysicalGroup& g : mesh.groups)
    if (!g.name.empty()) o << g.dim << ' ' << g.tag << " \"" << g.name << "\"\n";
  o << "$EndPhysicalNames\n";
}

void write_entities41(detail::OutBuffer& o, const Layout& L, bool binary) {
  std::array<std::uint64_t, 4> n{};
  for (const Entity& e : L.entities) ++n[static_cast<std::size_t>(e.dim)];
  o << "$Entities\n";
  if (binary) {
    for (auto v : n) o.raw(v);
  } else {
    o << n[0] << ' ' << n[1] << ' ' << n[2] << ' ' << n[3] << '\n';
  }
  for (int d = 0; d <= 3; ++d)
    for (const Entity& e : L.entities) {
      if (e.dim != d) continue;
      const int n_box = d == 0 ? 3 : 6;
      const std::uint64_t n_phys = e.physical != 0 ? 1 : 0;
      if (binary) {
        o.raw(e.tag);
        for (int k = 0; k < n_box; ++k) o.raw(e.box[static_cast<std::size_t>(k)]);
        o.raw(n_phys);
        if (n_phys) o.raw(e.physical);
        if (d > 0) o.raw(std::uint64_t{0});
      } else {
        o << e.tag;
        for (int k = 0; k < n_box; ++k) o << ' ' << e.box[static_cast<std::size_t>(k)];
        o << ' ' << n_phys;
        if (n_phys) o << ' ' << e.physical;
        if (d > 0) o << " 0";
        o << '\n';
      }
    }
  if (binary) o << '\n';
  o << "$EndEntities\n";
}

void write_nodes41(detail::OutBuffer& o, const Mesh& mesh, const Layout& L, bool binary) {
  const std::size_t n = mesh.n_nodes();
  std::int64_t lo = n ? node_tag(mesh, 0) : 0, hi = lo;
  for (std::size_t i = 0; i < n; ++i) {
    lo = std::min(lo, node_tag(mesh, i));
    hi = std::max(hi, node_tag(mesh, i));
  }
  o << "$Nodes\n";
  if (binary) {
    for (auto v : {std::uint64_t{1}, std::uint64_t{n}, static_cast<std::uint64_t>(lo), static_cast<std::uint64_t>(hi)}) o.raw(v);
    o.raw(std::int32_t{L.node_entity_dim});
    o.raw(L.node_entity_tag);
    o.raw(std::int32_t{0});
    o.raw(std::uint64_t{n});
    for (std::size_t i = 0; i < n; ++i) o.raw(static_cast<std::uint64_t>(node_tag(mesh, i)));
    for (std::size_t i = 0; i < n; ++i)
      for (int k = 0; k < 3; ++k) o.raw(coord(mesh, static_cast<std::int32_t>(i), k));
    o << '\n';
  } else {
    o << "1 " << n << ' ' << lo << ' ' << hi << '\n';
    o << L.node_entity_dim << ' ' << L.node_entity_tag << " 0 " << n << '\n';
    for (std::size_t i = 0; i < n; ++i) o << node_tag(mesh, i) << '\n';
    for (std::size_t i = 0; i < n; ++i) {
      const auto j = static_cast<std::int32_t>(i);
      o << coord(mesh, j, 0) << ' ' << coord(mesh, j, 1) << ' ' << coord(mesh, j, 2) << '\n';
    }
  }
  o << "$EndNodes\n";
}

void write_elements41(detail::OutBuffer& o, const Mesh& mesh, const Layout& L, bool binary) {
  std::uint64_t total = 0;
  for (const Run& r : L.runs) total += r.end - r.begin;
  o << "$Elements\n";
  if (binary) {
    for (auto v : {std::uint64_t{L.runs.size()}, total, std::uint64_t{total ? 1u : 0u}, total}) o.raw(v);
  } else {
    o << L.runs.size() << ' ' << total << ' ' << (total ? 1 : 0) << ' ' << total << '\n';
  }
  std::uint64_t tag = 1;
  for (const Run& r : L.runs) {
    const int code = detail::gmsh_type_of(r.block->type, r.block->order);
    const int k = r.block->n_nodes_per_cell();
    if (binary) {
      o.raw(std::int32_t{r.dim});
      o.raw(r.entity);
      o.raw(std::int32_t{code});
      o.raw(std::uint64_t{r.end - r.begin});
    } else {
      o << r.dim << ' ' << r.entity << ' ' << code << ' ' << (r.end - r.begin) << '\n';
    }
    for (std::size_t c = r.begin; c < r.end; ++c, ++tag) {
      const std::int32_t* nodes = r.block->cell(c);
      if (binary) {
        o.raw(tag);
        for (int j = 0; j < k; ++j) o.raw(static_cast<std::uint64_t>(node_tag(mesh, static_cast<std::size_t>(nodes[j]))));
      } else {
        o << tag;
        for (int j = 0; j < k; ++j) o << ' ' << node_tag(mesh, static_cast<std::size_t>(nodes[j]));
        o << '\n';
      }
    }
  }
  if (binary) o << '\n';
  o << "$EndElements\n";
}

void write_msh22(detail::OutBuffer& o, const Mesh& mesh, const Layout& L, bool binary) {
  const std::size_t n = mesh.n_nodes();
  for (std::size_t i = 0; i < n; ++i)
    if (node_tag(mesh, i) > std::numeric_limits<std::int32_t>::max() || node_tag(mesh, i) <= 0)
      throw InputError("MSH 2.2 holds node tags 1..2^31-1 only; node tag " + std::to_string(node_tag(mesh, i)));
  o << "$Nodes\n" << n << '\n';
  for (std::size_t i = 0; i < n; ++i) {
    const auto j = static_cast<std::int32_t>(i);
    if (binary) {
      o.raw(static_cast<std::int32_t>(node_tag(mesh, i)));
      for (int k = 0; k < 3; ++k) o.raw(coord(mesh, j, k));
    } else {
      o << node_tag(mesh, i) << ' ' << coord(mesh, j, 0) << ' ' << coord(mesh, j, 1) << ' ' << coord(mesh, j, 2) << '\n';
    }
  }
  if (binary) o << '\n';
  o << "$EndNodes\n";
  std::uint64_t total = 0;
  for (const Run& r : L.runs) total += r.end - r.begin;
  o << "$Elements\n" << total << '\n';
  std::int32_t tag = 1;
  for (const Run& r : L.runs) {
    const int code = detail::gmsh_type_of(r.block->type, r.block->order);
    const int k = r.block->n_nodes_per_cell();
    if (binary) {
      o.raw(std::int32_t{code});
      o.raw(static_cast<std::int32_t>(r.end - r.begin));
      o.raw(std::int32_t{2});
    }
    for (std::size_t c = r.begin; c < r.end; ++c, ++tag) {
      const std::int32_t* nodes = r.block->cell(c);
      if (binary) {
        for (std::int32_t v : {tag, r.physical, r.entity}) o.raw(v);
        for (int j = 0; j < k; ++j) o.raw(static_cast<std::int32_t>(node_tag(mesh, static_cast<std::size_t>(nodes[j]))));
      } else {
        o << tag << ' ' << code << " 2 " << r.physical << ' ' << r.entity;
        for (int j = 0; j < k; ++j) o << ' ' << node_tag(mesh, static_cast<std::size_t>(nodes[j]));
        o << '\n';
      }
    }
  }
  if (binary) o << '\n';
  o << "$EndElements\n";
}

// Fails before anything is written when a node field cannot be stored.
void check_node_fields(const Mesh& mesh, bool binary) {
  for (const auto& [name, values] : mesh.node_fields) {
    MESHMORPH_CHECK(static_cast<std::size_t>(values.size()) == mesh.n_nodes(),
                    "write_msh: node field '" + name + "' has " + std::to_string(values.size()) + " values for " +
                        std::to_string(mesh.n_nodes()) + " nodes");
    if (name.empty() || name.find_first_of("\"\n\r") != std::string::npos)
      throw InputError("MSH $NodeData cannot hold the node field name '" + name + "' (empty, or with a quote or line break)");
  }
  if (!binary || mesh.node_fields.empty()) return;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (node_tag(mesh, i) > std::numeric_limits<std::int32_t>::max())
      throw InputError("binary MSH $NodeData holds node tags up to 2^31-1 only (Gmsh writes them as int); node tag " +
                       std::to_string(node_tag(mesh, i)));
}

// One $NodeData section per field, laid out as Gmsh writes it: one header item per line,
// time step 0 at time 0, then (tag, value) records; binary tags are int32, as in Gmsh.
void write_node_data(detail::OutBuffer& o, const Mesh& mesh, bool binary) {
  const std::size_t n = mesh.n_nodes();
  for (const auto& [name, values] : mesh.node_fields) {
    o << "$NodeData\n1\n\"" << name << "\"\n1\n0\n3\n0\n1\n" << n << '\n';
    for (std::size_t i = 0; i < n; ++i) {
      const double v = values(static_cast<Eigen::Index>(i));
      if (binary) {
        o.raw(static_cast<std::int32_t>(node_tag(mesh, i)));
        o.raw(v);
      } else {
        o << node_tag(mesh, i) << ' ' << v << '\n';
      }
    }
    if (binary) o << '\n';
    o << "$EndNodeData\n";
  }
}

// The header of a $NodeData or $ElementData section as Gmsh writes it: time step 0 at time 0.
void data_header(detail::OutBuffer& o, const std::string& section, const std::string& name, int components,
                 std::size_t n) {
  if (name.empty() || name.find_first_of("\"\n\r") != std::string::npos)
    throw InputError("MSH $" + section + " cannot hold the name '" + name + "' (empty, or with a quote or line break)");
  o << '$' << section << "\n1\n\"" << name << "\"\n1\n0\n3\n0\n" << components << '\n' << n << '\n';
}

// Vectors as $NodeData of 3 components (z = 0 in 2D), in the layout of write_node_data.
void write_point_vectors(detail::OutBuffer& o, const Mesh& mesh, bool binary,
                         const std::map<std::string, Eigen::MatrixXd>& vectors) {
  for (const auto& [name, v] : vectors) {
    MESHMORPH_CHECK(v.rows() == mesh.dim && static_cast<std::size_t>(v.cols()) == mesh.n_nodes(),
                    "write_msh: point vectors '" + name + "' are not dim × n_nodes");
    data_header(o, "NodeData", name, 3, mesh.n_nodes());
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
      const auto j = static_cast<Eigen::Index>(i);
      const double c[3] = {v(0, j), mesh.dim > 1 ? v(1, j) : 0.0, mesh.dim > 2 ? v(2, j) : 0.0};
      if (binary) {
        o.raw(static_cast<std::int32_t>(node_tag(mesh, i)));
        for (const double x : c) o.raw(x);
      } else {
        o << node_tag(mesh, i) << ' ' << c[0] << ' ' << c[1] << ' ' << c[2] << '\n';
      }
    }
    if (binary) o << '\n';
    o << "$EndNodeData\n";
  }
}

// Per-cell values as $ElementData under the element tags the writers give (1, 2, … in the
// order of the layout's runs); facets get NaN, as in VTU, so that every element has a value
// (meshio refuses data that leaves elements out).
void write_element_data(detail::OutBuffer& o, const Mesh& mesh, const Layout& L, bool binary,
                        const std::map<std::string, std::vector<double>>& cell_data) {
  std::map<const CellBlock*, std::size_t> first;  // index of a cell block's first cell
  std::size_t n_cells = 0;
  for (const CellBlock& b : mesh.cells) first[&b] = std::exchange(n_cells, n_cells + b.n_cells());
  for (const auto& [name, values] : cell_data) {
    MESHMORPH_CHECK(values.size() == n_cells, "write_msh: cell data '" + name + "' has " + std::to_string(values.size()) +
                                                  " values for " + std::to_string(n_cells) + " cells");
    std::size_t n_elements = 0;
    for (const Run& r : L.runs) n_elements += r.end - r.begin;
    data_header(o, "ElementData", name, 1, n_elements);
    std::int64_t tag = 1;
    for (const Run& r : L.runs) {
      const auto block = first.find(r.block);
      for (std::size_t c = r.begin; c < r.end; ++c, ++tag) {
        const double v = block == first.end() ? std::numeric_limits<double>::quiet_NaN() : values[block->second + c];
        if (binary) {
          o.raw(static_cast<std::int32_t>(tag));
          o.raw(v);
        } else {
          o << tag << ' ' << v << '\n';
        }
      }
    }
    if (binary) o << '\n';
    o << "$EndElementData\n";
  }
}

}  // namespace

void write_msh(std::ostream& out, const Mesh& mesh, int version, bool binary,
               const std::map<std::string, std::vector<double>>& cell_data,
               const std::map<std::string, Eigen::MatrixXd>& point_vectors) {
  MESHMORPH_CHECK(version == 41 || version == 22, "write_msh: version must be 41 or 22");
  check_node_fields(mesh, binary);
  for (const auto& [name, v] : point_vectors)
    if (name.empty() || name.find_first_of("\"\n\r") != std::string::npos)
      throw InputError("MSH $NodeData cannot hold the name '" + name + "' (empty, or with a quote or line break)");
  for (const auto& [name, v] : cell_data)
    if (name.empty() || name.find_first_of("\"\n\r") != std::string::npos)
      throw InputError("MSH $ElementData cannot hold the name '" + name + "' (empty, or with a quote or line break)");
  const Layout L = layout_of(mesh);
  detail::OutBuffer o(out);
  write_header(o, mesh, version, binary);
  if (version == 41) {
    write_entities41(o, L, binary);
    write_nodes41(o, mesh, L, binary);
    write_elements41(o, mesh, L, binary);
  } else {
    write_msh22(o, mesh, L, binary);
  }
  write_node_data(o, mesh, binary);
  write_point_vectors(o, mesh, binary, point_vectors);
  write_element_data(o, mesh, L, binary, cell_data);
  o.flush();
}

}  // namespace meshmorph

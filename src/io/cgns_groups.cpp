// SPDX-License-Identifier: MIT
#include <cgnslib.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

#include "io/detail/cgns_reader.h"
#include "meshmorph/error.h"

namespace meshmorph::detail {
namespace {

struct Family {
  int ordinal = 0;
  bool unnamed = false;
};

// A BC_t or ZoneSubRegion_t: the elements or (at Vertex) nodes it lists.
struct PointSet {
  std::string where;  ///< "file: node /Base/Zone/ZoneBC/wall"
  std::string name;   ///< its FamilyName, else its own name
  const CgnsZone* zone = nullptr;
  bool vertex = false;
  bool points = false;  ///< a Vertex sub-region: its nodes are points, whatever facets hold them
  std::vector<cgsize_t> ids;
};

std::map<std::string, Family> read_families(const CgnsFile& f) {
  std::map<std::string, Family> out;
  int n = 0;
  f.check(cg_nfamilies(f.fn(), 1, &n), "node /Base");
  for (int i = 1; i <= n; ++i) {
    char name[33] = {};
    int nbc = 0, ngeo = 0, nd = 0;
    f.check(cg_family_read(f.fn(), 1, i, name, &nbc, &ngeo), "node /Base/Family_t " + std::to_string(i));
    Family fam;
    f.check(cg_goto(f.fn(), 1, "Family_t", i, "end"), std::string("node /Base/") + name);
    if (cg_ordinal_read(&fam.ordinal) != CG_OK) fam.ordinal = 0;
    if (cg_ndescriptors(&nd) == CG_OK)
      for (int d = 1; d <= nd; ++d) {
        char dname[33] = {};
        char* text = nullptr;
        if (cg_descriptor_read(d, dname, &text) != CG_OK) continue;
        fam.unnamed |= std::string(dname) == "meshmorph" && text && std::string(text) == "unnamed";
        cg_free(text);
      }
    out[name] = fam;
  }
  return out;
}

// The FamilyName under the node cg_goto went to, or `fallback`.
std::string family_or(const std::string& fallback) {
  char name[33] = {};
  return cg_famname_read(name) == CG_OK ? std::string(name) : fallback;
}

void expand(PointSet& s, PointSetType_t type) {
  if (type == PointList || type == ElementList) return;
  if (type != PointRange && type != ElementRange)
    throw InputError(s.where + ": unsupported point set type " + cg_PointSetTypeName(type));
  if (s.ids.size() != 2 || s.ids[1] < s.ids[0] || s.ids[1] - s.ids[0] > (cgsize_t{1} << 30))
    throw InputError(s.where + ": a range needs two numbers, first ≤ last");
  const cgsize_t lo = s.ids[0], hi = s.ids[1];
  s.ids.clear();
  for (cgsize_t i = lo; i <= hi; ++i) s.ids.push_back(i);
}

std::vector<PointSet> read_point_sets(const CgnsFile& f, const CgnsZone& z) {
  std::vector<PointSet> out;
  int nbc = 0, nsub = 0;
  f.check(cg_nbocos(f.fn(), z.base, z.zone, &nbc), "node " + z.path + "/ZoneBC");
  for (int i = 1; i <= nbc; ++i) {
    char name[33] = {};
    BCType_t bctype{};
    PointSetType_t pt{};
    cgsize_t n = 0, normal_size = 0;
    int normal_index[3] = {}, ndataset = 0;
    DataType_t normal_type{};
    GridLocation_t location{};
    const std::string at = "node " + z.path + "/ZoneBC/BC_t " + std::to_string(i);
    f.check(cg_boco_info(f.fn(), z.base, z.zone, i, name, &bctype, &pt, &n, normal_index, &normal_size, &normal_type, &ndataset), at);
    PointSet s{f.name() + ": node " + z.path + "/ZoneBC/" + name, name, &z, false, false, std::vector<cgsize_t>(static_cast<std::size_t>(std::max<cgsize_t>(n, 0)))};
    f.check(cg_boco_read(f.fn(), z.base, z.zone, i, s.ids.data(), nullptr), at);
    f.check(cg_boco_gridlocation_read(f.fn(), z.base, z.zone, i, &location), at);
    s.vertex = location == Vertex && pt != ElementList && pt != ElementRange;
    f.check(cg_goto(f.fn(), z.base, "Zone_t", z.zone, "ZoneBC_t", 1, "BC_t", i, "end"), at);
    s.name = family_or(name);
    expand(s, pt);
    out.push_back(std::move(s));
  }
  f.check(cg_nsubregs(f.fn(), z.base, z.zone, &nsub), "node " + z.path);
  for (int i = 1; i <= nsub; ++i) {
    char name[33] = {};
    int dim = 0, bclen = 0, gclen = 0;
    GridLocation_t location{};
    PointSetType_t pt{};
    cgsize_t n = 0;
    const std::string at = "node " + z.path + "/ZoneSubRegion_t " + std::to_string(i);
    f.check(cg_subreg_info(f.fn(), z.base, z.zone, i, name, &dim, &location, &pt, &n, &bclen, &gclen), at);
    if (bclen > 0 || gclen > 0) continue;  // the region of a BC or connectivity, read there
    PointSet s{f.name() + ": node " + z.path + "/" + name, name, &z, location == Vertex, location == Vertex, std::vector<cgsize_t>(static_cast<std::size_t>(std::max<cgsize_t>(n, 0)))};
    f.check(cg_subreg_ptset_read(f.fn(), z.base, z.zone, i, s.ids.data()), at);
    f.check(cg_goto(f.fn(), z.base, "Zone_t", z.zone, "ZoneSubRegion_t", i, "end"), at);
    s.name = family_or(name);
    expand(s, pt);
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace

void read_cgns_groups(const CgnsFile& f, MeshBuilder& b, const std::vector<CgnsZone>& zones, int cell_dim) {
  const std::map<std::string, Family> families = read_families(f);
  std::vector<PointSet> sets;
  for (const CgnsZone& z : zones) {
    std::vector<PointSet> more = read_point_sets(f, z);
    sets.insert(sets.end(), std::make_move_iterator(more.begin()), std::make_move_iterator(more.end()));
  }
  if (sets.empty())  // no BC: the facet sections are the groups
    for (const CgnsZone& z : zones)
      for (const CgnsZone::Section& s : z.sections)
        if (!s.elements.empty() && topological_dim(s.elements[0].type) < cell_dim) {
          PointSet p{f.name() + ": node " + z.path + "/" + s.name, s.name, &z, false, false, {}};
          for (cgsize_t e = s.start; e <= s.end; ++e) p.ids.push_back(e);
          sets.push_back(std::move(p));
        }
  // Tags: a family's ordinal where it is free in its dimension, then the next free numbers.
  std::map<std::pair<int, std::string>, std::int32_t> tag_of;
  std::map<int, std::vector<std::int32_t>> used;
  const auto tag = [&](int dim, const std::string& name) {
    const auto key = std::pair{dim, name};
    if (const auto it = tag_of.find(key); it != tag_of.end()) return it->second;
    std::vector<std::int32_t>& taken = used[dim];
    const auto fam = families.find(name);
    std::int32_t t = fam != families.end() ? fam->second.ordinal : 0;
    if (t <= 0 || std::find(taken.begin(), taken.end(), t) != taken.end())
      t = taken.empty() ? 1 : *std::max_element(taken.begin(), taken.end()) + 1;
    taken.push_back(t);
    tag_of[key] = t;
    const bool unnamed = fam != families.end() && fam->second.unnamed;
    b.named_groups.push_back({dim, t, unnamed ? std::string() : name});
    return t;
  };
  // Reserve the ordinals of the families first, so that no name takes another's number.
  for (const PointSet& s : sets)
    if (const auto fam = families.find(s.name); fam != families.end() && fam->second.ordinal > 0 && !s.vertex && !s.ids.empty())
      if (const CgnsElement* e = s.zone->find(s.ids[0])) tag(topological_dim(e->type), s.name);
  for (const PointSet& s : sets) {
    if (!s.vertex) {
      for (const cgsize_t id : s.ids) {
        const CgnsElement* e = s.zone->find(id);
        if (!e) throw InputError(s.where + ": element " + std::to_string(id) + " is in no element section");
        const int dim = topological_dim(e->type);
        const std::int32_t t = tag(dim, s.name);
        std::int32_t& phys = b.block(e->type, e->order).physical[e->cell];
        if (phys == 0) phys = t;
        else if (phys != t && dim < cell_dim) b.extra_physical.push_back({e->type, e->order, e->cell, t});
      }
      continue;
    }
    // At Vertex: the facets of dimension cell_dim − 1 whose nodes it holds all, else points.
    std::vector<bool> in(b.tags.size(), false);
    for (const cgsize_t id : s.ids) {
      if (id < 1 || id > static_cast<cgsize_t>(s.zone->node.size()))
        throw InputError(s.where + ": node " + std::to_string(id) + " is outside 1.." + std::to_string(s.zone->node.size()));
      in[static_cast<std::size_t>(s.zone->node[static_cast<std::size_t>(id - 1)])] = true;
    }
    bool any = false;
    for (const CgnsZone::Section& sec : s.zone->sections)
      for (const CgnsElement& e : sec.elements) {
        if (s.points || topological_dim(e.type) != cell_dim - 1) continue;
        CellBlock& blk = b.block(e.type, e.order);
        const std::int32_t* nodes = blk.cell(e.cell);
        if (!std::all_of(nodes, nodes + blk.n_nodes_per_cell(), [&](std::int32_t v) { return in[static_cast<std::size_t>(v)]; }))
          continue;
        any = true;
        const std::int32_t t = tag(cell_dim - 1, s.name);
        if (blk.physical[e.cell] == 0) blk.physical[e.cell] = t;
        else if (blk.physical[e.cell] != t) b.extra_physical.push_back({e.type, e.order, e.cell, t});
      }
    if (any) continue;
    for (const cgsize_t id : s.ids) {
      const std::int32_t v = s.zone->node[static_cast<std::size_t>(id - 1)];
      b.block(ElementType::Point, 1).push_back(&v, tag(0, s.name));
    }
  }
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#include <cgnslib.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "io/detail/cgns_writer.h"
#include "io/detail/library_file.h"
#include "meshmorph/error.h"
#include "meshmorph/io/cgns.h"
#include "meshmorph/io/solver_ordering.h"

namespace meshmorph {
namespace {

std::string family_name(const PhysicalGroup& g) {
  return g.name.empty() ? "group_" + std::to_string(g.dim) + "_" + std::to_string(g.tag) : g.name;
}

// The groups: those of the mesh, then the tags its elements use without a group.
std::vector<PhysicalGroup> all_groups(const Mesh& mesh) {
  std::vector<PhysicalGroup> out = mesh.groups;
  std::set<std::pair<int, std::int32_t>> known;
  for (const PhysicalGroup& g : out) known.insert({g.dim, g.tag});
  for (const auto* list : {&mesh.cells, &mesh.facets})
    for (const CellBlock& b : *list)
      for (const std::int32_t t : b.physical)
        if (t != 0 && known.insert({topological_dim(b.type), t}).second) out.push_back({topological_dim(b.type), t, ""});
  return out;
}

// The families of the groups, checked against what CGNS names can hold.
std::map<std::pair<int, std::int32_t>, std::string> families(const std::vector<PhysicalGroup>& groups) {
  std::map<std::pair<int, std::int32_t>, std::string> out;
  std::set<std::string> taken;
  for (const PhysicalGroup& g : groups) {
    const std::string name = family_name(g);
    if (name.size() > 32)
      throw InputError("group name '" + name + "' is longer than the 32 characters a CGNS name holds");
    if (name.find('/') != std::string::npos || name == "." || name == "..")
      throw InputError("group name '" + name + "' is no CGNS name ('/', '.' and '..' are paths)");
    if (!taken.insert(name).second) throw InputError("two groups are named '" + name + "', which CGNS families cannot be");
    out[{g.dim, g.tag}] = name;
  }
  return out;
}

}  // namespace

std::pair<int, int> detail::write_cgns_mesh(const CgnsFile& f, const Mesh& mesh) {
  const std::vector<PhysicalGroup> groups = all_groups(mesh);
  const auto family = families(groups);
  // A section per block, cells then facets, so that elements keep their order; points are
  // held by the Vertex sub-regions of their groups instead.
  std::vector<const CellBlock*> sections;
  for (const auto* list : {&mesh.cells, &mesh.facets})
    for (const CellBlock& b : *list)
      if (b.type != ElementType::Point && b.n_cells() > 0) {
        if (cgns_element_type(b.type, b.order) == 0)
          throw InputError("CGNS has no " + std::string(name_of(b.type)) + " of order " + std::to_string(b.order));
        sections.push_back(&b);
      }
  int base = 0, zone = 0, index = 0;
  f.check(cg_base_write(f.fn(), "Base", mesh.dim, mesh.dim, &base), "node /Base");
  cgsize_t size[3] = {static_cast<cgsize_t>(mesh.n_nodes()), static_cast<cgsize_t>(mesh.n_cells()), 0};
  f.check(cg_zone_write(f.fn(), base, "Zone", size, Unstructured, &zone), "node /Base/Zone");
  static const char* const coord_names[] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  for (int k = 0; k < mesh.dim; ++k) {
    const Eigen::VectorXd c = mesh.x.row(k).transpose();
    f.check(cg_coord_write(f.fn(), base, zone, RealDouble, coord_names[k], c.data(), &index),
            std::string("node /Base/Zone/GridCoordinates/") + coord_names[k]);
  }
  // Element numbers of each group, from 1 over the sections in order.
  std::map<std::pair<int, std::int32_t>, std::vector<cgsize_t>> members;
  cgsize_t next = 1;
  for (std::size_t s = 0; s < sections.size(); ++s) {
    const CellBlock& b = *sections[s];
    const std::vector<int>& perm = cgns_to_gmsh_permutation(b.type, b.order);
    std::vector<cgsize_t> conn;
    const cgsize_t first = next;
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      for (const int i : perm) conn.push_back(b.cell(c)[i] + 1);
      if (b.physical[c] != 0) members[{topological_dim(b.type), b.physical[c]}].push_back(next);
      ++next;
    }
    // Appended, not one chain of operator+: GCC 12's false -Wrestrict on that.
    std::string name = "E";
    name += std::to_string(s + 1);
    name += '_';
    name += name_of(b.type);
    name += std::to_string(b.order);
    f.check(cg_section_write(f.fn(), base, zone, name.c_str(), static_cast<ElementType_t>(cgns_element_type(b.type, b.order)),
                             first, next - 1, 0, conn.data(), &index),
            "node /Base/Zone/" + name);
  }
  for (const CellBlock& b : mesh.facets)
    if (b.type == ElementType::Point)
      for (std::size_t c = 0; c < b.n_cells(); ++c)
        if (b.physical[c] != 0) members[{0, b.physical[c]}].push_back(b.cell(c)[0] + 1);
  for (const PhysicalGroup& group : groups) {
    const PhysicalGroup* g = &group;
    const std::string& name = family.at({g->dim, g->tag});
    const std::string where = "node /Base/" + name;
    int fam = 0;
    f.check(cg_family_write(f.fn(), base, name.c_str(), &fam), where);
    f.check(cg_goto(f.fn(), base, "Family_t", fam, "end"), where);
    f.check(cg_ordinal_write(g->tag), where + "/Ordinal");
    if (g->name.empty()) f.check(cg_descriptor_write("meshmorph", "unnamed"), where + "/meshmorph");
    std::vector<cgsize_t>& list = members[{g->dim, g->tag}];
    if (list.empty()) continue;
    const auto n = static_cast<cgsize_t>(list.size());
    if (g->dim == mesh.dim - 1) {
      int bc = 0;
      const std::string at = "node /Base/Zone/ZoneBC/" + name;
      f.check(cg_boco_write(f.fn(), base, zone, name.c_str(), FamilySpecified, PointList, n, list.data(), &bc), at);
      f.check(cg_boco_gridlocation_write(f.fn(), base, zone, bc, mesh.dim == 3 ? FaceCenter : EdgeCenter), at);
      f.check(cg_goto(f.fn(), base, "Zone_t", zone, "ZoneBC_t", 1, "BC_t", bc, "end"), at);
    } else {
      const GridLocation_t location = g->dim == 0 ? Vertex : g->dim == mesh.dim ? CellCenter : EdgeCenter;
      int sub = 0;  // (a Vertex region's cell dimension must be at least 1)
      f.check(cg_subreg_ptset_write(f.fn(), base, zone, name.c_str(), std::max(g->dim, 1), location, PointList, n, list.data(), &sub),
              "node /Base/Zone/" + name);
      f.check(cg_goto(f.fn(), base, "Zone_t", zone, "ZoneSubRegion_t", sub, "end"), "node /Base/Zone/" + name);
    }
    f.check(cg_famname_write(name.c_str()), "FamilyName of " + name);
  }
  return {base, zone};
}

void write_cgns(const std::filesystem::path& file, const Mesh& mesh, const std::filesystem::path& shown,
                const std::map<std::string, std::vector<double>>& cell_data,
                const std::map<std::string, Eigen::MatrixXd>& point_vectors) {
  const std::lock_guard lock(detail::library_mutex());
  const detail::CgnsFile f(file, true, shown.string());
  const auto [base, zone] = detail::write_cgns_mesh(f, mesh);
  detail::write_cgns_fields(f, base, zone, mesh, "FlowSolution", "CellData", cell_data, point_vectors);
}

}  // namespace meshmorph

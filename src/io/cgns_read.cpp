// SPDX-License-Identifier: MIT
#include <cgnslib.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "io/detail/cgns_reader.h"
#include "io/detail/library_file.h"
#include "meshmorph/error.h"
#include "meshmorph/io/cgns.h"
#include "meshmorph/io/solver_ordering.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {
namespace {

using detail::CgnsFile;
using detail::CgnsZone;

// Nodes of equal coordinates in earlier zones: how zones that share an interface are merged.
using Coordinates = std::array<std::uint64_t, 3>;

static const char* const coordinate_names[] = {"CoordinateX", "CoordinateY", "CoordinateZ"};

// The grid of the zone's last time step: the last name of ZoneIterativeData_t's
// GridCoordinatesPointers (a moving grid), else GridCoordinates.
std::string last_grid(const CgnsFile& f, const CgnsZone& z) {
  char name[33] = {};
  const int found = cg_ziter_read(f.fn(), z.base, z.zone, name);
  if (found == CG_NODE_NOT_FOUND) return "GridCoordinates";
  const std::string where = "node " + z.path + "/" + name;
  f.check(found, where);
  f.check(cg_goto(f.fn(), z.base, "Zone_t", z.zone, "ZoneIterativeData_t", 1, "end"), where);
  int n = 0;
  f.check(cg_narrays(&n), where);
  for (int a = 1; a <= n; ++a) {
    char array[33] = {};
    DataType_t type{};
    int rank = 0;
    cgsize_t dims[12] = {};
    f.check(cg_array_info(a, array, &type, &rank, dims), where);
    if (std::string(array) != "GridCoordinatesPointers") continue;
    if (type != Character || rank != 2 || dims[0] != 32 || dims[1] < 1)
      throw InputError(f.name() + ": " + where + "/GridCoordinatesPointers: not 32 characters a step");
    std::vector<char> chars(static_cast<std::size_t>(dims[0] * dims[1]));
    f.check(cg_array_read(a, chars.data()), where + "/GridCoordinatesPointers");
    std::string last(chars.end() - 32, chars.end());
    last.erase(last.find_last_not_of(std::string(" \0", 2)) + 1);
    return last;
  }
  return "GridCoordinates";
}

// The coordinates of a GridCoordinates_t other than GridCoordinates (which cg_coord_read reads).
void read_grid(const CgnsFile& f, const CgnsZone& z, const std::string& grid, cgsize_t n, int phys_dim,
               std::array<std::vector<double>, 3>& xyz) {
  const std::string where = "node " + z.path + "/" + grid;
  int n_grids = 0, g = 0;
  f.check(cg_ngrids(f.fn(), z.base, z.zone, &n_grids), "node " + z.path);
  for (int i = 1; i <= n_grids && g == 0; ++i) {
    char name[33] = {};
    f.check(cg_grid_read(f.fn(), z.base, z.zone, i, name), "node " + z.path + "/GridCoordinates_t " + std::to_string(i));
    if (grid == name) g = i;
  }
  if (g == 0)
    throw InputError(f.name() + ": node " + z.path + "/ZoneIterativeData: GridCoordinatesPointers names '" + grid +
                     "', which is no GridCoordinates_t of the zone");
  f.check(cg_goto(f.fn(), z.base, "Zone_t", z.zone, "GridCoordinates_t", g, "end"), where);
  int n_arrays = 0;
  f.check(cg_narrays(&n_arrays), where);
  for (int k = 0; k < phys_dim; ++k) {
    int found = 0;
    for (int a = 1; a <= n_arrays && found == 0; ++a) {
      char array[33] = {};
      DataType_t type{};
      int rank = 0;
      cgsize_t dims[12] = {};
      f.check(cg_array_info(a, array, &type, &rank, dims), where);
      if (std::string(array) != coordinate_names[k]) continue;
      if (rank != 1 || dims[0] != n)
        throw InputError(f.name() + ": " + where + "/" + array + ": holds no value per node of the zone's " + std::to_string(n));
      found = a;
    }
    if (found == 0) throw InputError(f.name() + ": " + where + ": no " + coordinate_names[k]);
    f.check(cg_array_read_as(found, RealDouble, xyz[k].data()), where + "/" + coordinate_names[k]);
  }
}

void read_coordinates(const CgnsFile& f, CgnsZone& z, cgsize_t n, int phys_dim, detail::MeshBuilder& b,
                      std::map<Coordinates, std::int32_t>& earlier, std::vector<bool>& shared, bool merge) {
  std::array<std::vector<double>, 3> xyz;
  const auto* names = coordinate_names;
  const std::string grid = last_grid(f, z);  // (a moving grid: its last step)
  cgsize_t lo = 1, hi = n;
  for (int k = 0; k < 3; ++k) {
    xyz[k].assign(static_cast<std::size_t>(n), 0.0);
    if (k >= phys_dim || grid != "GridCoordinates") continue;
    f.check(cg_coord_read(f.fn(), z.base, z.zone, names[k], RealDouble, &lo, &hi, xyz[k].data()),
            "node " + z.path + "/GridCoordinates/" + names[k]);
  }
  if (grid != "GridCoordinates") read_grid(f, z, grid, n, phys_dim, xyz);
  std::map<Coordinates, std::int32_t> here;
  for (cgsize_t i = 0; i < n; ++i) {
    Coordinates key{};
    for (int k = 0; k < 3; ++k) {
      const double v = xyz[k][static_cast<std::size_t>(i)];
      if (!std::isfinite(v))
        throw InputError(f.name() + ": node " + z.path + "/" + grid + "/" + names[k] + ": node " + std::to_string(i + 1) +
                         " has a non-finite coordinate");
      key[k] = std::bit_cast<std::uint64_t>(v == 0.0 ? 0.0 : v);
    }
    const auto it = earlier.find(key);
    if (it != earlier.end()) {
      z.node.push_back(it->second);
      shared[static_cast<std::size_t>(it->second)] = true;
      continue;
    }
    const auto j = static_cast<std::int32_t>(b.tags.size());
    z.node.push_back(j);
    shared.push_back(false);
    if (merge) here.emplace(key, j);
    b.tags.push_back(j + 1);
    for (int k = 0; k < 3; ++k) b.xyz.push_back(xyz[k][static_cast<std::size_t>(i)]);
    if (xyz[2][static_cast<std::size_t>(i)] != 0.0 && b.first_nonzero_z.empty())
      b.first_nonzero_z = f.name() + ": node " + z.path + "/" + grid + ": node " + std::to_string(i + 1);
  }
  earlier.merge(here);
}

// Appends one element of `type` whose CGNS node numbers start at `nodes`.
void add_element(const std::string& where, cgsize_t number, int cgns_type, const cgsize_t* nodes, CgnsZone& z,
                 CgnsZone::Section& s, detail::MeshBuilder& b) {
  const auto to = cgns_type_order(cgns_type);
  if (!to)
    throw InputError(where + ": element " + std::to_string(number) + ": unsupported CGNS element type " +
                     std::string(cg_ElementTypeName(static_cast<ElementType_t>(cgns_type))) +
                     " (complete Lagrange elements only)");
  const auto [type, order] = *to;
  const std::vector<int>& perm = cgns_to_gmsh_permutation(type, order);
  std::vector<std::int32_t> cell(perm.size());
  for (std::size_t i = 0; i < perm.size(); ++i) {
    const cgsize_t v = nodes[i];
    if (v < 1 || v > static_cast<cgsize_t>(z.node.size()))
      throw InputError(where + ": element " + std::to_string(number) + " references node " + std::to_string(v) + ", outside 1.." +
                       std::to_string(z.node.size()));
    cell[static_cast<std::size_t>(perm[i])] = z.node[static_cast<std::size_t>(v - 1)];
  }
  if (const int k = detail::repeated_node(cell.data(), static_cast<int>(cell.size())); k >= 0)
    throw InputError(where + ": element " + std::to_string(number) + " lists node " + std::to_string(cell[k] + 1) +
                     " twice (a degenerate element)");
  CellBlock& blk = b.block(type, order);
  s.elements.push_back({type, order, blk.n_cells()});
  blk.push_back(cell.data(), 0);
}

void read_section(const CgnsFile& f, CgnsZone& z, int index, detail::MeshBuilder& b) {
  char name[33] = {};
  ElementType_t type{};
  CgnsZone::Section s;
  int nbndry = 0, parent = 0;
  f.check(cg_section_read(f.fn(), z.base, z.zone, index, name, &type, &s.start, &s.end, &nbndry, &parent),
          "node " + z.path + "/Elements_t " + std::to_string(index));
  s.name = name;
  const std::string where = f.name() + ": node " + z.path + "/" + s.name;
  if (s.end < s.start) throw InputError(where + ": element range " + std::to_string(s.start) + ".." + std::to_string(s.end) + " is empty");
  cgsize_t size = 0;
  f.check(cg_ElementDataSize(f.fn(), z.base, z.zone, index, &size), "node " + z.path + "/" + s.name);
  const cgsize_t count = s.end - s.start + 1;
  std::vector<cgsize_t> data(static_cast<std::size_t>(size));
  if (type == MIXED) {  // (each element its type, then its nodes; this library wants the offsets read too)
    std::vector<cgsize_t> offsets(static_cast<std::size_t>(count) + 1);
    f.check(cg_poly_elements_read(f.fn(), z.base, z.zone, index, data.data(), offsets.data(), nullptr), "node " + z.path + "/" + s.name);
  } else {
    f.check(cg_elements_read(f.fn(), z.base, z.zone, index, data.data(), nullptr), "node " + z.path + "/" + s.name);
  }
  std::size_t at = 0;
  for (cgsize_t e = 0; e < count; ++e) {
    int t = type, npe = 0;
    if (type == MIXED) {
      if (at >= data.size()) throw InputError(where + ": MIXED data ends before element " + std::to_string(s.start + e));
      t = static_cast<int>(data[at++]);
    }
    if (t < NODE || t >= NofValidElementTypes || t == MIXED || cg_npe(static_cast<ElementType_t>(t), &npe) != CG_OK || npe <= 0)
      throw InputError(where + ": element " + std::to_string(s.start + e) + ": unsupported CGNS element type " +
                       (t >= 0 && t < NofValidElementTypes ? std::string(cg_ElementTypeName(static_cast<ElementType_t>(t))) : std::to_string(t)));
    if (at + static_cast<std::size_t>(npe) > data.size())
      throw InputError(where + ": the connectivity ends inside element " + std::to_string(s.start + e));
    add_element(where, s.start + e, t, data.data() + at, z, s, b);
    at += static_cast<std::size_t>(npe);
  }
  z.sections.push_back(std::move(s));
}

// Zones merged on shared nodes must meet on whole facets: a boundary facet of the merged
// mesh whose corners are all shared nodes lies on another zone without matching its facets.
void check_zones_conform(const Mesh& mesh, const std::vector<bool>& shared, const std::string& file) {
  Topology topo;
  try {
    topo = build_topology(mesh, TopologyParts::Facets);
  } catch (const InputError& e) {
    throw InputError(file + ": node /Base: the merged zones overlap: " + e.what());
  }
  for (const std::int32_t f : topo.boundary_facets) {
    const CellFacet& cf = topo.facets[static_cast<std::size_t>(f)][0];
    const auto [bi, c] = topo.locate(cf.cell);
    const CellBlock& blk = mesh.cells[bi];
    const std::int32_t* nodes = blk.cell(c);  // a lambda may not capture a structured binding (clang 14)
    const auto& local = corner_facets(blk.type)[static_cast<std::size_t>(cf.local)];
    if (std::all_of(local.begin(), local.end(), [&](int i) { return shared[static_cast<std::size_t>(nodes[i])]; })) {
      const std::int32_t v = nodes[local[0]];
      throw InputError(file + ": node /Base: the zones do not conform: a facet at node " + std::to_string(v + 1) + " (" +
                       std::to_string(mesh.x(0, v)) + ", " + std::to_string(mesh.x(1, v)) +
                       (mesh.dim == 3 ? ", " + std::to_string(mesh.x(2, v)) : std::string()) +
                       ") lies on nodes of two zones but matches no facet of the other (merge them or make them conform)");
    }
  }
}

}  // namespace

const detail::CgnsElement* detail::CgnsZone::find(cgsize_t n) const {
  for (const Section& s : sections)
    if (n >= s.start && n <= s.end) return &s.elements[static_cast<std::size_t>(n - s.start)];
  return nullptr;
}

Mesh read_cgns(const std::filesystem::path& path) {
  const std::lock_guard lock(detail::library_mutex());
  const CgnsFile f(path, false, path.string());
  int nbases = 0;
  f.check(cg_nbases(f.fn(), &nbases), "node /");
  if (nbases != 1)
    throw InputError(f.name() + ": node /: holds " + std::to_string(nbases) + " bases (CGNSBase_t); meshmorph reads files of one");
  char base_name[33] = {};
  int cell_dim = 0, phys_dim = 0, nzones = 0;
  f.check(cg_base_read(f.fn(), 1, base_name, &cell_dim, &phys_dim), "node /");
  const std::string base_path = "/" + std::string(base_name);
  if (cell_dim < 2 || cell_dim > 3 || phys_dim < cell_dim || phys_dim > 3)
    throw InputError(f.name() + ": node " + base_path + ": cell dimension " + std::to_string(cell_dim) + " in physical dimension " +
                     std::to_string(phys_dim) + " (meshmorph reads 2D meshes in 2D and 3D meshes in 3D)");
  f.check(cg_nzones(f.fn(), 1, &nzones), "node " + base_path);
  if (nzones < 1) throw InputError(f.name() + ": node " + base_path + ": no zone");
  detail::MeshBuilder b;
  std::vector<CgnsZone> zones;
  std::map<Coordinates, std::int32_t> earlier;
  std::vector<bool> shared;
  for (int zi = 1; zi <= nzones; ++zi) {
    CgnsZone z;
    z.base = 1;
    z.zone = zi;
    char zone_name[33] = {};
    cgsize_t size[9] = {};
    ZoneType_t type{};
    f.check(cg_zone_type(f.fn(), 1, zi, &type), "node " + base_path + "/Zone_t " + std::to_string(zi));
    f.check(cg_zone_read(f.fn(), 1, zi, zone_name, size), "node " + base_path + "/Zone_t " + std::to_string(zi));
    z.path = base_path + "/" + zone_name;
    if (type != Unstructured) throw InputError(f.name() + ": node " + z.path + ": structured zones are not supported");
    if (size[0] < 1) throw InputError(f.name() + ": node " + z.path + ": the zone has no nodes");
    read_coordinates(f, z, size[0], phys_dim, b, earlier, shared, nzones > 1);
    int nsections = 0;
    f.check(cg_nsections(f.fn(), 1, zi, &nsections), "node " + z.path);
    for (int s = 1; s <= nsections; ++s) read_section(f, z, s, b);
    zones.push_back(std::move(z));
  }
  read_cgns_groups(f, b, zones, cell_dim);
  Mesh mesh = b.finish(f.name() + ": node " + base_path);
  if (nzones > 1) check_zones_conform(mesh, shared, f.name());
  return mesh;
}

}  // namespace meshmorph

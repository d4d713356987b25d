// SPDX-License-Identifier: MIT
#include <cgnslib.h>

#include <cstdio>
#include <string>
#include <vector>

#include "io/detail/cgns_writer.h"
#include "io/detail/library_file.h"
#include "meshmorph/error.h"
#include "meshmorph/io/cgns.h"

namespace meshmorph {
namespace {

// A CGNS name, checked: the library truncates longer ones, and '/' separates nodes.
std::string cgns_name(const std::string& name) {
  if (name.empty() || name.size() > 32 || name.find('/') != std::string::npos)
    throw InputError("field name '" + name + "' is no CGNS name (1 to 32 characters, no '/')");
  return name;
}

// A point vector's data name: the SIDS names where SIDS has one (Annex A).
std::string vector_name(const std::string& name) {
  if (name == "mesh_velocity") return "GridVelocity";
  if (name == "displacement") return "Displacement";
  return name;
}

// `name` followed by a 4-digit step number: Name_0003.
std::string numbered(const char* name, int step) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%s_%04d", name, step);
  return buf;
}

// A DataArray_t of `names`, each blank-padded to the 32 characters the pointers of
// ZoneIterativeData_t hold.
void write_pointers(const detail::CgnsFile& f, const char* array, const std::vector<std::string>& names) {
  std::string chars;
  for (const std::string& n : names) chars += n + std::string(32 - n.size(), ' ');
  const cgsize_t dims[2] = {32, static_cast<cgsize_t>(names.size())};
  f.check(cg_array_write(array, Character, 2, dims, chars.data()), std::string("node /Base/Zone/ZoneIterativeData/") + array);
}

}  // namespace

detail::CgnsSolutions detail::write_cgns_fields(const CgnsFile& f, int base, int zone, const Mesh& mesh, const std::string& vertex,
                                                const std::string& cells,
                                                const std::map<std::string, std::vector<double>>& cell_data,
                                                const std::map<std::string, Eigen::MatrixXd>& point_vectors) {
  CgnsSolutions written;
  static const char* const axes[] = {"X", "Y", "Z"};
  int sol = 0, field = 0;
  if (!point_vectors.empty()) {
    f.check(cg_sol_write(f.fn(), base, zone, vertex.c_str(), Vertex, &sol), "node /Base/Zone/" + vertex);
    for (const auto& [name, v] : point_vectors) {
      MESHMORPH_CHECK(v.rows() == mesh.dim && static_cast<std::size_t>(v.cols()) == mesh.n_nodes(),
                      "write_cgns: point vectors '" + name + "' are not dim × n_nodes");
      for (int k = 0; k < mesh.dim; ++k) {
        const std::string component = cgns_name(vector_name(name) + axes[k]);
        const Eigen::VectorXd c = v.row(k).transpose();
        f.check(cg_field_write(f.fn(), base, zone, sol, RealDouble, component.c_str(), c.data(), &field),
                "node /Base/Zone/" + vertex + "/" + component);
      }
    }
    written.vertex = vertex;
  }
  if (!cell_data.empty()) {
    f.check(cg_sol_write(f.fn(), base, zone, cells.c_str(), CellCenter, &sol), "node /Base/Zone/" + cells);
    for (const auto& [name, values] : cell_data) {
      MESHMORPH_CHECK(values.size() == mesh.n_cells(), "write_cgns: cell_data '" + name + "' has " +
                                                           std::to_string(values.size()) + " values for " +
                                                           std::to_string(mesh.n_cells()) + " cells");
      f.check(cg_field_write(f.fn(), base, zone, sol, RealDouble, cgns_name(name).c_str(), values.data(), &field),
              "node /Base/Zone/" + cells + "/" + name);
    }
    written.cells = cells;
  }
  return written;
}

void write_cgns_series(const std::filesystem::path& file, const Mesh& mesh, int n_steps,
                       const std::function<MeshStep(int)>& step, const std::filesystem::path& shown) {
  const std::lock_guard lock(detail::library_mutex());
  const detail::CgnsFile f(file, true, shown.string());
  const auto [base, zone] = detail::write_cgns_mesh(f, mesh);
  f.check(cg_simulation_type_write(f.fn(), base, TimeAccurate), "node /Base/SimulationType");
  static const char* const coord_names[] = {"CoordinateX", "CoordinateY", "CoordinateZ"};
  std::vector<double> times;
  std::vector<std::string> grids, vertex, cells;
  const auto n_nodes = static_cast<cgsize_t>(mesh.n_nodes());
  for (int k = 0; k < n_steps; ++k) {
    const MeshStep s = step(k);
    MESHMORPH_CHECK(s.x.rows() == mesh.dim && s.x.cols() == static_cast<Eigen::Index>(mesh.n_nodes()),
                    "write_cgns_series: a step's positions are not dim × n_nodes");
    times.push_back(s.time);
    grids.push_back(numbered("GridCoordinates", k + 1));
    int grid = 0;
    f.check(cg_grid_write(f.fn(), base, zone, grids.back().c_str(), &grid), "node /Base/Zone/" + grids.back());
    f.check(cg_goto(f.fn(), base, "Zone_t", zone, "GridCoordinates_t", grid, "end"), "node /Base/Zone/" + grids.back());
    for (int d = 0; d < mesh.dim; ++d) {
      const Eigen::VectorXd c = s.x.row(d).transpose();
      f.check(cg_array_write(coord_names[d], RealDouble, 1, &n_nodes, c.data()),
              "node /Base/Zone/" + grids.back() + "/" + coord_names[d]);
    }
    const detail::CgnsSolutions sol = detail::write_cgns_fields(f, base, zone, mesh, numbered("FlowSolution", k + 1),
                                                                numbered("CellData", k + 1), s.cell_data, s.point_vectors);
    // Every step holds the fields of the first (the pointers name a node of each step).
    if (k > 0 && (sol.vertex.empty() != vertex.empty() || sol.cells.empty() != cells.empty()))
      throw InputError("step " + std::to_string(k + 1) + " of the series holds other fields than step 1");
    if (!sol.vertex.empty()) vertex.push_back(sol.vertex);
    if (!sol.cells.empty()) cells.push_back(sol.cells);
  }
  // The times and iteration numbers of the steps, and per step the zone's nodes that hold it.
  f.check(cg_biter_write(f.fn(), base, "BaseIterativeData", n_steps), "node /Base/BaseIterativeData");
  f.check(cg_goto(f.fn(), base, "BaseIterativeData_t", 1, "end"), "node /Base/BaseIterativeData");
  const cgsize_t n = n_steps;
  std::vector<int> iterations;
  for (int k = 1; k <= n_steps; ++k) iterations.push_back(k);
  f.check(cg_array_write("TimeValues", RealDouble, 1, &n, times.data()), "node /Base/BaseIterativeData/TimeValues");
  f.check(cg_array_write("IterationValues", Integer, 1, &n, iterations.data()), "node /Base/BaseIterativeData/IterationValues");
  // The grid deforms (SIDS: without an ArbitraryGridMotion_t it is rigid); its velocity is the
  // GridVelocity of the steps' FlowSolution_t.
  int motion = 0;
  f.check(cg_arbitrary_motion_write(f.fn(), base, zone, "ArbitraryGridMotion", DeformingGrid, &motion),
          "node /Base/Zone/ArbitraryGridMotion");
  f.check(cg_ziter_write(f.fn(), base, zone, "ZoneIterativeData"), "node /Base/Zone/ZoneIterativeData");
  f.check(cg_goto(f.fn(), base, "Zone_t", zone, "ZoneIterativeData_t", 1, "end"), "node /Base/Zone/ZoneIterativeData");
  write_pointers(f, "GridCoordinatesPointers", grids);
  write_pointers(f, "ArbitraryGridMotionPointers", std::vector<std::string>(grids.size(), "ArbitraryGridMotion"));
  // SIDS gives one FlowSolution_t a step; the cell data's node goes in a second list that
  // VTK's reader (any FlowSolution…Pointers) takes too.
  if (!vertex.empty()) write_pointers(f, "FlowSolutionPointers", vertex);
  if (!cells.empty()) write_pointers(f, vertex.empty() ? "FlowSolutionPointers" : "FlowSolutionCellCenterPointers", cells);
}

}  // namespace meshmorph

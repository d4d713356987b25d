// SPDX-License-Identifier: MIT
// meshmorph._meshmorph: the C++ side of the Python module (python/meshmorph/__init__.py wraps
// it; docs/python.md). It calls the case runners of the command line (app/*_case.h), so a
// case gives the same report and mesh from both. Arrays cross as copies, n × d (a row per
// node); the library runs without the GIL.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string>
#include <utility>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "arrays.h"
#include "conversions.h"
#include "drawing.h"
#include "messages.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/deform_case.h"
#include "meshmorph/app/fit_case.h"
#include "meshmorph/app/morph_case.h"
#include "meshmorph/app/optimize_case.h"
#include "meshmorph/app/quality_case.h"
#include "meshmorph/threads.h"
#include "meshmorph/app/untangle_case.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

// The command line's --threads range, and 0 for the OpenMP default.
void check_threads(int threads, const std::string& where) {
  if (threads < 0 || threads > 1024)
    throw InputError(where + ": threads: expected 0 (all cores) or 1 to 1024, found " + std::to_string(threads));
}

// The case of a mesh in memory; `name` stands for its file in messages.
CaseFile case_of(const std::string& case_json, const std::string& name, int threads) {
  check_threads(threads, name);
  return parse_case_file(case_json, name, false);
}

py::dict quality_dict(const QualityReport& q) {
  py::dict d;
  d["cells"] = q.n_cells;
  d["inverted_elements"] = q.inverted_elements;
  d["flipped_elements"] = q.flipped_cells.size();
  d["boundary_crossings"] = q.boundary_crossings;
  d["cell_volume"] = q.cell_volume;
  d["enclosed_volume"] = q.enclosed_volume;
  d["valid"] = q.valid();
  if (q.has_input) {
    d["min_quality"] = q.min_quality;
    d["mean_quality"] = q.mean_quality;
    d["quality"] = array_of(q.quality);
  }
  d["min_shape_quality"] = q.min_shape_quality;
  d["mean_shape_quality"] = q.mean_shape_quality;
  d["min_scaled_jacobian"] = q.min_scaled_jacobian;
  d["shape_quality"] = array_of(q.shape_quality);
  d["scaled_jacobian"] = array_of(q.scaled_jacobian);
  py::dict types;
  for (const CellTypeQuality& t : q.by_type) {
    py::dict m;
    m["elements"] = t.n_cells;
    if (q.has_input) m["min_quality"] = t.min_quality;
    m["min_shape_quality"] = t.min_shape_quality;
    m["min_scaled_jacobian"] = t.min_scaled_jacobian;
    types[py::str(std::string(name_of(t.type)))] = m;
  }
  d["cell_types"] = types;
  return d;
}

// A run's report as JSON text (seconds from `start`) and its mesh.
std::pair<std::string, Mesh> reported(RunOutput&& run, const RunTimings& timings) {
  stamp_times(run.report, timings);
  return {run.json().dump(), std::move(run.moved)};
}

/// A method's whole case on a mesh in memory (morph(), untangle(), fit(), deform(),
/// optimize()): the runner of the command line, its report as JSON text and the moved mesh.
template <class Runner>
std::pair<std::string, Mesh> run_case(const Mesh& mesh, const std::string& case_json, const std::string& name, int threads,
                                      const py::object& progress) {
  const RunTimings timings;
  const CaseFile c = case_of(case_json, name, threads);
  Mesh copy = mesh;  // with the GIL: another thread may set mesh.points
  ProgressScope scope(progress);
  std::pair<std::string, Mesh> out;
  {
    py::gil_scoped_release release;
    const ScopedThreads scoped(threads);
    Runner runner(c, std::move(copy), threads);
    out = reported(runner.run(), timings);
  }
  scope.rethrow();
  return out;
}

/// A morph or untangle case on a mesh in memory, solved as often as the caller asks (the
/// Python Morpher and Untangler): each solve starts where the last ended, as a step of a time
/// series does.
class Session {
 public:
  virtual ~Session() = default;
  virtual const Mesh& input() const = 0;
  /// The current positions: waits for a solve of another thread to end.
  Eigen::MatrixXd points() {
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    return x_;
  }
  /// The motion at fraction t of its path (d × n).
  virtual Eigen::MatrixXd targets_at(double t) const = 0;
  /// `a` as targets (d × n).
  Eigen::MatrixXd targets_from(const Array& a) const {
    const Mesh& mesh = input();
    Eigen::MatrixXd x = matrix_of(a, mesh.dim, mesh.n_nodes(), name_ + ".solve: targets");
    if (const auto bad = coordinate_range_problem(x); bad && bad->node >= 0)
      throw InputError(name_ + ".solve: targets: row " + std::to_string(bad->node) + ": " + bad->what);
    return x;
  }
  /// One solve towards `target`: the report as JSON text and the positions it ends at.
  /// Without the GIL; solves of one session from several threads take turns.
  std::pair<std::string, Eigen::MatrixXd> solve(const Eigen::MatrixXd& target, const py::object& progress) {
    ProgressScope scope(progress);
    std::pair<std::string, Eigen::MatrixXd> out;
    {
      py::gil_scoped_release release;
      std::lock_guard lock(mutex_);
      const ScopedThreads scoped(threads_);
      const RunTimings timings;
      auto [report, moved] = reported(run(target), timings);
      x_ = std::move(moved.x);
      out = {std::move(report), x_};
    }
    scope.rethrow();
    return out;
  }

 protected:
  Session(std::string name, int threads) : name_(std::move(name)), threads_(threads) {}
  virtual RunOutput run(const Eigen::MatrixXd& target) = 0;
  void check_t(double t) const {
    if (!(t >= 0.0 && t <= 1.0)) throw InputError(name_ + ".solve: t must be in [0, 1], found " + std::to_string(t));
  }

  std::string name_;
  int threads_;  // 0: the OpenMP default
  Eigen::MatrixXd x_;
  std::mutex mutex_;  // x_ and the runner's state belong to one solve at a time
};

/// A Session on one of the runners that solve step by step (MorphRunner, UntangleRunner).
template <class Runner>
class RunnerSession final : public Session {
 public:
  RunnerSession(std::unique_ptr<Runner> runner, std::string name, int threads)
      : Session(std::move(name), threads), runner_(std::move(runner)) {
    x_ = runner_->input().x;
  }
  const Mesh& input() const override { return runner_->input(); }
  Eigen::MatrixXd targets_at(double t) const override {
    check_t(t);
    return runner_->motion().at(t);
  }

 private:
  RunOutput run(const Eigen::MatrixXd& target) override { return runner_->solve(target); }
  std::unique_ptr<Runner> runner_;
};

std::unique_ptr<Session> morph_session(const Mesh& mesh, const std::string& case_json, int threads) {
  const CaseFile c = case_of(case_json, "Morpher", threads);
  if (read_morph_settings(c, threads).method != "morph")
    throw InputError("Morpher: options.method: the Morpher runs \"morph\"; the baselines run from morph() and the "
                     "command line (meshmorph morph)");
  return std::make_unique<RunnerSession<MorphRunner>>(std::make_unique<MorphRunner>(c, mesh, threads), "Morpher", threads);
}

std::unique_ptr<Session> untangle_session(const Mesh& mesh, const std::string& case_json, int threads) {
  const CaseFile c = case_of(case_json, "Untangler", threads);
  return std::make_unique<RunnerSession<UntangleRunner>>(std::make_unique<UntangleRunner>(c, mesh, threads), "Untangler", threads);
}

// A solve's report text and its positions as (str, array).
py::tuple solved(const std::pair<std::string, Eigen::MatrixXd>& r) { return py::make_tuple(r.first, rows_of(r.second)); }

// Mesh.write: the format from the extension.
void write_mesh_file(const Mesh& mesh, const std::filesystem::path& path, bool binary) {
  if (binary && path.extension() == ".mesh") throw InputError(path.string() + ": binary is not available for Medit .mesh (ASCII only)");
  if (binary && path.extension() == ".su2") throw InputError(path.string() + ": binary is not available for SU2 .su2 (ASCII only)");
  WriteOptions o;
  o.binary = binary;
  write_mesh(path, mesh, o);
}

std::string mesh_repr(const Mesh& mesh) {
  std::string cells;
  for (const CellBlock& b : mesh.cells)
    cells += (cells.empty() ? "" : ", ") + std::to_string(b.n_cells()) + " " + std::string(name_of(b.type)) + " P" + std::to_string(b.order);
  std::string groups;
  for (const PhysicalGroup& g : mesh.groups)
    groups += (groups.empty() ? "; groups " : ", ") + (g.name.empty() ? std::string() : g.name + " ") + "(" + std::to_string(g.tag) + ")";
  return "<meshmorph.Mesh " + std::to_string(mesh.dim) + "D: " + std::to_string(mesh.n_nodes()) + " nodes, " + cells + groups + ">";
}

}  // namespace
}  // namespace meshmorph

PYBIND11_MODULE(_meshmorph, m) {
  using namespace meshmorph;
  m.doc() = "meshmorph's C++ core; use the package meshmorph";
  // NumPy's C API is looked up on its first use, under a static guard: first used by two
  // threads at once, one held the guard and waited for the GIL while the other held the GIL
  // and waited for the guard. Looked up now, at import.
  (void)py::array_t<double>(0);
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<IoError>(m, "IoError", PyExc_OSError);
  m.attr("__version__") = meshmorph_version();

  py::class_<Mesh>(m, "Mesh", "An unstructured mesh of 2D or 3D cells of order 1-4, its nodes in Gmsh's order "
                              "(docs/python.md, Meshes).")
      .def(py::init(&mesh_of), py::arg("points"), py::arg("cells"), py::arg("facets") = py::list(),
           py::arg("groups") = py::list(),
           "A mesh from arrays: points (n_nodes, dim), cell and facet blocks as Mesh.cell_blocks gives them "
           "(type, order, nodes in Gmsh's order, physical tags), groups as Mesh.groups. Curved cells nearly all "
           "inverted are refused: their nodes are likely in VTK's order, as meshio holds them (Mesh.from_meshio "
           "converts).")
      .def_readonly("dim", &Mesh::dim, "Spatial dimension, 2 or 3.")
      .def_property_readonly("order", &Mesh::order, "The highest order of the cells (1 straight-sided).")
      .def_property_readonly("n_nodes", &Mesh::n_nodes, "Number of nodes.")
      .def_property_readonly("n_cells", &Mesh::n_cells, "Number of cells (of dimension dim; facets not counted).")
      .def_property(
          "points", [](const py::object& self) { return points_view(self.cast<const Mesh&>().x, self); },
          // Into the same storage: the views handed out see the new coordinates.
          [](Mesh& mesh, const Array& a) {
            const Eigen::MatrixXd x = points_of(a, mesh.dim, mesh.n_nodes(), "Mesh.points");
            mesh.x = x;
          },
          "The node coordinates, (n_nodes, dim) float64: a read-only view of the mesh's own (it follows the "
          "mesh; .copy() for an array of one's own). Assigning an array of the same shape, finite, sets them.")
      .def_property_readonly("node_tags", [](const Mesh& mesh) { return read_only(array_of(mesh.node_tags)); },
                             "The file's node tags (int64; 1 ... n for a mesh from arrays), a read-only copy.")
      .def_property_readonly("cell_blocks", [](const Mesh& mesh) { return block_dicts(mesh.cells); },
                             "The cells, a list of {\"type\", \"order\", \"nodes\", \"physical\"} per block: nodes "
                             "(n_cells, nodes per cell), 0-based, in Gmsh's order; physical the group tag of each cell "
                             "(0: none). The arrays are read-only copies.")
      .def_property_readonly("facet_blocks", [](const Mesh& mesh) { return block_dicts(mesh.facets); },
                             "The tagged boundary and interface elements (and, in 3D, tagged edges and points) that "
                             "carry the groups, as cell_blocks.")
      .def_property_readonly("groups",
                             [](const Mesh& mesh) {
                               py::list groups;
                               for (const PhysicalGroup& g : mesh.groups) {
                                 py::dict d;
                                 d["name"] = g.name;
                                 d["dim"] = g.dim;
                                 d["tag"] = g.tag;
                                 groups.append(d);
                               }
                               return groups;
                             },
                             "The physical groups, a list of {\"name\", \"dim\", \"tag\"}.")
      .def("group_nodes",
           [](const Mesh& mesh, const py::object& group) {
             if (!py::isinstance<py::str>(group) && (!py::isinstance<py::int_>(group) || py::isinstance<py::bool_>(group)))
               throw py::type_error("Mesh.group_nodes: expected a group name (str) or number (int), found " +
                                    std::string(py::str(py::type::of(group).attr("__name__"))));
             const std::string key = py::str(group);
             const std::optional<PhysicalGroup> g = mesh.find_group(key);
             if (!g) throw InputError("Mesh.group_nodes: no physical group \"" + key + "\" in the mesh");
             return read_only(array_of(mesh.group_nodes(*g)));
           },
           py::arg("group"), "0-based indices of the nodes of a physical group, by name or number (2 or \"2\"); "
                             "a read-only array.")
      .def("write", &write_mesh_file, py::arg("path"), py::arg("binary") = false,
           "Writes the mesh atomically; the format comes from the extension (.msh: MSH 4.1, .vtu, .mesh, .su2, "
           ".cgns, .exo/.e/.ex2), or a time folder of the OpenFOAM case the mesh was read from (case/0.001: its "
           "polyMesh/points). binary: binary MSH, base64 VTU.")
      .def("copy", [](const Mesh& mesh) { return mesh; }, "An independent copy.")
      .def("__copy__", [](const Mesh& mesh) { return mesh; })
      .def("__deepcopy__", [](const Mesh& mesh, const py::dict&) { return mesh; }, py::arg("memo"))
      .def("__repr__", &mesh_repr);

  m.def("read_mesh", [](const std::filesystem::path& path) {
    py::gil_scoped_release release;
    return read_mesh(path);
  }, py::arg("path"), "Reads a mesh: .msh (2.2 or 4.1, ASCII or binary), .vtu, .mesh, .su2, .cgns, .exo/.e/.ex2, or an "
                       "OpenFOAM case, polyMesh or time folder. Nodes come in Gmsh's order.");
  m.def("elevate", [](const Mesh& mesh, int order) {
    int highest = 4;
    for (const CellBlock& b : mesh.cells) highest = std::min(highest, max_order_of(b.type));
    if (order < mesh.order() || order > highest)
      throw InputError("elevate: expected an order from " + std::to_string(mesh.order()) + " to " +
                       std::to_string(highest) + ", found " + std::to_string(order));
    return elevate_order(mesh, order);
  }, py::arg("mesh"), py::arg("order"), "The mesh at a higher order (straight-sided; its own nodes kept).");
  m.def("quality", [](const Mesh& mesh, const Mesh* reference) {
    return quality_dict(run_quality(mesh, "quality", reference).quality);
  }, py::arg("mesh"), py::arg("reference") = py::none(),
        "Validity and quality of every cell (`meshmorph quality`): against `reference` too (quality 1/eta "
        "of paper 000) when it is given, a mesh with the same cells.");
  add_messages(m);

  const auto run = [&m]<class Runner>(const char* name) {
    m.def((std::string("_") + name).c_str(), [name](const Mesh& mesh, const std::string& text, int threads, const py::object& progress) {
      return run_case<Runner>(mesh, text, name, threads, progress);
    }, py::arg("mesh"), py::arg("case_json"), py::arg("threads"), py::arg("progress") = py::none());
  };
  run.operator()<MorphRunner>("morph");
  run.operator()<UntangleRunner>("untangle");
  run.operator()<FitRunner>("fit");
  run.operator()<DeformRunner>("deform");
  run.operator()<OptimizeRunner>("optimize");
  m.def("_convert", [](const std::filesystem::path& input, const std::filesystem::path& output, int order, bool binary, bool msh22) {
    const WriteOptions options = convert_options(output.string(), binary, msh22);
    py::gil_scoped_release release;
    Mesh mesh = converted(read_mesh(input), order, input.string());
    write_mesh(output, mesh, options);
    return mesh;
  }, py::arg("input"), py::arg("output"), py::arg("order"), py::arg("binary"), py::arg("msh22"));

  py::class_<Session>(m, "Session")
      .def_property_readonly("mesh", [](const Session& s) { return s.input(); })  // a copy: the reference stays
      .def_property_readonly("points", [](Session& s) { return read_only(rows_of(s.points())); })
      .def("solve_at", [](Session& s, double t, const py::object& progress) { return solved(s.solve(s.targets_at(t), progress)); },
           py::arg("t"), py::arg("progress") = py::none())
      .def("solve_to", [](Session& s, const Array& targets, const py::object& progress) {
        return solved(s.solve(s.targets_from(targets), progress));
      }, py::arg("targets"), py::arg("progress") = py::none());
  add_conversions(m);
  add_drawing(m);
  m.def("MorphSession", &morph_session, py::arg("mesh"), py::arg("case_json"), py::arg("threads"));
  m.def("UntangleSession", &untangle_session, py::arg("mesh"), py::arg("case_json"), py::arg("threads"));
}

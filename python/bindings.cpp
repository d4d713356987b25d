// SPDX-License-Identifier: MIT
// meshmorph._meshmorph: the C++ side of the Python module (python/meshmorph/__init__.py wraps
// it; docs/python.md). Arrays cross as copies, n × d (a row per node); the library runs
// without the GIL.
#include <chrono>
#include <cstdio>
#include <cstring>
#include <memory>
#include <string>
#include <utility>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "app/detail/method_output.h"
#include "meshmorph/app/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/morph_case.h"
#include "meshmorph/app/report.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/log.h"
#include "meshmorph/methods/morph.h"
#include "meshmorph/quality/quality_report.h"

namespace py = pybind11;

namespace meshmorph {
namespace {

using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The n × d array of a d × n matrix: Eigen's column-major d × n is row-major n × d.
py::array_t<double> rows_of(const Eigen::MatrixXd& x) {
  py::array_t<double> a({static_cast<py::ssize_t>(x.cols()), static_cast<py::ssize_t>(x.rows())});
  std::memcpy(a.mutable_data(), x.data(), sizeof(double) * static_cast<std::size_t>(x.size()));
  return a;
}

// The d × n matrix of an n × d array; InputError naming `what` for another shape or a
// coordinate that is not finite.
Eigen::MatrixXd matrix_of(const Array& a, int dim, std::size_t n, const std::string& what) {
  const auto shape = [&] {
    std::string s = "(";
    for (py::ssize_t k = 0; k < a.ndim(); ++k) s += (k ? ", " : "") + std::to_string(a.shape(k));
    return s + (a.ndim() == 1 ? ",)" : ")");
  };
  if (a.ndim() != 2 || a.shape(0) != static_cast<py::ssize_t>(n) || a.shape(1) != dim)
    throw InputError(what + ": expected an array of shape (" + std::to_string(n) + ", " + std::to_string(dim) +
                     "), found " + shape());
  Eigen::MatrixXd x(dim, static_cast<Eigen::Index>(n));
  std::memcpy(x.data(), a.data(), sizeof(double) * static_cast<std::size_t>(x.size()));
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    if (!x.col(j).allFinite()) throw InputError(what + ": row " + std::to_string(j) + " is not finite");
  return x;
}

template <class T>
py::array_t<T> array_of(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

py::dict quality_dict(const QualityReport& q) {
  py::dict d;
  d["cells"] = q.n_cells;
  d["inverted_elements"] = q.inverted_elements;
  d["valid"] = q.inverted_elements == 0;
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
  return d;
}

/// A morph case on a mesh in memory, solved as often as the caller asks: λ, μ and the weights
/// carry from one solve to the next as in a time series (Morpher), the mesh's topology, DOF
/// numbering and symbolic factorization are made once.
class MorphSession {
 public:
  MorphSession(const Mesh& mesh, const std::string& case_json, int threads)
      : case_(parse_case_file(case_json, "Morpher", false)), input_(mesh) {
    check_case_against_mesh(case_, input_);
    settings_ = read_morph_settings(case_, threads);
    if (settings_.method != "morph")
      throw InputError("Morpher: options.method: the Morpher runs \"morph\"; the baselines \"" + settings_.method +
                       "\" run from the command line (meshmorph morph)");
    if (case_.order && *case_.order > input_.order()) input_ = elevate_order(input_, *case_.order);
    if (const std::size_t bad = count_invalid_cells(input_); bad > 0)
      throw InputError("Morpher: the mesh has " + std::to_string(bad) +
                       " inverted elements: morph needs a valid input mesh (untangle recovers one)");
    topology_ = build_topology(input_);
    motion_ = std::make_unique<BoundaryMotion>(case_, input_, topology_);
    morpher_ = std::make_unique<Morpher>(input_, topology_, motion_->targets(), settings_.morph);
    x_ = input_.x;
  }

  const Mesh& input() const { return input_; }
  const Eigen::MatrixXd& points() const { return x_; }
  Eigen::MatrixXd targets_at(double t) const {
    if (!(t >= 0.0 && t <= 1.0)) throw InputError("Morpher.solve: t must be in [0, 1], found " + std::to_string(t));
    return motion_->at(t);
  }

  /// One solve towards `target` (d × n); the report of DESIGN §3.3 as JSON text.
  std::string solve(const Eigen::MatrixXd& target) {
    const auto start = std::chrono::steady_clock::now();
    Report report;
    report.method = "morph";
    MorphResult r;
    {
      py::gil_scoped_release release;
      r = morpher_->solve(target, x_, ++step_);
    }
    report.iterations = IterationCounts{r.outer, r.nonlinear, r.newton, r.linear};
    report.history = morph_history(r);
    report.converged = r.converged;
    report.message = r.message;
    Mesh moved = input_;
    moved.x = x_;
    detail::fill_result(report, moved, &input_, motion_->targets());
    if (report.converged && report.message.empty()) report.message = "boundary reached, mesh valid";
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.meshmorph_version = meshmorph_version();
    report.peak_memory_mb = peak_memory_mb();
    nlohmann::ordered_json j = report_to_json(report);
    j["guarded_cells"] = r.guarded_cells;
    return j.dump();
  }

 private:
  CaseFile case_;
  Mesh input_;
  MorphSettings settings_;
  Topology topology_;
  std::unique_ptr<BoundaryMotion> motion_;  // holds pointers to input_ and topology_
  std::unique_ptr<Morpher> morpher_;
  Eigen::MatrixXd x_;
  int step_ = 0;
};

}  // namespace
}  // namespace meshmorph

PYBIND11_MODULE(_meshmorph, m) {
  using namespace meshmorph;
  m.doc() = "meshmorph's C++ core; use the package meshmorph";
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);
  py::register_exception<IoError>(m, "IoError", PyExc_OSError);
  m.attr("__version__") = meshmorph_version();

  py::class_<Mesh>(m, "Mesh")
      .def_readonly("dim", &Mesh::dim)
      .def_property_readonly("order", &Mesh::order)
      .def_property_readonly("n_nodes", &Mesh::n_nodes)
      .def_property_readonly("n_cells", &Mesh::n_cells)
      .def_property(
          "points", [](const Mesh& mesh) { return rows_of(mesh.x); },
          [](Mesh& mesh, const Array& a) { mesh.x = matrix_of(a, mesh.dim, mesh.n_nodes(), "Mesh.points"); })
      .def_property_readonly("node_tags", [](const Mesh& mesh) { return array_of(mesh.node_tags); })
      .def_property_readonly("cell_blocks",
                             [](const Mesh& mesh) {
                               py::list blocks;
                               for (const CellBlock& b : mesh.cells) {
                                 py::array_t<std::int32_t> nodes({static_cast<py::ssize_t>(b.n_cells()),
                                                                  static_cast<py::ssize_t>(b.n_nodes_per_cell())});
                                 std::copy(b.nodes.begin(), b.nodes.end(), nodes.mutable_data());
                                 py::dict d;
                                 d["type"] = std::string(name_of(b.type));
                                 d["order"] = b.order;
                                 d["nodes"] = nodes;
                                 blocks.append(d);
                               }
                               return blocks;
                             })
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
                             })
      .def("group_nodes",
           [](const Mesh& mesh, const std::string& key) {
             const std::optional<PhysicalGroup> g = mesh.find_group(key);
             if (!g) throw InputError("Mesh.group_nodes: no physical group \"" + key + "\" in the mesh");
             return array_of(mesh.group_nodes(*g));
           },
           py::arg("group"), "0-based indices of the nodes of a physical group (name, or number as a string).")
      .def("write",
           [](const Mesh& mesh, const std::string& path, bool binary) {
             WriteOptions o;
             o.binary = binary;
             py::gil_scoped_release release;
             write_mesh(path, mesh, o);
           },
           py::arg("path"), py::arg("binary") = false,
           "Writes the mesh atomically; the format comes from the extension (.msh: MSH 4.1, .vtu, .mesh).")
      .def("copy", [](const Mesh& mesh) { return mesh; }, "An independent copy.");

  m.def("read_mesh", [](const std::string& path) {
    py::gil_scoped_release release;
    return read_mesh(path);
  }, py::arg("path"), "Reads .msh (2.2 or 4.1, ASCII or binary), .vtu or .mesh.");
  m.def("elevate", [](const Mesh& mesh, int order) {
    if (order < mesh.order() || order > 4)
      throw InputError("elevate: expected an order from " + std::to_string(mesh.order()) + " to 4, found " +
                       std::to_string(order));
    py::gil_scoped_release release;
    return elevate_order(mesh, order);
  }, py::arg("mesh"), py::arg("order"), "The mesh at a higher order (straight-sided; its own nodes kept).");
  m.def("quality", [](const Mesh& mesh, const Mesh* reference) {
    QualityReport q;
    {
      py::gil_scoped_release release;
      q = quality_report(mesh, reference);
    }
    return quality_dict(q);
  }, py::arg("mesh"), py::arg("reference") = py::none(),
        "Validity and quality of every cell (`meshmorph quality`): against `reference` too (quality 1/eta "
        "of paper 000) when it is given, a mesh with the same cells.");
  m.def("set_log_level", [](const std::string& level) {
    if (level == "quiet") return set_log_sink({});
    const LogLevel max = level == "detail" ? LogLevel::Detail : level == "progress" ? LogLevel::Progress : LogLevel::Info;
    if (level != "detail" && level != "progress" && level != "info")
      throw InputError("set_log_level: expected \"quiet\", \"info\", \"progress\" or \"detail\", found \"" + level + "\"");
    set_log_sink([](LogLevel, std::string_view message) { std::fprintf(stderr, "meshmorph: %.*s\n", static_cast<int>(message.size()), message.data()); },
                 max);
  }, py::arg("level"), "Where the library's messages go: \"quiet\" (none, the default), \"info\", \"progress\" "
                        "(a line per iteration) or \"detail\" (Newton steps), on stderr.");

  py::class_<MorphSession>(m, "MorphSession")
      .def(py::init<const Mesh&, const std::string&, int>(), py::arg("mesh"), py::arg("case_json"), py::arg("threads"))
      .def_property_readonly("mesh", &MorphSession::input)
      .def_property_readonly("points", [](const MorphSession& s) { return rows_of(s.points()); })
      .def("solve_at", [](MorphSession& s, double t) { return s.solve(s.targets_at(t)); })
      .def("solve_to", [](MorphSession& s, const Array& targets) {
        const Mesh& mesh = s.input();
        return s.solve(matrix_of(targets, mesh.dim, mesh.n_nodes(), "Morpher.solve: targets"));
      });
}

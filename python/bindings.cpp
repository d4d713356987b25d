// SPDX-License-Identifier: MIT
// meshmorph._meshmorph: the C++ side of the Python module (python/meshmorph/__init__.py wraps
// it; docs/python.md). Arrays cross as copies, n × d (a row per node); the library runs
// without the GIL.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "app/detail/method_output.h"
#include "io/detail/mesh_builder.h"
#include "meshmorph/app/boundary_motion.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/app/fit_case.h"
#include "meshmorph/app/morph_case.h"
#include "meshmorph/app/report.h"
#include "meshmorph/app/untangle_case.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/log.h"
#include "meshmorph/methods/fit.h"
#include "meshmorph/methods/morph.h"
#include "meshmorph/methods/untangle.h"
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

// matrix_of for a mesh's coordinates, which must also be in the range the methods compute in.
Eigen::MatrixXd points_of(const Array& a, int dim, std::size_t n, const std::string& what) {
  Eigen::MatrixXd x = matrix_of(a, dim, n, what);
  if (const auto bad = coordinate_range_problem(x))
    throw InputError(what + ": " + (bad->node >= 0 ? "row " + std::to_string(bad->node) + ": " : std::string()) + bad->what);
  return x;
}

template <class T>
py::array_t<T> array_of(const std::vector<T>& v) {
  py::array_t<T> a(static_cast<py::ssize_t>(v.size()));
  std::copy(v.begin(), v.end(), a.mutable_data());
  return a;
}

// d[key] as T; InputError naming `where`.key and what was expected otherwise.
template <class T>
T entry(const py::dict& d, const char* key, const std::string& where, const char* expected) {
  try {
    return d[key].cast<T>();
  } catch (const py::cast_error&) {
    throw InputError(where + "." + key + ": expected " + expected + ", found " +
                     std::string(py::str(py::type::of(d[key]).attr("__name__"))));
  }
}

// An array of integers (signed or unsigned dtype, or a list of Python ints), as int64: floats
// and booleans are not truncated into node numbers or tags.
py::array_t<std::int64_t> integers_of(const py::handle& value, const std::string& where) {
  const py::array a = py::array::ensure(value);
  const char kind = a ? a.dtype().kind() : '?';
  if (kind != 'i' && kind != 'u') throw InputError(where + ": expected integers");
  return py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
}

// The keys of a dict are among `known` (a comma-separated list for the message).
void only_keys(const py::dict& d, std::initializer_list<const char*> known, const std::string& where) {
  for (const auto& item : d) {
    const std::string k = py::str(item.first);
    if (std::none_of(known.begin(), known.end(), [&](const char* n) { return k == n; })) {
      std::string list;
      for (const char* n : known) list += (list.empty() ? "" : ", ") + std::string(n);
      throw InputError(where + "." + k + ": unknown key (expected one of: " + list + ")");
    }
  }
}

// A list of cell blocks as `Mesh.cell_blocks` gives them: dicts of "type", "order", "nodes"
// (n_cells × nodes per cell, 0-based, Gmsh's order) and, optionally, "physical" (a tag per
// cell). `what` names the list in messages; the blocks are of dimension min_dim to max_dim.
std::vector<CellBlock> blocks_of(const py::list& list, std::size_t n_nodes, int min_dim, int max_dim,
                                 const std::string& what) {
  std::vector<CellBlock> blocks;
  for (std::size_t i = 0; i < list.size(); ++i) {
    const std::string where = what + "[" + std::to_string(i) + "]";
    if (!py::isinstance<py::dict>(list[i])) throw InputError(where + ": expected a dict of type, order, nodes, physical");
    const py::dict d = list[i].cast<py::dict>();
    only_keys(d, {"type", "order", "nodes", "physical"}, where);
    if (!d.contains("type") || !d.contains("nodes")) throw InputError(where + ": needs \"type\" and \"nodes\"");
    CellBlock b;
    const std::string type = entry<std::string>(d, "type", where, "a string");
    bool known = false;
    for (ElementType t : {ElementType::Point, ElementType::Line, ElementType::Triangle, ElementType::Quadrilateral,
                          ElementType::Tetrahedron, ElementType::Hexahedron})
      if (name_of(t) == type) b.type = t, known = true;
    if (!known || topological_dim(b.type) < min_dim || topological_dim(b.type) > max_dim)
      throw InputError(where + ".type: \"" + type + "\" is not a " + (min_dim == max_dim ? "cell" : "facet") +
                       " type of this mesh");
    b.order = 1;
    if (d.contains("order")) {
      if (!py::isinstance<py::int_>(d["order"]) || py::isinstance<py::bool_>(d["order"]))
        throw InputError(where + ".order: expected an integer");
      const long long order = d["order"].cast<long long>();
      b.order = order >= 1 && order <= 4 ? static_cast<int>(order) : 0;
    }
    if (b.order < 1 || b.order > std::max(1, max_order_of(b.type)))
      throw InputError(where + ".order: " + py::str(d["order"]).cast<std::string>() + " is not an order of " + type + " cells");
    const auto nodes = integers_of(d["nodes"], where + ".nodes");
    const int k = b.n_nodes_per_cell();
    if (nodes.ndim() != 2 || nodes.shape(1) != k)
      throw InputError(where + ".nodes: expected an array of " + std::to_string(k) + " columns (" + type + " of order " +
                       std::to_string(b.order) + ")");
    const auto n_cells = static_cast<std::size_t>(nodes.shape(0));
    b.nodes.resize(n_cells * static_cast<std::size_t>(k));
    for (std::size_t j = 0; j < b.nodes.size(); ++j) {
      const std::int64_t v = nodes.data()[j];
      if (v < 0 || v >= static_cast<std::int64_t>(n_nodes))
        throw InputError(where + ".nodes: node " + std::to_string(v) + " of cell " + std::to_string(j / k) +
                         " is not in [0, " + std::to_string(n_nodes) + ")");
      b.nodes[j] = static_cast<std::int32_t>(v);
    }
    for (std::size_t c = 0; c < n_cells; ++c)  // a cell listing a node twice has no volume
      if (const int twice = detail::repeated_node(b.cell(c), k); twice >= 0)
        throw InputError(where + ".nodes: cell " + std::to_string(c) + " lists node " + std::to_string(b.cell(c)[twice]) +
                         " twice (a degenerate cell)");
    b.physical.assign(n_cells, 0);
    b.entity.assign(n_cells, 0);
    if (d.contains("physical")) {
      const auto tags = integers_of(d["physical"], where + ".physical");
      if (tags.ndim() != 1 || static_cast<std::size_t>(tags.shape(0)) != n_cells)
        throw InputError(where + ".physical: expected one tag per cell (" + std::to_string(n_cells) + ")");
      for (std::size_t c = 0; c < n_cells; ++c) {
        const std::int64_t t = tags.data()[c];
        if (t < 0 || t > std::numeric_limits<std::int32_t>::max())
          throw InputError(where + ".physical: tag " + std::to_string(t) + " of cell " + std::to_string(c) +
                           " is not in [0, 2^31)");
        b.physical[c] = static_cast<std::int32_t>(t);
      }
    }
    blocks.push_back(std::move(b));
  }
  return blocks;
}

// Mesh.cell_blocks and Mesh.facet_blocks.
py::list block_dicts(const std::vector<CellBlock>& blocks) {
  py::list list;
  for (const CellBlock& b : blocks) {
    py::array_t<std::int32_t> nodes({static_cast<py::ssize_t>(b.n_cells()), static_cast<py::ssize_t>(b.n_nodes_per_cell())});
    std::copy(b.nodes.begin(), b.nodes.end(), nodes.mutable_data());
    py::dict d;
    d["type"] = std::string(name_of(b.type));
    d["order"] = b.order;
    d["nodes"] = nodes;
    d["physical"] = array_of(b.physical);
    list.append(d);
  }
  return list;
}

/// A mesh from arrays (Mesh(points, cells, facets, groups)): the blocks as Mesh.cell_blocks
/// and Mesh.facet_blocks give them, the groups as Mesh.groups.
Mesh mesh_of(const Array& points, const py::list& cells, const py::list& facets, const py::list& groups) {
  if (points.ndim() != 2 || (points.shape(1) != 2 && points.shape(1) != 3))
    throw InputError("Mesh: points: expected an array of shape (n_nodes, 2) or (n_nodes, 3)");
  Mesh m;
  m.dim = static_cast<int>(points.shape(1));
  m.x = points_of(points, m.dim, static_cast<std::size_t>(points.shape(0)), "Mesh: points");
  // (n, 3) points of a 2D mesh, as meshio and VTK hold them: z must be 0 and goes.
  const auto flat = [&] {
    for (std::size_t i = 0; i < cells.size(); ++i)
      if (py::isinstance<py::dict>(cells[i]) && cells[i].cast<py::dict>().contains("type")) {
        const std::string t = py::str(cells[i].cast<py::dict>()["type"]);
        if (t != "triangle" && t != "quadrilateral") return false;
      }
    return cells.size() > 0;
  };
  if (m.dim == 3 && flat()) {
    if (!m.x.row(2).isZero(0.0)) throw InputError("Mesh: points: z is not 0 but the cells are 2D");
    m.x = m.x.topRows(2).eval();
    m.dim = 2;
  }
  m.node_tags.resize(m.n_nodes());
  for (std::size_t i = 0; i < m.n_nodes(); ++i) m.node_tags[i] = static_cast<std::int64_t>(i) + 1;
  m.cells = blocks_of(cells, m.n_nodes(), m.dim, m.dim, "Mesh: cells");
  if (m.cells.empty()) throw InputError("Mesh: cells: no cell block");
  m.facets = blocks_of(facets, m.n_nodes(), 0, m.dim - 1, "Mesh: facets");
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const std::string where = "Mesh: groups[" + std::to_string(i) + "]";
    if (!py::isinstance<py::dict>(groups[i])) throw InputError(where + ": expected a dict of name, dim, tag");
    const py::dict g = groups[i].cast<py::dict>();
    only_keys(g, {"name", "dim", "tag"}, where);
    if (!g.contains("dim") || !g.contains("tag")) throw InputError(where + ": needs \"dim\" and \"tag\"");
    const long long dim = entry<long long>(g, "dim", where, "an integer");
    const long long tag = entry<long long>(g, "tag", where, "an integer");
    const std::string name = g.contains("name") ? entry<std::string>(g, "name", where, "a string") : "";
    if (dim < 0 || dim > m.dim) throw InputError(where + ".dim: " + std::to_string(dim) + " is not in [0, " + std::to_string(m.dim) + "]");
    if (tag < 1 || tag > std::numeric_limits<std::int32_t>::max()) throw InputError(where + ".tag: " + std::to_string(tag) + " is not in [1, 2^31)");
    if (name.find_first_of("\"\n\r") != std::string::npos)
      throw InputError(where + ".name: a group name holds no quote or line break (MSH could not store it)");
    for (const PhysicalGroup& other : m.groups)
      if ((other.dim == dim && other.tag == tag) || (!name.empty() && other.name == name))
        throw InputError(where + ": group " + (name.empty() ? std::to_string(tag) : "\"" + name + "\"") + " is given twice");
    m.groups.push_back({static_cast<int>(dim), static_cast<std::int32_t>(tag), name});
  }
  return m;
}

// The command line's --threads range, and 0 for the OpenMP default.
void check_threads(int threads, const std::string& where) {
  if (threads < 0 || threads > 1024)
    throw InputError(where + ": threads: expected 0 (all cores) or 1 to 1024, found " + std::to_string(threads));
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

/// A method's case on a mesh in memory, solved as often as the caller asks (the Python
/// Morpher and Untangler): the boundary is resolved once, and each solve starts where the last
/// ended, as a step of a time series does.
class Session {
 public:
  virtual ~Session() = default;
  const Mesh& input() const { return input_; }
  /// The current positions: waits for a solve of another thread to end.
  Eigen::MatrixXd points() {
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    return x_;
  }

  /// The motion at fraction t of its path (d × n).
  Eigen::MatrixXd targets_at(double t) const {
    if (!(t >= 0.0 && t <= 1.0)) throw InputError(name_ + ".solve: t must be in [0, 1], found " + std::to_string(t));
    return motion_ ? motion_->at(t) : input_.x;
  }
  Eigen::MatrixXd targets_from(const Array& a) const {
    Eigen::MatrixXd x = matrix_of(a, input_.dim, input_.n_nodes(), name_ + ".solve: targets");
    if (const auto bad = coordinate_range_problem(x); bad && bad->node >= 0)
      throw InputError(name_ + ".solve: targets: row " + std::to_string(bad->node) + ": " + bad->what);
    return x;
  }

  /// One solve towards `target` (d × n): the report of DESIGN §3.3 as JSON text, and the
  /// positions it ends at. Without the GIL; solves of one session from several threads take
  /// turns.
  std::pair<std::string, Eigen::MatrixXd> solve(const Eigen::MatrixXd& target) {
    py::gil_scoped_release release;
    std::lock_guard lock(mutex_);
    const auto start = std::chrono::steady_clock::now();
    Report report;
    nlohmann::ordered_json extra = nlohmann::ordered_json::object();
    run(target, ++step_, report, extra);
    Mesh moved = input_;
    moved.x = x_;
    // The boundary error against this solve's targets, not the case's motion at its end.
    BoundaryTargets bc = targets();
    for (std::size_t i = 0; i < bc.n_nodes(); ++i)
      if (bc.role[i] == NodeRole::Prescribed) bc.target.col(static_cast<Eigen::Index>(i)) = target.col(static_cast<Eigen::Index>(i));
    detail::fill_result(report, moved, input_inverted_ == 0 ? &input_ : nullptr, bc);
    report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report.meshmorph_version = meshmorph_version();
    report.peak_memory_mb = peak_memory_mb();
    nlohmann::ordered_json j = report_to_json(report);
    for (auto& [key, value] : extra.items()) j[key] = value;
    return {j.dump(), x_};
  }

 protected:
  /// Parses the case (`name` stands for its file in messages), checks it against the mesh and
  /// elevates the mesh to the case's order.
  Session(const Mesh& mesh, const std::string& case_json, std::string name, int threads)
      : name_(std::move(name)), case_(parse_case_file(case_json, name_, false)), input_(mesh) {
    check_threads(threads, name_);
    check_case_against_mesh(case_, input_);
    if (case_.order && below_order(input_, *case_.order)) input_ = elevate_order(input_, *case_.order);
    input_inverted_ = count_invalid_cells(input_);
  }
  /// Resolves the boundary entries on the mesh; without any, every boundary node is fixed.
  void resolve_boundary() {
    topology_ = build_topology(input_);
    if (!case_.boundary.empty()) motion_ = std::make_unique<BoundaryMotion>(case_, input_, topology_);
    else bare_ = detail::fixed_boundary(input_, topology_);
    x_ = input_.x;
  }
  const BoundaryTargets& targets() const { return motion_ ? motion_->targets() : bare_; }
  /// The method's solve from x_ towards `target`, filling the report's method fields and the
  /// members that follow DESIGN §3.3's (`extra`); runs without the GIL.
  virtual void run(const Eigen::MatrixXd& target, int step, Report& report, nlohmann::ordered_json& extra) = 0;

  std::string name_;
  CaseFile case_;
  Mesh input_;
  std::size_t input_inverted_ = 0;
  Topology topology_;
  std::unique_ptr<BoundaryMotion> motion_;  // holds pointers to input_ and topology_
  BoundaryTargets bare_;
  Eigen::MatrixXd x_;
  int step_ = 0;
  std::mutex mutex_;  // x_, step_ and the method's state belong to one solve at a time
};

// A solve's report text and its positions as (str, array).
py::tuple solved(const std::pair<std::string, Eigen::MatrixXd>& r) { return py::make_tuple(r.first, rows_of(r.second)); }

/// `meshmorph morph` on a mesh in memory: λ, μ and the weights carry from one solve to the
/// next (Morpher), the mesh's topology, DOF numbering and symbolic factorization are made once.
class MorphSession final : public Session {
 public:
  MorphSession(const Mesh& mesh, const std::string& case_json, int threads)
      : Session(mesh, case_json, "Morpher", threads) {
    const MorphSettings settings = read_morph_settings(case_, threads);
    if (settings.method != "morph")
      throw InputError("Morpher: options.method: the Morpher runs \"morph\"; the baselines \"" + settings.method +
                       "\" run from the command line (meshmorph morph)");
    if (input_inverted_ > 0)
      throw InputError("Morpher: the mesh has " + std::to_string(input_inverted_) +
                       " inverted elements: morph needs a valid input mesh (untangle recovers one)");
    resolve_boundary();
    morpher_ = std::make_unique<Morpher>(input_, topology_, targets(), settings.morph);
  }

 private:
  void run(const Eigen::MatrixXd& target, int step, Report& report, nlohmann::ordered_json& extra) override {
    const MorphResult r = morpher_->solve(target, x_, step);
    report.method = "morph";
    report.iterations = IterationCounts{r.outer, r.nonlinear, r.newton, r.linear};
    report.history = morph_history(r);
    report.converged = r.converged;
    report.message = r.converged && r.message.empty() ? "boundary reached, mesh valid" : r.message;
    extra["guarded_cells"] = r.guarded_cells;
    nlohmann::ordered_json passes = nlohmann::ordered_json::array();
    if (r.finish) passes.push_back(untangle_pass(*r.finish, step));
    extra["untangle_passes"] = passes;
  }
  std::unique_ptr<Morpher> morpher_;
};

/// `meshmorph untangle` on a mesh in memory (paper 001): tangled input welcome; each solve
/// starts from the last result, moved by the differential predictor when it is on.
class UntangleSession final : public Session {
 public:
  UntangleSession(const Mesh& mesh, const std::string& case_json, int threads)
      : Session(mesh, case_json, "Untangler", threads) {
    std::optional<UntangleReference> reference;
    options_ = read_untangle_options(case_.options, name_, threads, reference);
    resolve_untangle_reference(options_, reference, input_inverted_, name_);
    resolve_boundary();
    untangler_ = std::make_unique<Untangler>(input_, topology_, targets(), options_);
  }

 private:
  void run(const Eigen::MatrixXd& target, int step, Report& report, nlohmann::ordered_json& extra) override {
    const UntangleResult r = untangler_->solve(target, x_, step);
    report.method = "untangle";
    report.iterations = IterationCounts{r.delta_updates, 1, r.newton, r.linear};
    report.history = untangle_history(r);
    report.converged = r.converged;
    report.message = r.message;
    extra["initial_inverted_elements"] = r.initial_inverted;
    extra["min_edge_quality"] = r.min_quality;
    extra["predictor"] = options_.predictor;
    extra["reference"] = options_.reference == UntangleReference::Input ? "input" : "regular";
  }
  UntangleOptions options_;
  std::unique_ptr<Untangler> untangler_;
};

/// `meshmorph fit` on a mesh in memory (paper 003): the fitted mesh, which the case may have
/// trimmed, split and elevated, and its report as JSON text.
std::pair<std::string, Mesh> fit_mesh(const Mesh& mesh, const std::string& case_json, int threads) {
  const auto start = std::chrono::steady_clock::now();
  check_threads(threads, "fit");
  const CaseFile c = parse_case_file(case_json, "fit", false);
  check_case_against_mesh(c, mesh);
  const FitSettings settings = read_fit_settings(c, threads);
  if (const std::size_t bad = count_invalid_cells(mesh); bad > 0)
    throw InputError("fit: the mesh has " + std::to_string(bad) + " inverted elements: fit needs a valid input mesh");
  const FitSetup setup = prepare_fit(c, mesh, settings, "fit");
  Eigen::MatrixXd x = setup.mesh.x;
  FitResult r;
  {
    py::gil_scoped_release release;
    r = fit_to_level_sets(setup.mesh, setup.topology, setup.terms, setup.fixed, settings.fit, x);
  }
  FitOutcome o = fit_outcome(setup, settings, r, x);
  o.report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  o.report.meshmorph_version = meshmorph_version();
  o.report.peak_memory_mb = peak_memory_mb();
  nlohmann::ordered_json j = report_to_json(o.report);
  for (auto& [key, value] : o.extra.items()) j[key] = value;
  return {j.dump(), std::move(o.moved)};
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

  py::class_<Mesh>(m, "Mesh")
      .def(py::init(&mesh_of), py::arg("points"), py::arg("cells"), py::arg("facets") = py::list(),
           py::arg("groups") = py::list(),
           "A mesh from arrays: points (n_nodes, dim), cell and facet blocks as Mesh.cell_blocks gives them "
           "(type, order, nodes in Gmsh's order, physical tags), groups as Mesh.groups.")
      .def_readonly("dim", &Mesh::dim)
      .def_property_readonly("order", &Mesh::order)
      .def_property_readonly("n_nodes", &Mesh::n_nodes)
      .def_property_readonly("n_cells", &Mesh::n_cells)
      .def_property(
          "points", [](const Mesh& mesh) { return rows_of(mesh.x); },
          [](Mesh& mesh, const Array& a) { mesh.x = points_of(a, mesh.dim, mesh.n_nodes(), "Mesh.points"); })
      .def_property_readonly("node_tags", [](const Mesh& mesh) { return array_of(mesh.node_tags); })
      .def_property_readonly("cell_blocks", [](const Mesh& mesh) { return block_dicts(mesh.cells); })
      .def_property_readonly("facet_blocks", [](const Mesh& mesh) { return block_dicts(mesh.facets); })
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
           [](const Mesh& mesh, const std::filesystem::path& path, bool binary) {
             if (binary && path.extension() == ".mesh")
               throw InputError(path.string() + ": binary is not available for Medit .mesh (ASCII only)");
             WriteOptions o;
             o.binary = binary;
             write_mesh(path, mesh, o);
           },
           py::arg("path"), py::arg("binary") = false,
           "Writes the mesh atomically; the format comes from the extension (.msh: MSH 4.1, .vtu, .mesh).")
      .def("copy", [](const Mesh& mesh) { return mesh; }, "An independent copy.")
      .def("__copy__", [](const Mesh& mesh) { return mesh; })
      .def("__deepcopy__", [](const Mesh& mesh, const py::dict&) { return mesh; }, py::arg("memo"));

  m.def("read_mesh", [](const std::filesystem::path& path) {
    py::gil_scoped_release release;
    return read_mesh(path);
  }, py::arg("path"), "Reads .msh (2.2 or 4.1, ASCII or binary), .vtu or .mesh.");
  m.def("elevate", [](const Mesh& mesh, int order) {
    int highest = 4;
    for (const CellBlock& b : mesh.cells) highest = std::min(highest, max_order_of(b.type));
    if (order < mesh.order() || order > highest)
      throw InputError("elevate: expected an order from " + std::to_string(mesh.order()) + " to " +
                       std::to_string(highest) + ", found " + std::to_string(order));
    return elevate_order(mesh, order);
  }, py::arg("mesh"), py::arg("order"), "The mesh at a higher order (straight-sided; its own nodes kept).");
  m.def("quality", [](const Mesh& mesh, const Mesh* reference) {
    if (reference) {
      bool same = reference->dim == mesh.dim && reference->n_nodes() == mesh.n_nodes() &&
                  reference->cells.size() == mesh.cells.size();
      for (std::size_t i = 0; same && i < mesh.cells.size(); ++i)
        same = reference->cells[i].type == mesh.cells[i].type && reference->cells[i].order == mesh.cells[i].order &&
               reference->cells[i].nodes == mesh.cells[i].nodes;
      if (!same) throw InputError("quality: reference: not the same cells and nodes as the mesh");
    }
    return quality_dict(quality_report(mesh, reference));
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

  m.def("_fit", &fit_mesh, py::arg("mesh"), py::arg("case_json"), py::arg("threads"));

  py::class_<Session>(m, "Session")
      .def_property_readonly("mesh", [](const Session& s) { return s.input(); })  // a copy: the reference stays
      .def_property_readonly("points", [](Session& s) { return rows_of(s.points()); })
      .def("solve_at", [](Session& s, double t) { return solved(s.solve(s.targets_at(t))); }, py::arg("t"))
      .def("solve_to", [](Session& s, const Array& targets) { return solved(s.solve(s.targets_from(targets))); },
           py::arg("targets"));
  py::class_<MorphSession, Session>(m, "MorphSession")
      .def(py::init<const Mesh&, const std::string&, int>(), py::arg("mesh"), py::arg("case_json"), py::arg("threads"));
  py::class_<UntangleSession, Session>(m, "UntangleSession")
      .def(py::init<const Mesh&, const std::string&, int>(), py::arg("mesh"), py::arg("case_json"), py::arg("threads"));
}

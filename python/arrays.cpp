// SPDX-License-Identifier: MIT
// NumPy arrays and Python lists to and from the library's matrices and meshes.
#include "arrays.h"

#include <algorithm>
#include <cstring>
#include <limits>

#include "io/detail/mesh_builder.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/error.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

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
                          ElementType::Tetrahedron, ElementType::Hexahedron, ElementType::Prism, ElementType::Pyramid})
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

}  // namespace

// Eigen's column-major d × n is row-major n × d.
py::array_t<double> rows_of(const Eigen::MatrixXd& x) {
  py::array_t<double> a({static_cast<py::ssize_t>(x.cols()), static_cast<py::ssize_t>(x.rows())});
  std::memcpy(a.mutable_data(), x.data(), sizeof(double) * static_cast<std::size_t>(x.size()));
  return a;
}

py::array_t<double> points_view(const Eigen::MatrixXd& x, const py::object& owner) {
  const auto d = static_cast<py::ssize_t>(x.rows());
  py::array_t<double> a({static_cast<py::ssize_t>(x.cols()), d}, {d * py::ssize_t{sizeof(double)}, py::ssize_t{sizeof(double)}},
                        x.data(), owner);
  return read_only(a);
}

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

Eigen::MatrixXd points_of(const Array& a, int dim, std::size_t n, const std::string& what) {
  Eigen::MatrixXd x = matrix_of(a, dim, n, what);
  if (const auto bad = coordinate_range_problem(x))
    throw InputError(what + ": " + (bad->node >= 0 ? "row " + std::to_string(bad->node) + ": " : std::string()) + bad->what);
  return x;
}

py::list block_dicts(const std::vector<CellBlock>& blocks) {
  py::list list;
  for (const CellBlock& b : blocks) {
    py::array_t<std::int32_t> nodes({static_cast<py::ssize_t>(b.n_cells()), static_cast<py::ssize_t>(b.n_nodes_per_cell())});
    std::copy(b.nodes.begin(), b.nodes.end(), nodes.mutable_data());
    py::dict d;
    d["type"] = std::string(name_of(b.type));
    d["order"] = b.order;
    d["nodes"] = read_only(nodes);
    d["physical"] = read_only(array_of(b.physical));
    list.append(d);
  }
  return list;
}

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
  if (m.n_cells() == 0) throw InputError("Mesh: cells: no cell (every block is empty)");
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
    if (const auto bad = group_name_problem(name)) throw InputError(where + ".name: the name " + *bad);
    for (const PhysicalGroup& other : m.groups)
      if ((other.dim == dim && other.tag == tag) || (!name.empty() && other.name == name))
        throw InputError(where + ": group " + (name.empty() ? std::to_string(tag) : "\"" + name + "\"") + " is given twice");
    m.groups.push_back({static_cast<int>(dim), static_cast<std::int32_t>(tag), name});
  }
  // Curved cells listed in VTK's node order, as meshio holds them, come out nearly all inverted.
  if (m.order() >= 2)
    if (const std::size_t bad = count_invalid_cells(m); bad * 10 >= m.n_cells() * 9)
      throw InputError("Mesh: cells: " + std::to_string(bad) + " of " + std::to_string(m.n_cells()) +
                       " cells are inverted: their nodes are likely in VTK's order (as meshio holds them), where "
                       "Mesh(...) takes Gmsh's (docs/node-ordering.md); Mesh.from_meshio converts a meshio mesh");
  return m;
}

}  // namespace meshmorph

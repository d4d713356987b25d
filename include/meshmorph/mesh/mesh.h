// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <unordered_map>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph {

/// Cells of one family and one order. Nodes are 0-based indices into Mesh::x, listed per
/// cell in the internal ordering, which is Gmsh's (corners, then edge, face and interior
/// nodes; docs/node-ordering.md). Formats with another ordering convert at the border.
struct CellBlock {
  ElementType type = ElementType::Triangle;
  int order = 1;
  std::vector<std::int32_t> nodes;     ///< n_cells × n_nodes_per_cell, row per cell
  std::vector<std::int32_t> physical;  ///< physical-group tag per cell, 0 = none
  std::vector<std::int32_t> entity;    ///< geometric-entity tag per cell (Gmsh), 0 = unknown

  int n_nodes_per_cell() const { return n_nodes_of(type, order); }
  std::size_t n_cells() const { return nodes.size() / static_cast<std::size_t>(n_nodes_per_cell()); }
  const std::int32_t* cell(std::size_t c) const { return nodes.data() + c * n_nodes_per_cell(); }
  std::int32_t* cell(std::size_t c) { return nodes.data() + c * n_nodes_per_cell(); }
  /// Appends one cell; `cell_nodes` holds n_nodes_per_cell() entries.
  void push_back(const std::int32_t* cell_nodes, std::int32_t physical_tag, std::int32_t entity_tag = 0);
};

/// A named physical group (Gmsh's notion): a tag in a dimension, with an optional name.
struct PhysicalGroup {
  int dim = 0;
  std::int32_t tag = 0;
  std::string name;
};

/// An unstructured mesh in 2D or 3D.
///
/// `cells` hold the elements of dimension `dim`; `facets` hold the tagged elements of lower
/// dimension (boundary and interface facets of dimension dim−1, and in 3D also tagged edges
/// and points). Physical groups are per element; a node is in a group when an element of
/// that group holds it.
struct Mesh {
  int dim = 0;                           ///< spatial dimension, 2 or 3
  Eigen::MatrixXd x;                     ///< dim × n_nodes, column j = node j
  std::vector<std::int64_t> node_tags;   ///< file tag of each node (1-based in the files)
  std::vector<CellBlock> cells;
  std::vector<CellBlock> facets;
  std::vector<PhysicalGroup> groups;
  /// Scalar nodal fields (point data) by name: n_nodes() values each, in node order. Read
  /// from VTU PointData and MSH $NodeData and written back there (docs/formats.md); code
  /// that renumbers or adds nodes must update or drop them.
  std::map<std::string, Eigen::VectorXd, std::less<>> node_fields;

  std::size_t n_nodes() const { return static_cast<std::size_t>(x.cols()); }
  std::size_t n_cells() const;
  /// Highest order over the cell blocks (1 for an empty mesh).
  int order() const;
  /// Most nodes of a cell over the blocks of the mesh's dimension (0 when there are none).
  int max_cell_nodes() const;

  /// Finds a group by name, or by number when `key` is all digits; the dimension of the
  /// group is preferred in this order: dim−1, dim, lower. Empty if there is none.
  std::optional<PhysicalGroup> find_group(const std::string& key) const;
  /// Sorted, unique node indices of all elements (cells and facets) tagged with `group`.
  std::vector<std::int32_t> group_nodes(const PhysicalGroup& group) const;
  /// Node index of each node tag (tags may be sparse and as large as MSH allows).
  std::unordered_map<std::int64_t, std::int32_t> node_index_of_tag() const;
};

/// Coordinates beyond ±kMaxCoordinate make the volumes of 3D cells (products of three) overflow
/// double precision, and a mesh smaller than kMinExtent (its bounding box's diagonal) makes them
/// underflow: the readers, the case's motions and the Python module refuse both.
inline constexpr double kMaxCoordinate = 1e100;
inline constexpr double kMinExtent = 1e-90;

/// Why the coordinates x (d × n) are outside that range, or empty: `node` is the column of
/// the first coordinate beyond ±kMaxCoordinate, −1 where the extent is the problem.
struct CoordinateRangeProblem {
  std::ptrdiff_t node = -1;
  std::string what;
};
std::optional<CoordinateRangeProblem> coordinate_range_problem(const Eigen::MatrixXd& x);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/fem/elevate.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <unordered_map>

#include "meshmorph/error.h"
#include "meshmorph/fem/shape_table.h"

namespace meshmorph {
namespace {

// A new node is identified by the corners of the lowest-dimensional entity it lies on and
// its (multi)linear corner weights there, sorted by corner: two cells that share an edge
// or face compute the same key for the same point. Weights are rational (k/p^d), so
// rounding to 1e-9 makes the key exact.
using NodeKey = std::array<std::int64_t, 16>;

struct NodeKeyHash {
  std::size_t operator()(const NodeKey& k) const {
    std::uint64_t h = 1469598103934665603ull;
    for (auto v : k) h = (h ^ static_cast<std::uint64_t>(v)) * 1099511628211ull;
    return static_cast<std::size_t>(h);
  }
};

struct Elevator {
  const Mesh& in;
  int order;
  std::vector<std::int32_t> old_to_new;            // kept old node → new index (−1: dropped)
  std::unordered_map<NodeKey, std::int32_t, NodeKeyHash> created;
  std::vector<Eigen::VectorXd> positions;          // new nodes, in creation order
  std::int32_t n_kept = 0;
  std::vector<const Eigen::VectorXd*> fields;      // in.node_fields, in map order
  std::vector<std::vector<double>> field_values;   // per field: values at the new nodes

  CellBlock elevate(const CellBlock& b) {
    if (b.type == ElementType::Point || b.order == order) return renumbered(b);
    const auto& ref = reference_element(b.type, order);
    const auto table = tabulate(b.type, b.order, ref.nodes);  // old basis at new nodes
    const int nc = n_corners_of(b.type), n_old = b.n_nodes_per_cell(), n_new = ref.n_nodes();
    std::vector<Eigen::VectorXd> weights;
    for (int j = 0; j < n_new; ++j) weights.push_back(corner_weights(b.type, ref.nodes.col(j)));

    CellBlock out{b.type, order, {}, b.physical, b.entity};
    out.nodes.resize(b.n_cells() * static_cast<std::size_t>(n_new));
    Eigen::MatrixXd X(in.dim, n_old);
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      const auto* v = b.cell(c);
      for (int a = 0; a < n_old; ++a) X.col(a) = in.x.col(v[a]);
      auto* w = out.nodes.data() + c * static_cast<std::size_t>(n_new);
      for (int j = 0; j < n_new; ++j) {
        if (j < nc) {
          w[j] = old_to_new[static_cast<std::size_t>(v[j])];
          continue;
        }
        std::array<std::pair<std::int64_t, std::int64_t>, 8> terms{};
        int nt = 0;
        for (int i = 0; i < nc; ++i) {
          const auto q = std::llround(weights[static_cast<std::size_t>(j)](i) * 1e9);
          if (q == 0) continue;
          // Insertion into sorted order (at most eight terms; std::sort on the first nt of
          // eight draws GCC 12's false -Warray-bounds).
          const std::pair<std::int64_t, std::int64_t> t{v[i], q};
          int at = nt++;
          for (; at > 0 && t < terms[static_cast<std::size_t>(at - 1)]; --at)
            terms[static_cast<std::size_t>(at)] = terms[static_cast<std::size_t>(at - 1)];
          terms[static_cast<std::size_t>(at)] = t;
        }
        NodeKey key;
        key.fill(-1);
        for (int t = 0; t < nt; ++t) {
          key[static_cast<std::size_t>(2 * t)] = terms[static_cast<std::size_t>(t)].first;
          key[static_cast<std::size_t>(2 * t + 1)] = terms[static_cast<std::size_t>(t)].second;
        }
        auto [it, fresh] = created.try_emplace(key, n_kept + static_cast<std::int32_t>(positions.size()));
        if (fresh) {
          positions.push_back(X * table.N.col(j));
          // Fields are interpolated like the coordinates: the old cell's basis at the new node.
          for (std::size_t f = 0; f < fields.size(); ++f) {
            double value = 0;
            for (int a = 0; a < n_old; ++a) value += (*fields[f])(v[a]) * table.N(a, j);
            field_values[f].push_back(value);
          }
        }
        w[j] = it->second;
      }
    }
    return out;
  }

  CellBlock renumbered(const CellBlock& b) {
    CellBlock out = b;
    for (auto& v : out.nodes) v = old_to_new[static_cast<std::size_t>(v)];
    return out;
  }
};

}  // namespace

bool below_order(const Mesh& mesh, int order) {
  const auto below = [&](const CellBlock& b) { return b.order < order; };
  const auto above = [&](const CellBlock& b) { return b.order > order; };
  return std::any_of(mesh.cells.begin(), mesh.cells.end(), below) && std::none_of(mesh.cells.begin(), mesh.cells.end(), above);
}

Mesh elevate_order(const Mesh& mesh, int order) {
  for (const auto& b : mesh.cells)
    MESHMORPH_CHECK(order >= b.order, "cannot lower the order of a mesh (" + std::to_string(b.order) + " → " +
                                          std::to_string(order) + ")");
  // Facets follow their cells: a quartic prism's quadrilaterals are quartic.
  for (const auto& b : mesh.cells)
    MESHMORPH_CHECK(order <= max_order_of(b.type) || b.type == ElementType::Point,
                    "order " + std::to_string(order) + " exceeds the maximum for " + std::string(name_of(b.type)));

  // Keep every node except the high-order nodes of elements that are elevated: those are
  // replaced by the nodes of the new order.
  Elevator e{mesh, order, std::vector<std::int32_t>(mesh.n_nodes(), 0), {}, {}, 0, {}, {}};
  for (const auto& [name, values] : mesh.node_fields) {
    MESHMORPH_CHECK(static_cast<std::size_t>(values.size()) == mesh.n_nodes(),
                    "elevate_order: node field '" + name + "' does not have one value per node");
    e.fields.push_back(&values);
  }
  e.field_values.resize(e.fields.size());
  for (const auto& blocks : {&mesh.cells, &mesh.facets})
    for (const auto& b : *blocks) {
      if (b.order == order || b.type == ElementType::Point) continue;
      const int nc = n_corners_of(b.type), n = b.n_nodes_per_cell();
      for (std::size_t c = 0; c < b.n_cells(); ++c)
        for (int a = nc; a < n; ++a) e.old_to_new[static_cast<std::size_t>(b.cell(c)[a])] = -1;
    }
  for (auto& v : e.old_to_new) v = v == 0 ? e.n_kept++ : -1;

  Mesh out;
  out.dim = mesh.dim;
  out.groups = mesh.groups;
  for (const auto& b : mesh.cells) out.cells.push_back(e.elevate(b));
  for (const auto& b : mesh.facets) out.facets.push_back(e.elevate(b));

  out.x.resize(mesh.dim, e.n_kept + static_cast<Eigen::Index>(e.positions.size()));
  out.node_tags.resize(static_cast<std::size_t>(out.x.cols()));
  std::int64_t max_tag = 0;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    const auto tag = i < mesh.node_tags.size() ? mesh.node_tags[i] : static_cast<std::int64_t>(i + 1);
    max_tag = std::max(max_tag, tag);
    if (e.old_to_new[i] < 0) continue;
    out.x.col(e.old_to_new[i]) = mesh.x.col(static_cast<Eigen::Index>(i));
    out.node_tags[static_cast<std::size_t>(e.old_to_new[i])] = tag;
  }
  for (std::size_t k = 0; k < e.positions.size(); ++k) {
    out.x.col(e.n_kept + static_cast<Eigen::Index>(k)) = e.positions[k];
    out.node_tags[static_cast<std::size_t>(e.n_kept) + k] = max_tag + 1 + static_cast<std::int64_t>(k);
  }
  std::size_t f = 0;
  for (const auto& [name, values] : mesh.node_fields) {
    Eigen::VectorXd& to = out.node_fields[name];
    to.resize(out.x.cols());
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
      if (e.old_to_new[i] >= 0) to(e.old_to_new[i]) = values(static_cast<Eigen::Index>(i));
    for (std::size_t k = 0; k < e.positions.size(); ++k) to(e.n_kept + static_cast<Eigen::Index>(k)) = e.field_values[f][k];
    ++f;
  }
  return out;
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/fem/orientation.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/shape_table.h"
#include "meshmorph/fem/trace.h"

namespace meshmorph {
namespace {

// Neumaier's compensated sum: a volume balance over 10⁸ cells must not drift by the
// rounding of the sum itself.
struct Sum {
  double s = 0.0, c = 0.0;
  void add(double v) {
    const double t = s + v;
    c += std::abs(s) >= std::abs(v) ? (s - t) + v : (v - t) + s;
    s = t;
  }
  double value() const { return s + c; }
};

// The corners of local facet f of a cell, in the facet's outward order (2 to 4 of them).
struct Corners {
  std::array<std::int32_t, 4> v{};
  std::size_t n = 0;
};

Corners facet_corners(const CellBlock& b, std::size_t c, int f) {
  const auto& local = corner_facets(b.type)[static_cast<std::size_t>(f)];
  Corners out;
  out.n = local.size();
  for (std::size_t i = 0; i < local.size(); ++i) out.v[i] = b.cell(c)[local[i]];
  return out;
}

// Whether two facets have the same corners (distinct within each facet), in any order.
bool same_corners(const Corners& a, const Corners& b) {
  if (a.n != b.n) return false;
  for (std::size_t i = 0; i < a.n; ++i) {
    bool found = false;
    for (std::size_t j = 0; j < b.n; ++j) found = found || a.v[i] == b.v[j];
    if (!found) return false;
  }
  return true;
}

// Two cells are oriented alike when each lists their shared facet the other way round: the
// same cycle of corners, reversed (for a line facet: the same two corners swapped).
bool alike(const Corners& a, const Corners& b) {
  const std::size_t n = a.n;
  if (n == 2) return b.v[0] == a.v[1];
  std::size_t k = 0;
  while (k < n && b.v[k] != a.v[0]) ++k;
  return k < n && b.v[(k + n - 1) % n] == a.v[1];
}

// Degrees that integrate det A (cells) and x·n (facets) exactly: det A has total degree
// d(p−1) on simplices and degree dp−1 in each variable on tensor cells; x·n on a facet of
// order p has p more in each variable than its area element.
int volume_degree(ElementType t, int order) {
  const int d = topological_dim(t);
  return is_simplex(t) ? d * (order - 1) : d * order - 1;
}

int flux_degree(ElementType facet, int order) {
  if (facet == ElementType::Line) return 2 * order - 1;
  return facet == ElementType::Triangle ? 3 * order - 2 : 3 * order - 1;
}

// (1/d)·∫ x·n over one facet; x relative to `origin`, nodes in the facet's own (outward) order.
double facet_term(const Mesh& mesh, ElementType facet, int order, const std::vector<std::int32_t>& nodes,
                  const Eigen::VectorXd& origin) {
  const ShapeTable& t = shape_table(facet, order, flux_degree(facet, order));
  Eigen::MatrixXd X(mesh.dim, static_cast<Eigen::Index>(nodes.size()));
  for (std::size_t i = 0; i < nodes.size(); ++i) X.col(static_cast<Eigen::Index>(i)) = mesh.x.col(nodes[i]) - origin;
  double sum = 0.0;
  for (int q = 0; q < t.n_points(); ++q) {
    const Eigen::VectorXd x = X * t.N.col(q);
    const Eigen::MatrixXd T = X * t.grad(q);
    const double flux = mesh.dim == 2 ? x(0) * T(1, 0) - x(1) * T(0, 0)
                                      : x.dot(Eigen::Vector3d(T.col(0)).cross(Eigen::Vector3d(T.col(1))));
    sum += t.weights(q) * flux;
  }
  return sum / mesh.dim;
}

// The node permutation that mirrors a cell: node i of the mirrored cell is the node at the
// reference point of node i with its first two coordinates swapped.
std::vector<int> mirror_permutation(ElementType type, int order) {
  const Eigen::MatrixXd& nodes = reference_element(type, order).nodes;
  std::vector<int> perm(static_cast<std::size_t>(nodes.cols()), -1);
  for (Eigen::Index i = 0; i < nodes.cols(); ++i) {
    Eigen::VectorXd swapped = nodes.col(i);
    std::swap(swapped(0), swapped(1));
    for (Eigen::Index j = 0; j < nodes.cols(); ++j)
      if ((nodes.col(j) - swapped).norm() < 1e-12) perm[static_cast<std::size_t>(i)] = static_cast<int>(j);
  }
  return perm;
}

}  // namespace

bool VolumeBalance::balanced() const {
  return std::isfinite(cells) && std::isfinite(enclosed) && std::abs(cells - enclosed) <= 1e-10 * scale;
}

double signed_volume(ElementType type, int order, const Eigen::MatrixXd& X) {
  const ShapeTable& t = shape_table(type, order, volume_degree(type, order));
  double v = 0.0;
  for (int q = 0; q < t.n_points(); ++q) v += t.weights(q) * (X * t.grad(q)).determinant();
  return v;
}

std::vector<double> signed_volumes(const Mesh& mesh) {
  std::vector<double> out;
  for (const CellBlock& b : mesh.cells) {
    const std::size_t first = out.size();
    out.resize(first + b.n_cells());
    const auto n = static_cast<std::ptrdiff_t>(b.n_cells());
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t c = 0; c < n; ++c)
      out[first + static_cast<std::size_t>(c)] = signed_volume(b.type, b.order, cell_coordinates(mesh, b, static_cast<std::size_t>(c)));
  }
  return out;
}

CellOrientation cell_orientation(const Mesh& mesh, const Topology& topology, const std::vector<double>& volumes) {
  const std::size_t n = topology.block_offset.back();
  auto corners = [&](std::int32_t cell, int local) {
    const auto [b, c] = topology.locate(cell);
    return facet_corners(mesh.cells[b], c, local);
  };
  // Whether cell m, across local facet l of cell c, is listed alike with c: m's facet with the
  // same corners runs the other way round.
  auto alike_across = [&](std::int32_t c, int l, std::int32_t m) {
    const Corners a = corners(c, l);
    const auto first = topology.cell_neighbor_offset[static_cast<std::size_t>(m)];
    const auto count = topology.cell_neighbor_offset[static_cast<std::size_t>(m) + 1] - first;
    for (int k = 0; k < count; ++k) {
      if (topology.cell_neighbors[static_cast<std::size_t>(first + k)] != c) continue;
      const Corners b = corners(m, k);
      if (same_corners(a, b)) return alike(a, b);
    }
    return true;  // not reached: topology lists c across one of m's facets
  };

  CellOrientation out;
  std::vector<std::int8_t> parity(n, -1);
  std::vector<std::int32_t> part, stack;
  for (std::size_t seed = 0; seed < n; ++seed) {
    if (parity[seed] >= 0) continue;
    part.clear();
    parity[seed] = 0;
    stack.assign(1, static_cast<std::int32_t>(seed));
    while (!stack.empty()) {
      const auto c = static_cast<std::size_t>(stack.back());
      stack.pop_back();
      part.push_back(static_cast<std::int32_t>(c));
      const auto first = topology.cell_neighbor_offset[c];
      const auto count = topology.cell_neighbor_offset[c + 1] - first;
      for (int l = 0; l < count; ++l) {
        const std::int32_t m = topology.cell_neighbors[static_cast<std::size_t>(first + l)];
        if (m < 0) continue;
        const auto mi = static_cast<std::size_t>(m);
        const auto want = static_cast<std::int8_t>(parity[c] ^ (alike_across(static_cast<std::int32_t>(c), l, m) ? 0 : 1));
        if (parity[mi] < 0) {
          parity[mi] = want;
          stack.push_back(m);
        } else if (parity[mi] != want && out.twisted_cell < 0) {
          out.twisted_cell = static_cast<std::int32_t>(c);
        }
      }
    }
    // The class kept is the one whose orientation gives the part the larger volume.
    Sum volume[2];
    std::size_t count[2] = {0, 0};
    for (auto c : part) {
      volume[parity[static_cast<std::size_t>(c)]].add(volumes[static_cast<std::size_t>(c)]);
      ++count[parity[static_cast<std::size_t>(c)]];
    }
    const double lead = volume[0].value() - volume[1].value();
    const int wrong = lead > 0.0 ? 1 : lead < 0.0 ? 0 : count[1] > count[0] ? 0 : 1;
    for (auto c : part)
      if (parity[static_cast<std::size_t>(c)] == wrong) out.flipped.push_back(c);
  }
  std::sort(out.flipped.begin(), out.flipped.end());
  return out;
}

VolumeBalance volume_balance(const Mesh& mesh, const Topology& topology, const std::vector<double>& volumes,
                             const CellOrientation& orientation) {
  VolumeBalance out;
  Sum cells, enclosed;
  double scale = 0.0;
  for (double v : volumes) {
    cells.add(v);
    scale += std::abs(v);
  }
  // Relative to the middle of the bounding box: far from the origin the facet terms would be
  // large and cancel.
  const Eigen::VectorXd origin = mesh.n_nodes() ? Eigen::VectorXd(0.5 * (mesh.x.rowwise().minCoeff() + mesh.x.rowwise().maxCoeff()))
                                                : Eigen::VectorXd::Zero(mesh.dim);
  for (auto f : topology.boundary_facets) {
    const CellFacet& cf = topology.facets[static_cast<std::size_t>(f)][0];
    const auto [b, c] = topology.locate(cf.cell);
    const CellBlock& block = mesh.cells[b];
    const bool flipped = std::binary_search(orientation.flipped.begin(), orientation.flipped.end(), cf.cell);
    const double term = (flipped ? -1.0 : 1.0) *
                        facet_term(mesh, facet_type(block.type, cf.local), block.order, facet_nodes(block, c, cf.local), origin);
    enclosed.add(term);
    scale += std::abs(term);
  }
  out.cells = cells.value();
  out.enclosed = enclosed.value();
  out.scale = scale;
  return out;
}

void mirror_cells(Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& cells) {
  std::vector<std::vector<int>> perms(mesh.cells.size());
  std::vector<std::int32_t> old;
  for (auto cell : cells) {
    const auto [b, c] = topology.locate(cell);
    CellBlock& block = mesh.cells[b];
    if (perms[b].empty()) perms[b] = mirror_permutation(block.type, block.order);
    std::int32_t* v = block.cell(c);
    old.assign(v, v + block.n_nodes_per_cell());
    for (std::size_t i = 0; i < perms[b].size(); ++i) v[i] = old[static_cast<std::size_t>(perms[b][i])];
  }
}

}  // namespace meshmorph

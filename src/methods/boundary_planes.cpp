// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>

#include <Eigen/Geometry>

#include "meshmorph/fem/trace.h"
#include "meshmorph/methods/optimize.h"

namespace meshmorph {
namespace {

struct Plane {
  Eigen::VectorXd normal;  // unit; its largest component positive, so one plane has one key
  double offset = 0.0;     // normal · x on the plane
};

// The plane of a facet through its corner nodes, if every node of the facet lies on it.
std::optional<Plane> facet_plane(const Eigen::MatrixXd& x, const std::vector<std::int32_t>& nodes, int n_corners,
                                 double tol) {
  const int d = static_cast<int>(x.rows());
  const Eigen::VectorXd a = x.col(nodes[0]);
  Eigen::VectorXd n(d);
  if (d == 2) {
    const Eigen::VectorXd t = x.col(nodes[1]) - a;
    n << -t[1], t[0];
  } else {
    // Newell-like: the largest cross product of corner edge pairs is robust on quads.
    n.setZero();
    for (int i = 1; i + 1 < n_corners; ++i) {
      const Eigen::Vector3d u = x.col(nodes[i]) - a, v = x.col(nodes[i + 1]) - a;
      n += u.cross(v);
    }
  }
  if (!(n.norm() > 0.0)) return std::nullopt;
  n.normalize();
  Eigen::Index k;
  n.cwiseAbs().maxCoeff(&k);
  if (n[k] < 0.0) n = -n;
  const double offset = n.dot(a);
  for (std::int32_t node : nodes)
    if (std::abs(n.dot(x.col(node)) - offset) > tol) return std::nullopt;
  return Plane{n, offset};
}

}  // namespace

std::vector<FitTerm> planar_boundary_slides(const Mesh& mesh, const Topology& topology, std::vector<std::uint8_t>& fixed) {
  const int d = mesh.dim;
  const double size = (mesh.x.rowwise().maxCoeff() - mesh.x.rowwise().minCoeff()).norm();
  const double tol = 1e-10 * size;
  // Planes keyed by their rounded coefficients (1e-8 relative): facets of one plane meet here.
  std::map<std::array<long long, 4>, int> index;
  std::vector<Plane> planes;
  std::map<std::int32_t, std::vector<int>> node_planes;  // boundary node → planes (−1: a curved facet)
  for (std::int32_t f : topology.boundary_facets) {
    const CellFacet cf = topology.facets[static_cast<std::size_t>(f)][0];
    const auto [b, c] = topology.locate(cf.cell);
    const CellBlock& block = mesh.cells[b];
    const std::vector<std::int32_t> nodes = facet_nodes(block, c, cf.local);
    const int n_corners = static_cast<int>(corner_facets(block.type)[static_cast<std::size_t>(cf.local)].size());
    int id = -1;
    if (const std::optional<Plane> p = facet_plane(mesh.x, nodes, n_corners, tol)) {
      std::array<long long, 4> key{};
      for (int k = 0; k < d; ++k) key[static_cast<std::size_t>(k)] = std::llround(p->normal[k] * 1e8);
      key[3] = std::llround(p->offset / size * 1e8);
      const auto [it, added] = index.emplace(key, static_cast<int>(planes.size()));
      if (added) planes.push_back(*p);
      id = it->second;
    }
    for (std::int32_t node : nodes) {
      std::vector<int>& list = node_planes[node];
      if (std::find(list.begin(), list.end(), id) == list.end()) list.push_back(id);
    }
  }
  std::vector<std::vector<std::int32_t>> members(planes.size());
  for (const auto& [node, list] : node_planes) {
    const bool curved = std::find(list.begin(), list.end(), -1) != list.end();
    const bool slides = !curved && static_cast<int>(list.size()) < d &&
                        (list.size() < 2 || std::abs(planes[static_cast<std::size_t>(list[0])].normal.dot(
                                                planes[static_cast<std::size_t>(list[1])].normal)) < 1.0 - 1e-12);
    for (int k = 0; k < d; ++k) fixed[static_cast<std::size_t>(d * node + k)] = slides ? 0 : 1;
    if (slides)
      for (int id : list) members[static_cast<std::size_t>(id)].push_back(node);
  }
  std::vector<FitTerm> terms;
  for (std::size_t i = 0; i < planes.size(); ++i) {
    if (members[i].empty()) continue;
    LevelSet ls{PlaneLevelSet{planes[i].normal * planes[i].offset, planes[i].normal}, "boundary plane"};
    terms.push_back({LevelSetFunction(ls, d), std::move(members[i])});  // map order: sorted
  }
  return terms;
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include <Eigen/Geometry>

#include "meshmorph/fem/lagrange_basis.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/geometry/facet_surface.h"
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

struct BoundaryFacet {
  std::int32_t id = 0;                 // into topology.facets
  std::vector<std::int32_t> nodes;     // the facet element's ordering
  const LagrangeBasis* basis = nullptr;
  int n_corners = 0, plane = -1;       // plane: index of its plane, −1 when curved
};

int root(std::vector<int>& parent, int i) {
  while (parent[static_cast<std::size_t>(i)] != i) i = parent[static_cast<std::size_t>(i)] = parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(i)])];
  return i;
}

}  // namespace

std::vector<FitTerm> boundary_slides(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& facets,
                                     double feature_angle, bool curved, std::vector<std::uint8_t>& fixed) {
  const int d = mesh.dim;
  const double size = (mesh.x.rowwise().maxCoeff() - mesh.x.rowwise().minCoeff()).norm();
  const double tol = 1e-10 * size;
  // Planes keyed by their rounded coefficients (1e-8 relative): facets of one plane meet here.
  std::map<std::array<long long, 4>, int> plane_index;
  std::vector<Plane> planes;
  std::vector<BoundaryFacet> bf;
  // Corner edges (3D, by their corner nodes) or corners (2D: (node, node)) → (facet, local index).
  std::map<std::pair<std::int32_t, std::int32_t>, std::vector<std::pair<int, int>>> joints;
  for (std::int32_t id : facets) {
    const CellFacet cf = topology.facets[static_cast<std::size_t>(id)][0];
    const auto [b, c] = topology.locate(cf.cell);
    const CellBlock& block = mesh.cells[b];
    BoundaryFacet f{id, facet_nodes(block, c, cf.local), &lagrange_basis(facet_type(block.type, cf.local), block.order)};
    f.n_corners = static_cast<int>(corner_facets(block.type)[static_cast<std::size_t>(cf.local)].size());
    if (const std::optional<Plane> p = facet_plane(mesh.x, f.nodes, f.n_corners, tol)) {
      std::array<long long, 4> key{};
      for (int k = 0; k < d; ++k) key[static_cast<std::size_t>(k)] = std::llround(p->normal[k] * 1e8);
      key[3] = std::llround(p->offset / size * 1e8);
      const auto [it, added] = plane_index.emplace(key, static_cast<int>(planes.size()));
      if (added) planes.push_back(*p);
      f.plane = it->second;
    }
    for (int k = 0; k < f.n_corners; ++k) {
      const std::int32_t a = f.nodes[static_cast<std::size_t>(k)];
      const std::int32_t e = d == 2 ? a : f.nodes[static_cast<std::size_t>((k + 1) % f.n_corners)];
      joints[{std::min(a, e), std::max(a, e)}].emplace_back(static_cast<int>(bf.size()), k);
    }
    bf.push_back(std::move(f));
  }
  // The outward normal of facet i at the midpoint of its reference edge k (3D) or corner k (2D).
  auto normal_at = [&](int i, int k) {
    const BoundaryFacet& f = bf[static_cast<std::size_t>(i)];
    const Eigen::MatrixXd& ref = f.basis->reference().nodes;
    const Eigen::VectorXd u = d == 2 ? Eigen::VectorXd(ref.col(k)) : Eigen::VectorXd(0.5 * (ref.col(k) + ref.col((k + 1) % f.n_corners)));
    return outward_normal(mesh.x(Eigen::all, f.nodes) * f.basis->gradients(u));
  };
  // Patches: facets joined across joints where their normals turn by at most feature_angle.
  const double cos_feature = std::cos(feature_angle * M_PI / 180.0);
  std::vector<int> parent(bf.size());
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<std::pair<std::int32_t, std::int32_t>> sharp;
  for (const auto& joint : joints) {
    const auto& uses = joint.second;  // not a structured binding: clang before 16 cannot capture one
    // Planes only: facets join when they lie on one plane (a patch is then a plane).
    const auto joins = [&](int i, int j) {
      return curved ? normal_at(i, uses[0].second).dot(normal_at(j, uses[1].second)) >= cos_feature
                    : bf[static_cast<std::size_t>(i)].plane >= 0 && bf[static_cast<std::size_t>(i)].plane == bf[static_cast<std::size_t>(j)].plane;
    };
    if (uses.size() == 2 && joins(uses[0].first, uses[1].first)) {
      parent[static_cast<std::size_t>(root(parent, uses[0].first))] = root(parent, uses[1].first);
    } else if (uses.size() > 1) {
      sharp.push_back(joint.first);
    }
  }
  std::map<int, int> patch_of_root;
  std::vector<int> patch(bf.size());
  for (std::size_t i = 0; i < bf.size(); ++i)
    patch[i] = patch_of_root.emplace(root(parent, static_cast<int>(i)), static_cast<int>(patch_of_root.size())).first->second;
  const std::size_t n_patches = patch_of_root.size();
  // Nodes on a sharp joint inside one patch (a crease that dies out) have no smooth surface: fixed.
  std::vector<std::uint8_t> creased(mesh.n_nodes(), 0);
  for (const auto& key : sharp) {
    const auto& uses = joints[key];
    bool one_patch = true;
    for (const auto& [i, k] : uses) one_patch = one_patch && patch[static_cast<std::size_t>(i)] == patch[static_cast<std::size_t>(uses[0].first)];
    if (!one_patch) continue;
    for (const auto& [i, k] : uses) {
      // The facet's nodes on its reference edge k (3D), or its corner k (2D).
      const BoundaryFacet& f = bf[static_cast<std::size_t>(i)];
      const Eigen::MatrixXd& ref = f.basis->reference().nodes;
      const Eigen::VectorXd a = ref.col(k), e = d == 2 ? Eigen::VectorXd(Eigen::VectorXd::Zero(a.size())) : Eigen::VectorXd(ref.col((k + 1) % f.n_corners) - a);
      for (Eigen::Index j = 0; j < ref.cols(); ++j) {
        const Eigen::VectorXd v = ref.col(j) - a;
        const double t = d == 2 ? 0.0 : std::clamp(v.dot(e) / e.squaredNorm(), 0.0, 1.0);
        if ((v - t * e).norm() < 1e-12) creased[static_cast<std::size_t>(f.nodes[static_cast<std::size_t>(j)])] = 1;
      }
    }
  }
  // A patch is planar when all its facets lie on one plane.
  std::vector<int> patch_plane(n_patches, -2);  // −2: none seen yet, −1: not one plane
  std::vector<std::vector<std::int32_t>> patch_facets(n_patches);
  std::map<std::int32_t, std::vector<int>> node_patches;
  for (std::size_t i = 0; i < bf.size(); ++i) {
    int& pp = patch_plane[static_cast<std::size_t>(patch[i])];
    pp = pp == -2 || pp == bf[i].plane ? bf[i].plane : -1;
    patch_facets[static_cast<std::size_t>(patch[i])].push_back(bf[i].id);
    for (std::int32_t node : bf[i].nodes) {
      std::vector<int>& list = node_patches[node];
      if (std::find(list.begin(), list.end(), patch[i]) == list.end()) list.push_back(patch[i]);
    }
  }
  std::vector<std::optional<LevelSetFunction>> sigma(n_patches);
  auto level_set = [&](int k) -> const LevelSetFunction& {
    std::optional<LevelSetFunction>& s = sigma[static_cast<std::size_t>(k)];
    if (!s) {
      if (const int p = patch_plane[static_cast<std::size_t>(k)]; p >= 0) {
        const Plane& pl = planes[static_cast<std::size_t>(p)];
        s.emplace(LevelSet{PlaneLevelSet{pl.normal * pl.offset, pl.normal}, "boundary plane"}, d);
      } else {
        s.emplace(facet_surface(mesh, topology, patch_facets[static_cast<std::size_t>(k)]));
      }
    }
    return *s;
  };
  // One patch: slide on it; two (3D): on their common curve, unless they are tangent there.
  std::vector<std::vector<std::int32_t>> members(n_patches);
  for (const auto& [node, list] : node_patches) {
    bool slides = !creased[static_cast<std::size_t>(node)] && static_cast<int>(list.size()) < d;
    for (int id : list) slides = slides && (curved || patch_plane[static_cast<std::size_t>(id)] >= 0);
    if (slides && list.size() == 2) {
      const Eigen::VectorXd p = mesh.x.col(node);
      slides = std::abs(level_set(list[0]).gradient(p).dot(level_set(list[1]).gradient(p))) < 1.0 - 1e-12;
    }
    for (int k = 0; k < d; ++k) fixed[static_cast<std::size_t>(d * node + k)] = slides ? 0 : 1;
    if (slides)
      for (int id : list) members[static_cast<std::size_t>(id)].push_back(node);
  }
  std::vector<FitTerm> terms;
  for (std::size_t k = 0; k < n_patches; ++k)
    if (!members[k].empty()) terms.push_back({level_set(static_cast<int>(k)), std::move(members[k])});  // map order: sorted
  return terms;
}

}  // namespace meshmorph

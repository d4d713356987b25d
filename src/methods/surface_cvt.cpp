// SPDX-License-Identifier: MIT
#include "meshmorph/methods/surface_cvt.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>

#include <Eigen/Geometry>

#include "meshmorph/error.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/geometry/closest_on_simplex.h"

namespace meshmorph {
namespace {

// Linear sub-facets of one facet (nodes in the facet element's Gmsh ordering), appended to out.
void split_facet(ElementType type, int order, const std::vector<std::int32_t>& v, std::vector<std::int32_t>& out) {
  auto tri = [&](int a, int b, int c) { out.insert(out.end(), {v[static_cast<std::size_t>(a)], v[static_cast<std::size_t>(b)], v[static_cast<std::size_t>(c)]}); };
  if (type == ElementType::Line) {
    // Gmsh: the two ends, then the interior nodes from the first end to the second.
    std::vector<std::int32_t> chain{v[0]};
    for (int k = 2; k <= order; ++k) chain.push_back(v[static_cast<std::size_t>(k)]);
    chain.push_back(v[1]);
    for (std::size_t k = 0; k + 1 < chain.size(); ++k) out.insert(out.end(), {chain[k], chain[k + 1]});
    return;
  }
  if (type == ElementType::Triangle && order == 1) return tri(0, 1, 2);
  if (type == ElementType::Triangle && order == 2) {
    tri(0, 3, 5), tri(3, 1, 4), tri(5, 4, 2), tri(3, 4, 5);
    return;
  }
  if (type == ElementType::Quadrilateral && order == 1) {
    tri(0, 1, 2), tri(0, 2, 3);
    return;
  }
  if (type == ElementType::Quadrilateral && order == 2) {
    for (const auto& q : {std::array{0, 4, 8, 7}, std::array{4, 1, 5, 8}, std::array{8, 5, 2, 6}, std::array{7, 8, 6, 3}})
      tri(q[0], q[1], q[2]), tri(q[0], q[2], q[3]);
    return;
  }
  throw InputError("deform: the CVT step handles boundary facets of order 1 and 2 only (found a " +
                   std::string(name_of(type)) + " of order " + std::to_string(order) + ")");
}

// The closest point of facet f (nodes at x) to p, in 3D (z = 0 in 2D).
Eigen::Vector3d closest_on_facet(const DesignSurface& s, std::size_t f, const Eigen::MatrixXd& x, const Eigen::Vector3d& p) {
  const std::int32_t* v = s.facets.data() + f * static_cast<std::size_t>(s.dim);
  const auto node = [&](int k) { return padded_3d(x.col(v[k])); };
  return s.dim == 2 ? closest_on_segment(p, node(0), node(1)) : closest_on_triangle(p, node(0), node(1), node(2));
}

// Measure, centroid and area-weighted normal (normal · measure) of facet f at positions x.
struct FacetGeometry {
  double measure = 0.0;
  Eigen::VectorXd centroid, normal;
};

FacetGeometry facet_geometry(const DesignSurface& s, std::size_t f, const Eigen::MatrixXd& x) {
  const std::int32_t* v = s.facets.data() + f * static_cast<std::size_t>(s.dim);
  FacetGeometry g;
  if (s.dim == 2) {
    const Eigen::Vector2d t = x.col(v[1]) - x.col(v[0]);
    g.measure = t.norm();
    g.centroid = 0.5 * (x.col(v[0]) + x.col(v[1]));
    g.normal = Eigen::Vector2d(t[1], -t[0]);  // the cell is on the left of a boundary segment
  } else {
    const Eigen::Vector3d a = x.col(v[0]), b = x.col(v[1]), c = x.col(v[2]);
    g.normal = 0.5 * (b - a).cross(c - a);
    g.measure = g.normal.norm();
    g.centroid = (a + b + c) / 3.0;
  }
  return g;
}

}  // namespace

DesignSurface design_surface(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& on_design) {
  DesignSurface s;
  s.dim = mesh.dim;
  for (std::int32_t f : topology.boundary_facets) {
    const CellFacet& cf = topology.facets[static_cast<std::size_t>(f)][0];
    const auto [bi, c] = topology.locate(cf.cell);
    const CellBlock& block = mesh.cells[bi];
    const std::vector<std::int32_t> nodes = facet_nodes(block, c, cf.local);
    if (std::all_of(nodes.begin(), nodes.end(), [&](std::int32_t v) { return on_design[static_cast<std::size_t>(v)] != 0; }))
      split_facet(facet_type(block.type, cf.local), block.order, nodes, s.facets);
  }
  return s;
}

double spacing_ratio(const DesignSurface& s, const Eigen::MatrixXd& x) {
  double lo = std::numeric_limits<double>::max(), hi = 0.0;
  for (std::size_t f = 0; f < s.n_facets(); ++f) {
    const std::int32_t* v = s.facets.data() + f * static_cast<std::size_t>(s.dim);
    for (int k = 0; k < (s.dim == 2 ? 1 : 3); ++k) {
      const double l = (x.col(v[k]) - x.col(v[(k + 1) % s.dim])).norm();
      lo = std::min(lo, l);
      hi = std::max(hi, l);
    }
  }
  return hi > 0.0 ? hi / lo : 1.0;
}

double distance_to_surface(const DesignSurface& s, const Eigen::MatrixXd& x, const Eigen::VectorXd& p) {
  double best = std::numeric_limits<double>::infinity();
  const Eigen::Vector3d p3 = padded_3d(p);
  for (std::size_t f = 0; f < s.n_facets(); ++f) best = std::min(best, (closest_on_facet(s, f, x, p3) - p3).norm());
  return best;
}

CvtResult surface_cvt(const DesignSurface& s, const Eigen::MatrixXd& x, const Eigen::MatrixXd& reference,
                      const std::vector<std::uint8_t>& pinned_nodes, const CvtOptions& options,
                      const SurfaceProjection& projection) {
  const int d = s.dim;
  const std::size_t n_facets = s.n_facets();
  CvtResult result;
  result.x = x;
  if (n_facets == 0) {
    result.converged = true;
    return result;
  }
  // node → facets (CSR over all mesh nodes; most are off the surface).
  const auto n_nodes = static_cast<std::size_t>(x.cols());
  std::vector<std::int32_t> offset(n_nodes + 1, 0), adjacent;
  for (std::int32_t v : s.facets) ++offset[static_cast<std::size_t>(v) + 1];
  for (std::size_t i = 0; i < n_nodes; ++i) offset[i + 1] += offset[i];
  adjacent.resize(s.facets.size());
  {
    std::vector<std::int32_t> fill(offset.begin(), offset.end() - 1);
    for (std::size_t f = 0; f < n_facets; ++f)
      for (int k = 0; k < d; ++k)
        adjacent[static_cast<std::size_t>(fill[static_cast<std::size_t>(s.facets[f * d + k])]++)] = static_cast<std::int32_t>(f);
  }
  std::vector<std::int32_t> nodes;
  for (std::size_t i = 0; i < n_nodes; ++i)
    if (offset[i + 1] > offset[i]) nodes.push_back(static_cast<std::int32_t>(i));

  std::vector<FacetGeometry> input(n_facets);
  std::vector<double> rho(n_facets, 1.0);
  for (std::size_t f = 0; f < n_facets; ++f) {
    input[f] = facet_geometry(s, f, x);
    if (options.density == CvtDensity::Input)
      rho[f] = std::pow(std::max(facet_geometry(s, f, reference).measure, 1e-300), -static_cast<double>(d) / (d - 1));
  }

  // Pinned: the rim (an edge of one facet; in 2D a node of one segment), features, and nodes
  // the caller holds.
  std::vector<std::uint8_t> pinned(n_nodes, 0);
  const double cos_feature = std::cos(options.feature_angle * M_PI / 180.0);
  for (std::int32_t i : nodes) {
    const auto ui = static_cast<std::size_t>(i);
    if (pinned_nodes[ui]) pinned[ui] = 1;
    Eigen::VectorXd normal = Eigen::VectorXd::Zero(d);
    for (std::int32_t k = offset[ui]; k < offset[ui + 1]; ++k) normal += input[static_cast<std::size_t>(adjacent[static_cast<std::size_t>(k)])].normal;
    for (std::int32_t k = offset[ui]; k < offset[ui + 1]; ++k) {
      const FacetGeometry& g = input[static_cast<std::size_t>(adjacent[static_cast<std::size_t>(k)])];
      if (!(g.normal.dot(normal) > cos_feature * g.normal.norm() * normal.norm())) pinned[ui] = 1;
    }
    if (d == 2 && offset[ui + 1] - offset[ui] != 2) pinned[ui] = 1;
    if (d == 3)  // an edge i–j used by one facet is on the rim
      for (std::int32_t k = offset[ui]; k < offset[ui + 1]; ++k) {
        const std::int32_t* v = s.facets.data() + static_cast<std::size_t>(adjacent[static_cast<std::size_t>(k)]) * 3;
        for (int e = 0; e < 3; ++e) {
          if (v[e] != i) continue;
          for (std::int32_t j : {v[(e + 1) % 3], v[(e + 2) % 3]}) {
            int shared = 0;
            for (std::int32_t m = offset[ui]; m < offset[ui + 1]; ++m) {
              const std::int32_t* w = s.facets.data() + static_cast<std::size_t>(adjacent[static_cast<std::size_t>(m)]) * 3;
              shared += (w[0] == j || w[1] == j || w[2] == j);
            }
            if (shared < 2) pinned[ui] = 1;
          }
        }
      }
  }
  for (std::int32_t i : nodes) result.pinned += pinned[static_cast<std::size_t>(i)];

  // Closest point on the input surface, walking from `host` over the facets that share a node
  // with it; the walk stops when the host is the closest of its neighbourhood.
  std::vector<std::int32_t> host(n_nodes, -1);
  for (std::int32_t i : nodes) host[static_cast<std::size_t>(i)] = adjacent[static_cast<std::size_t>(offset[static_cast<std::size_t>(i)])];
  auto project_discrete = [&](std::int32_t i, const Eigen::VectorXd& p_d) -> Eigen::VectorXd {
    std::int32_t& h = host[static_cast<std::size_t>(i)];
    const Eigen::Vector3d p = padded_3d(p_d);
    Eigen::Vector3d best = closest_on_facet(s, static_cast<std::size_t>(h), x, p);
    for (int walk = 0; walk < 1000; ++walk) {
      std::int32_t next = h;
      const std::int32_t* v = s.facets.data() + static_cast<std::size_t>(h) * d;
      for (int k = 0; k < d; ++k)
        for (std::int32_t m = offset[static_cast<std::size_t>(v[k])]; m < offset[static_cast<std::size_t>(v[k]) + 1]; ++m) {
          const std::int32_t f = adjacent[static_cast<std::size_t>(m)];
          const Eigen::Vector3d cand = closest_on_facet(s, static_cast<std::size_t>(f), x, p);
          if ((cand - p).squaredNorm() < (best - p).squaredNorm() * (1.0 - 1e-14)) best = cand, next = f;
        }
      if (next == h) break;
      h = next;
    }
    return best.head(d);
  };

  double mean_edge = 0.0;
  for (std::size_t f = 0; f < n_facets; ++f) mean_edge += d == 2 ? input[f].measure : std::sqrt(2.0 * input[f].measure);
  mean_edge /= static_cast<double>(n_facets);
  result.spacing_ratio_before = spacing_ratio(s, x);

  Eigen::MatrixXd& y = result.x;
  std::vector<FacetGeometry> geometry(n_facets);
  Eigen::MatrixXd next = y;
  for (int it = 1; it <= options.max_iterations; ++it) {
    for (std::size_t f = 0; f < n_facets; ++f) geometry[f] = facet_geometry(s, f, y);
    double update = 0.0;
    // Thousands of cheap sweeps: threads pay off on large surfaces only (barriers cost more
    // than the work below a few thousand nodes, and spin long on a loaded machine).
#pragma omp parallel for schedule(static) reduction(max : update) if (nodes.size() >= 4096)
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      const std::int32_t i = nodes[k];
      const auto ui = static_cast<std::size_t>(i);
      if (pinned[ui]) continue;
      Eigen::VectorXd num = Eigen::VectorXd::Zero(d), normal = Eigen::VectorXd::Zero(d);
      double den = 0.0;
      for (std::int32_t m = offset[ui]; m < offset[ui + 1]; ++m) {
        const auto f = static_cast<std::size_t>(adjacent[static_cast<std::size_t>(m)]);
        const double mass = rho[f] * geometry[f].measure;
        num += mass * (geometry[f].centroid - y.col(i));
        den += mass;
        normal += geometry[f].normal;
      }
      if (!(den > 0.0) || !(normal.norm() > 0.0)) continue;
      normal.normalize();
      const Eigen::VectorXd tau = (num - normal * normal.dot(num)) / den;  // eq. 3.5: P_i (x* − x_i)
      Eigen::VectorXd p = y.col(i) + tau;
      std::optional<Eigen::VectorXd> exact = projection ? projection(i, p) : std::nullopt;
      p = exact ? *exact : project_discrete(i, p);
      update = std::max(update, (p - y.col(i)).norm());
      next.col(i) = p;
    }
    y = next;
    result.iterations = it;
    result.last_update = update / mean_edge;
    if (result.last_update <= options.tolerance) {
      result.converged = true;
      break;
    }
  }
  result.spacing_ratio_after = spacing_ratio(s, y);
  return result;
}

}  // namespace meshmorph

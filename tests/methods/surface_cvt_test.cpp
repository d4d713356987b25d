// SPDX-License-Identifier: MIT
#include "meshmorph/methods/surface_cvt.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "methods/deform_meshes.h"

namespace meshmorph {
namespace {

std::vector<std::uint8_t> mask(std::size_t n, const std::vector<std::int32_t>& nodes) {
  std::vector<std::uint8_t> m(n, 0);
  for (std::int32_t v : nodes) m[static_cast<std::size_t>(v)] = 1;
  return m;
}

// Enclosed area (2D, segments with the domain on their left) or volume (3D) of a closed
// surface, by the divergence theorem.
double enclosed(const DesignSurface& s, const Eigen::MatrixXd& x) {
  double sum = 0.0;
  for (std::size_t f = 0; f < s.n_facets(); ++f) {
    const std::int32_t* v = s.facets.data() + f * static_cast<std::size_t>(s.dim);
    if (s.dim == 2) sum += 0.5 * (x(0, v[0]) * x(1, v[1]) - x(0, v[1]) * x(1, v[0]));
    else sum += Eigen::Vector3d(x.col(v[0])).dot(Eigen::Vector3d(x.col(v[1])).cross(Eigen::Vector3d(x.col(v[2])))) / 6.0;
  }
  return sum;
}

SurfaceProjection onto_unit_sphere() {
  return [](std::int32_t, const Eigen::VectorXd& p) -> std::optional<Eigen::VectorXd> { return p.normalized(); };
}

// Nodes of a flat side bunched by x → x − 0.9 sin(2πx)/(2π) inside it (the rim is pinned, so
// it keeps its spacing) stay on the plane and spread out more evenly.
TEST(SurfaceCvt, StaysOnAPlaneAndEqualizesTheSpacing) {
  for (ElementType type : {ElementType::Triangle, ElementType::Tetrahedron}) {
    SCOPED_TRACE(name_of(type));
    Mesh mesh = structured_mesh(type, 1, 8);
    const Topology topo = build_topology(mesh);
    const std::vector<std::int32_t> bottom = mesh.group_nodes(*mesh.find_group("bottom"));
    const int normal_axis = mesh.dim - 1;
    for (std::int32_t v : bottom) {
      const auto in_plane = mesh.x.col(v).head(mesh.dim - 1).array();
      if ((in_plane > 0.0).all() && (in_plane < 1.0).all())
        for (int k = 0; k < mesh.dim - 1; ++k) mesh.x(k, v) -= 0.9 * std::sin(2 * M_PI * mesh.x(k, v)) / (2 * M_PI);
    }
    const DesignSurface s = design_surface(mesh, topo, mask(mesh.n_nodes(), bottom));
    ASSERT_EQ(s.n_facets(), mesh.dim == 2 ? 8u : 128u);
    const CvtResult r = surface_cvt(s, mesh.x, mesh.x, std::vector<std::uint8_t>(mesh.n_nodes(), 0));
    EXPECT_TRUE(r.converged);
    for (std::int32_t v : bottom) EXPECT_LE(std::abs(r.x(normal_axis, v)), 1e-10);
    EXPECT_LT(r.spacing_ratio_after, 0.5 * r.spacing_ratio_before);
    if (mesh.dim == 2) {
      EXPECT_LT(r.spacing_ratio_after, 1.01);
    }
    for (Eigen::Index j = 0; j < mesh.x.cols(); ++j)  // nodes off the surface do not move
      if (std::find(bottom.begin(), bottom.end(), j) == bottom.end()) {
        EXPECT_TRUE(r.x.col(j) == mesh.x.col(j)) << j;
      }
  }
}

// Nodes of a circle or a sphere, pulled towards one side: with the exact projection they stay
// on it to rounding; with the discrete surface the enclosed area or volume changes by less
// than the gap between the polygon and the circle (discretization accuracy).
TEST(SurfaceCvt, StaysOnACircleOrSphereAndKeepsTheEnclosedMeasure) {
  for (ElementType type : {ElementType::Triangle, ElementType::Tetrahedron}) {
    SCOPED_TRACE(name_of(type));
    Mesh mesh = testing::ball_mesh(type, 1, type == ElementType::Triangle ? 16 : 6);
    const Topology topo = build_topology(mesh);
    const std::vector<std::int32_t> boundary = boundary_nodes(mesh, topo);
    const Eigen::VectorXd pole = Eigen::VectorXd::Unit(mesh.dim, 0);
    for (std::int32_t v : boundary) {
      const Eigen::VectorXd p = mesh.x.col(v);
      mesh.x.col(v) = (p + 0.4 * (pole - pole.dot(p) * p)).normalized();
    }
    const DesignSurface s = design_surface(mesh, topo, mask(mesh.n_nodes(), boundary));
    const std::vector<std::uint8_t> none(mesh.n_nodes(), 0);
    CvtOptions o;
    o.feature_angle = 60.0;  // the coarse sphere turns by up to ~25° at a node
    const CvtResult exact = surface_cvt(s, mesh.x, mesh.x, none, o, onto_unit_sphere());
    EXPECT_EQ(exact.pinned, 0u);
    for (std::int32_t v : boundary) EXPECT_LE(std::abs(exact.x.col(v).norm() - 1.0), 1e-10);
    // The coarse sphere's connectivity (valence 4 to 8) bounds how even it can get.
    EXPECT_LT(exact.spacing_ratio_after, 0.7 * exact.spacing_ratio_before);

    const CvtResult discrete = surface_cvt(s, mesh.x, mesh.x, none, o);
    const double before = enclosed(s, mesh.x), after = enclosed(s, discrete.x);
    const double exact_measure = mesh.dim == 2 ? M_PI : 4.0 * M_PI / 3.0;
    EXPECT_LT(std::abs(after - before), std::abs(exact_measure - before)) << before << " " << after;
    EXPECT_LT(discrete.spacing_ratio_after, 0.7 * discrete.spacing_ratio_before);
  }
}

// The lateral surface of a cylinder: on it to rounding with the exact projection, its rims
// (the edges on the end caps) pinned.
TEST(SurfaceCvt, StaysOnACylinder) {
  Mesh mesh = structured_mesh(ElementType::Tetrahedron, 1, 6);
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j) {
    const double u = 2 * mesh.x(0, j) - 1, v = 2 * mesh.x(1, j) - 1;
    mesh.x(0, j) = u * std::sqrt(1 - v * v / 2);
    mesh.x(1, j) = v * std::sqrt(1 - u * u / 2);
  }
  const Topology topo = build_topology(mesh);
  std::vector<std::uint8_t> lateral(mesh.n_nodes(), 0);
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j) lateral[static_cast<std::size_t>(j)] = std::abs(mesh.x.col(j).head<2>().norm() - 1) < 1e-12;
  DesignSurface s = design_surface(mesh, topo, lateral);
  DesignSurface side{3, {}};  // drop the cap triangles whose three nodes are on the rim
  for (std::size_t f = 0; f < s.n_facets(); ++f) {
    const std::int32_t* v = s.facets.data() + 3 * f;
    const double z0 = mesh.x(2, v[0]);
    if (mesh.x(2, v[1]) == z0 && mesh.x(2, v[2]) == z0) continue;
    side.facets.insert(side.facets.end(), v, v + 3);
  }
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j)
    if (lateral[static_cast<std::size_t>(j)] && mesh.x(2, j) > 0 && mesh.x(2, j) < 1) mesh.x(2, j) = std::pow(mesh.x(2, j), 1.5);
  const SurfaceProjection onto_cylinder = [](std::int32_t, const Eigen::VectorXd& p) -> std::optional<Eigen::VectorXd> {
    Eigen::VectorXd q = p;
    q.head<2>().normalize();
    return q;
  };
  CvtOptions o;
  o.feature_angle = 60.0;
  const CvtResult r = surface_cvt(side, mesh.x, mesh.x, std::vector<std::uint8_t>(mesh.n_nodes(), 0), o, onto_cylinder);
  EXPECT_GT(r.pinned, 0u);
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j)
    if (lateral[static_cast<std::size_t>(j)]) {
      EXPECT_LE(std::abs(r.x.col(j).head<2>().norm() - 1.0), 1e-10);
      if (mesh.x(2, j) == 0.0 || mesh.x(2, j) == 1.0) {
        EXPECT_EQ(r.x(2, j), mesh.x(2, j));  // rims pinned
      }
    }
  EXPECT_LT(r.spacing_ratio_after, r.spacing_ratio_before);
}

// With the input density, the input spacing of a graded line is a fixed point (exactly in
// 1D: ρ_e l_e² is the same on both sides of every node).
TEST(SurfaceCvt, InputDensityKeepsTheInputSpacing) {
  Mesh mesh = structured_mesh(ElementType::Triangle, 1, 8);
  const Topology topo = build_topology(mesh);
  const std::vector<std::int32_t> bottom = mesh.group_nodes(*mesh.find_group("bottom"));
  for (std::int32_t v : bottom) mesh.x(0, v) = std::pow(mesh.x(0, v), 2);
  const DesignSurface s = design_surface(mesh, topo, mask(mesh.n_nodes(), bottom));
  CvtOptions o;
  o.density = CvtDensity::Input;
  const CvtResult r = surface_cvt(s, mesh.x, mesh.x, std::vector<std::uint8_t>(mesh.n_nodes(), 0), o);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_LT((r.x - mesh.x).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(SurfaceCvt, SplitsOrderTwoFacets) {
  const Mesh mesh = testing::ball_mesh(ElementType::Triangle, 2, 4);
  const Topology topo = build_topology(mesh);
  const std::vector<std::int32_t> boundary = boundary_nodes(mesh, topo);
  const DesignSurface s = design_surface(mesh, topo, mask(mesh.n_nodes(), boundary));
  EXPECT_EQ(s.n_facets(), 32u);  // 16 P2 segments, 2 linear pieces each
}

}  // namespace
}  // namespace meshmorph

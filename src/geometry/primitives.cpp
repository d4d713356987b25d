// SPDX-License-Identifier: MIT
// Closed forms of the analytic level sets. Each σ is the exact signed distance, so the
// closest point is x − σ(x)·∇σ(x) wherever ∇σ is defined; the degenerate points (a
// sphere's centre, a cylinder's axis, ...) pick a fixed direction so results are
// deterministic. The Hessian of a distance is the derivative of its unit gradient n,
// (I − n nᵀ)·(∂(x − foot point)/∂x)/distance; there it is NaN.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include <Eigen/Geometry>

#include "geometry/detail/level_set_node.h"

namespace meshmorph::detail {

namespace {

// A unit vector orthogonal to the unit vector a (3D).
Vec any_perpendicular(const Vec& a) {
  Eigen::Vector3d e = Eigen::Vector3d::Zero();
  Eigen::Index k = 0;
  a.cwiseAbs().minCoeff(&k);
  e(k) = 1;
  Eigen::Vector3d p = e - e.dot(a) * Eigen::Vector3d(a);
  return p.normalized();
}

// Unit v/|v|, or e₁ when v = 0.
Vec direction_or_first_axis(const Vec& v) {
  const double n = v.norm();
  if (n > 0) return v / n;
  Vec e = Vec::Zero(v.size());
  e(0) = 1;
  return e;
}

class Sphere final : public LevelSetNode {
 public:
  Sphere(Vec c, double r) : c_(std::move(c)), r_(r) {}
  double value(const Vec& x) const override { return (x - c_).norm() - r_; }
  double value_gradient(const Vec& x, Vec& g) const override {
    g = direction_or_first_axis(x - c_);
    return (x - c_).norm() - r_;
  }
  Eigen::MatrixXd hessian(const Vec& x) const override {
    const Vec v = x - c_;
    const double r = v.norm();
    if (!(r > 0)) return undefined_hessian(x.size());
    const Vec n = v / r;
    return (Eigen::MatrixXd::Identity(x.size(), x.size()) - n * n.transpose()) / r;
  }
  std::optional<Vec> closest_point(const Vec& x) const override {
    return Vec(c_ + r_ * direction_or_first_axis(x - c_));
  }

 private:
  Vec c_;
  double r_;
};

class Cylinder final : public LevelSetNode {
 public:
  Cylinder(Vec c, Vec axis, double r) : c_(std::move(c)), a_(axis.stableNormalized()), r_(r) {}
  double value(const Vec& x) const override { return ((x - c_) - (x - c_).dot(a_) * a_).norm() - r_; }
  double value_gradient(const Vec& x, Vec& g) const override {
    const Vec v = radial(x);
    g = direction(v);
    return v.norm() - r_;
  }
  // (I − a aᵀ − n nᵀ)/|v⊥|: the axis direction and the normal are flat.
  Eigen::MatrixXd hessian(const Vec& x) const override {
    const Vec v = radial(x);
    const double r = v.norm();
    if (!(r > 0)) return undefined_hessian(x.size());
    const Vec n = v / r;
    return (Eigen::MatrixXd::Identity(x.size(), x.size()) - a_ * a_.transpose() - n * n.transpose()) / r;
  }
  std::optional<Vec> closest_point(const Vec& x) const override {
    const Vec v = radial(x);
    return Vec(x - v + r_ * direction(v));
  }

 private:
  // Component of x − c orthogonal to the axis.
  Vec radial(const Vec& x) const {
    const Vec v = x - c_;
    return v - v.dot(a_) * a_;
  }
  Vec direction(const Vec& v) const {
    const double n = v.norm();
    return n > 0 ? Vec(v / n) : any_perpendicular(a_);
  }
  Vec c_, a_;
  double r_;
};

class Plane final : public LevelSetNode {
 public:
  Plane(Vec p, Vec n) : p_(std::move(p)), n_(n.stableNormalized()) {}
  double value(const Vec& x) const override { return (x - p_).dot(n_); }
  double value_gradient(const Vec& x, Vec& g) const override {
    g = n_;
    return (x - p_).dot(n_);
  }
  Eigen::MatrixXd hessian(const Vec& x) const override { return Eigen::MatrixXd::Zero(x.size(), x.size()); }
  std::optional<Vec> closest_point(const Vec& x) const override { return Vec(x - (x - p_).dot(n_) * n_); }

 private:
  Vec p_, n_;
};

// Axis-aligned box with half edge lengths h: q = |x − c| − h per axis; outside
// σ = |max(q, 0)|, inside σ = max_k q_k (the nearest face).
class Box final : public LevelSetNode {
 public:
  Box(Vec c, const Vec& size) : c_(std::move(c)), h_(size / 2) {}
  // Without the gradient's temporaries: CSG indicators evaluate boxes millions of times.
  double value(const Vec& x) const override {
    double outside2 = 0.0, inside = -std::numeric_limits<double>::infinity();
    for (Eigen::Index k = 0; k < x.size(); ++k) {
      const double q = std::abs(x(k) - c_(k)) - h_(k);
      if (q > 0) outside2 += q * q;
      inside = std::max(inside, q);
    }
    return outside2 > 0 ? std::sqrt(outside2) : inside;
  }
  double value_gradient(const Vec& x, Vec& g) const override {
    const Vec v = x - c_;
    const Vec q = v.cwiseAbs() - h_;
    const Vec s = v.unaryExpr([](double t) { return t < 0 ? -1.0 : 1.0; });
    const Vec outside = q.cwiseMax(0.0);
    const double d = outside.norm();
    if (d > 0) {
      g = s.cwiseProduct(outside) / d;
      return d;
    }
    Eigen::Index k = 0;
    const double m = q.maxCoeff(&k);
    g = Vec::Zero(x.size());
    g(k) = s(k);
    return m;
  }
  // Inside, σ is affine near x (the nearest face): 0. Outside, σ = |o| with o the offsets
  // beyond the active faces A = {k : q_k > 0}: (P_A − g gᵀ)/σ, P_A = diag(1 on A); 0 in a
  // face region (A = {k}, g = ±e_k).
  Eigen::MatrixXd hessian(const Vec& x) const override {
    const Vec v = x - c_;
    const Vec q = v.cwiseAbs() - h_;
    const Vec outside = q.cwiseMax(0.0);
    const double d = outside.norm();
    if (!(d > 0)) return Eigen::MatrixXd::Zero(x.size(), x.size());
    const Vec s = v.unaryExpr([](double t) { return t < 0 ? -1.0 : 1.0; });
    const Vec g = s.cwiseProduct(outside) / d;
    const Vec active = q.unaryExpr([](double t) { return t > 0 ? 1.0 : 0.0; });
    return (Eigen::MatrixXd(active.asDiagonal()) - g * g.transpose()) / d;
  }
  std::optional<Vec> closest_point(const Vec& x) const override {
    const Vec v = x - c_;
    const Vec q = v.cwiseAbs() - h_;
    if (q.maxCoeff() > 0) return Vec(c_ + v.cwiseMax(-h_).cwiseMin(h_));
    // Inside (or on) the box: move straight to the nearest face.
    Eigen::Index k = 0;
    q.maxCoeff(&k);
    Vec p = x;
    p(k) = c_(k) + (v(k) < 0 ? -h_(k) : h_(k));
    return p;
  }

 private:
  Vec c_, h_;
};

// Ring torus: the distance to the core circle (radius R in the plane ⊥ axis through c)
// minus r.
class Torus final : public LevelSetNode {
 public:
  Torus(Vec c, Vec axis, double major, double minor)
      : c_(std::move(c)), a_(axis.stableNormalized()), R_(major), r_(minor) {}
  double value(const Vec& x) const override { return (x - core_point(x)).norm() - r_; }
  double value_gradient(const Vec& x, Vec& g) const override {
    const Vec k = core_point(x);
    g = tube_direction(x, k);
    return (x - k).norm() - r_;
  }
  // The foot point k moves with x along the core circle's tangent t = a × u at the rate
  // R/ρ (ρ = distance from the axis), so ∂(x − k)/∂x = I − (R/ρ) t tᵀ and, as t ⊥ n,
  // ∇²σ = (I − n nᵀ − (R/ρ) t tᵀ)/|x − k|.
  Eigen::MatrixXd hessian(const Vec& x) const override {
    const Vec v = x - c_;
    const Vec radial = v - v.dot(a_) * a_;
    const double rho = radial.norm();
    const Vec d = x - core_point(x);
    const double dist = d.norm();
    if (!(rho > 0) || !(dist > 0)) return undefined_hessian(x.size());
    const Vec n = d / dist;
    const Eigen::Vector3d t = Eigen::Vector3d(a_).cross(Eigen::Vector3d(radial / rho));
    return (Eigen::Matrix3d::Identity() - n * n.transpose() - (R_ / rho) * t * t.transpose()) / dist;
  }
  std::optional<Vec> closest_point(const Vec& x) const override {
    const Vec k = core_point(x);
    return Vec(k + r_ * tube_direction(x, k));
  }

 private:
  // The nearest point of the core circle (any, on the axis).
  Vec core_point(const Vec& x) const {
    const Vec v = x - c_;
    const Vec radial = v - v.dot(a_) * a_;
    const double n = radial.norm();
    return c_ + R_ * (n > 0 ? Vec(radial / n) : any_perpendicular(a_));
  }
  // Unit (x − k), or the outward radial direction when x is on the core circle.
  Vec tube_direction(const Vec& x, const Vec& k) const {
    const Vec d = x - k;
    const double n = d.norm();
    return n > 0 ? Vec(d / n) : Vec((k - c_) / R_);
  }
  Vec c_, a_;
  double R_, r_;
};

}  // namespace

NodePtr make_sphere(const SphereLevelSet& s) { return std::make_shared<Sphere>(s.center, s.radius); }
NodePtr make_cylinder(const CylinderLevelSet& s) { return std::make_shared<Cylinder>(s.center, s.axis, s.radius); }
NodePtr make_plane(const PlaneLevelSet& s) { return std::make_shared<Plane>(s.point, s.normal); }
NodePtr make_box(const BoxLevelSet& s) { return std::make_shared<Box>(s.center, s.size); }
NodePtr make_torus(const TorusLevelSet& s) {
  return std::make_shared<Torus>(s.center, s.axis, s.major, s.minor);
}

}  // namespace meshmorph::detail

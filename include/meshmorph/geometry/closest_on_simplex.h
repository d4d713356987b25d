// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>

#include <Eigen/Geometry>

namespace meshmorph {

/// The point x of a 2D or 3D problem in 3D (z = 0 in 2D), as the functions below take it.
inline Eigen::Vector3d padded_3d(const Eigen::Ref<const Eigen::VectorXd>& x) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(x.size()) = x;
  return p;
}

/// The closest point of segment ab to p (a when the segment has zero length). A 2D problem's
/// result is that of its points padded with z = 0 (the zero terms change no sum).
inline Eigen::Vector3d closest_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d ab = b - a;
  const double l2 = ab.squaredNorm();
  if (l2 == 0) return a;
  return a + std::clamp((p - a).dot(ab) / l2, 0.0, 1.0) * ab;
}

/// The closest point of triangle abc to p, by the Voronoi region of p (a vertex, an edge or
/// the face; Ericson, Real-Time Collision Detection §5.1.5). A degenerate triangle (its area
/// below 1e-14 of the product of two sides) gives the closest point of its edges.
inline Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                           const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a;
  if (ab.cross(ac).squaredNorm() <= 1e-28 * ab.squaredNorm() * ac.squaredNorm()) {
    Eigen::Vector3d best = closest_on_segment(p, a, b);
    for (const Eigen::Vector3d& q : {closest_on_segment(p, b, c), closest_on_segment(p, c, a)})
      if ((q - p).squaredNorm() < (best - p).squaredNorm()) best = q;
    return best;
  }
  const Eigen::Vector3d ap = p - a, bp = p - b, cp = p - c;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap), d3 = ab.dot(bp), d4 = ac.dot(bp), d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d1 <= 0 && d2 <= 0) return a;
  if (d3 >= 0 && d4 <= d3) return b;
  if (d6 >= 0 && d5 <= d6) return c;
  const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + (d1 / (d1 - d3)) * ab;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + (d2 / (d2 - d6)) * ac;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);
  const double sum = va + vb + vc;
  return a + (vb / sum) * ab + (vc / sum) * ac;
}

}  // namespace meshmorph

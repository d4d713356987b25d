// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/LU>
#include <Eigen/QR>

namespace meshmorph::test {

/// Fixed-seed samples of d×d matrices T for metric tests (STYLE §4): well shaped,
/// anisotropic (condition number 1e3), near-singular (τ = 1e-6 |T|^d) and inverted (τ < 0).
template <int d>
struct MatrixSample {
  std::string kind;
  Eigen::Matrix<double, d, d> T;
};

/// A random rotation (det +1), from the QR factorization of a Gaussian matrix.
template <int d>
Eigen::Matrix<double, d, d> random_rotation(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  Eigen::Matrix<double, d, d> G;
  for (int i = 0; i < d * d; ++i) G(i) = n(rng);
  Eigen::HouseholderQR<Eigen::Matrix<double, d, d>> qr(G);
  Eigen::Matrix<double, d, d> Q = qr.householderQ();
  if (Q.determinant() < 0) Q.col(0) *= -1.0;
  return Q;
}

/// U diag(s) V with random rotations U, V: singular values s, det = Π s.
template <int d>
Eigen::Matrix<double, d, d> with_singular_values(std::mt19937& rng, const Eigen::Matrix<double, d, 1>& s) {
  return random_rotation<d>(rng) * s.asDiagonal() * random_rotation<d>(rng);
}

/// `count` samples of each kind; the inverted ones only when `with_inverted`.
template <int d>
std::vector<MatrixSample<d>> matrix_samples(int count, bool with_inverted, unsigned seed = 20240601u) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.5, 2.0);
  std::vector<MatrixSample<d>> out;
  using Vec = Eigen::Matrix<double, d, 1>;
  for (int k = 0; k < count; ++k) {
    Vec s;
    for (int i = 0; i < d; ++i) s(i) = u(rng);
    out.push_back({"well_shaped", with_singular_values<d>(rng, s)});

    Vec a = Vec::Constant(u(rng));  // condition number exactly 1e3
    a(d - 1) = a(0) * 1e-3;
    if (d == 3) a(1) = a(0) * std::sqrt(1e-3);
    out.push_back({"anisotropic_1e3", with_singular_values<d>(rng, a)});

    // Singular values (c, …, c, t) with t solving τ = 1e-6 |T|^d (fixed point, contracts fast).
    const double c = u(rng);
    double t = 1e-6 * c;
    for (int it = 0; it < 20; ++it) {
      const double frob = std::sqrt((d - 1) * c * c + t * t);
      t = 1e-6 * std::pow(frob, d) / std::pow(c, d - 1);
    }
    Vec ns = Vec::Constant(c);
    ns(d - 1) = t;
    out.push_back({"near_singular", with_singular_values<d>(rng, ns)});

    if (with_inverted) {
      Vec m;
      for (int i = 0; i < d; ++i) m(i) = u(rng);
      m(0) = -m(0);
      out.push_back({"inverted", with_singular_values<d>(rng, m)});
    }
  }
  return out;
}

}  // namespace meshmorph::test

// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>

#include "meshmorph/quality/metric.h"
#include "meshmorph/quality/spd_projection.h"

namespace meshmorph::detail {

/// PSD projection of H = d²μ/dT² (in place), fast for isotropic metrics.
///
/// Every metric of DESIGN §2 except the edge-based q is isotropic: μ(R₁ T R₂) = μ(T) for
/// rotations R₁, R₂. With T = U Σ Vᵀ and K = V ⊗ U (orthogonal, vec(T) = K vec(Σ)), the Hessian
/// in the singular frame, Kᵀ H K, is then block diagonal: one d×d block on the diagonal
/// entries of Σ and one 2×2 block per pair (ab, ba) (the "scaling", "twist" and "flip" modes
/// of Smith, De Goes, Kim, "Analytic eigensystems for isotropic distortion energies", 2019).
/// Projecting the small blocks replaces one d²×d² eigenproblem by a d×d SVD and small ones.
/// The structure is checked, not assumed: when the off-block part is not negligible the
/// general quality/ project_spd runs instead. As there, H stays bit-for-bit unchanged when it
/// is already PSD.
/// Sylvester's criterion for a 2×2 or 3×3 symmetric matrix: every principal minor ≥ 0,
/// with a rounding allowance of 1e-14 relative (a semidefinite block from a scale-invariant
/// metric has minors of exactly 0 up to rounding; clamping those would change nothing).
template <int n>
bool is_psd(const Eigen::Matrix<double, n, n>& A) {
  const double s = A.cwiseAbs().maxCoeff();
  const double tol = 1e-14 * s;
  for (int i = 0; i < n; ++i)
    if (A(i, i) < -tol) return false;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      if (A(i, i) * A(j, j) - A(i, j) * A(j, i) < -tol * s) return false;
  return n < 3 || A.determinant() >= -tol * s * s;
}

// (L ⊗ R) Y for a d²×d² matrix Y, column by column: (L ⊗ R) vec(X) = vec(R X Lᵀ) takes two
// d×d products per column, 2d⁵ multiplications in all instead of the d⁶ of a dense K.
template <int d>
HessT<d> kron_times(const MatT<d>& L, const MatT<d>& R, const HessT<d>& Y) {
  HessT<d> out;
  for (int c = 0; c < d * d; ++c)
    Eigen::Map<MatT<d>>(out.col(c).data()).noalias() =
        R.lazyProduct(Eigen::Map<const MatT<d>>(Y.col(c).data())).lazyProduct(L.transpose());
  return out;
}

// K S Kᵀ for K = L ⊗ R and a symmetric S: K (K S)ᵀ = K Sᵀ Kᵀ.
template <int d>
HessT<d> kron_congruence(const MatT<d>& L, const MatT<d>& R, const HessT<d>& S) {
  return kron_times<d>(L, R, kron_times<d>(L, R, S).transpose());
}

template <int d>
void project_isotropic(const MatT<d>& T, HessT<d>& H) {
  constexpr int N = d * d;
  const Eigen::JacobiSVD<MatT<d>> svd(T, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const MatT<d>& U = svd.matrixU();
  const MatT<d>& V = svd.matrixV();
  // K = V ⊗ U: vec(T) = K vec(Σ). M = Kᵀ H K, with Kᵀ = Vᵀ ⊗ Uᵀ.
  const HessT<d> Hs = H.template selfadjointView<Eigen::Lower>();
  const HessT<d> M = kron_congruence<d>(V.transpose(), U.transpose(), Hs);
  // Group of each entry of vec(Σ): 0 for the diagonal, 1 + pair index for (a, b) and (b, a).
  int group[N];
  int pair_a[d * (d - 1) / 2], pair_b[d * (d - 1) / 2];
  int n_pairs = 0;
  for (int a = 0; a < d; ++a) group[a + d * a] = 0;
  for (int a = 0; a < d; ++a)
    for (int b = a + 1; b < d; ++b, ++n_pairs) {
      group[a + d * b] = group[b + d * a] = 1 + n_pairs;
      pair_a[n_pairs] = a + d * b;
      pair_b[n_pairs] = b + d * a;
    }
  double off = 0.0;
  for (int c = 0; c < N; ++c)
    for (int r = 0; r < N; ++r)
      if (group[r] != group[c]) off += M(r, c) * M(r, c);
  if (!(off <= 1e-24 * M.squaredNorm())) {  // not isotropic (or not finite): general route
    project_spd(H);
    return;
  }
  bool clamped = false;
  // Block on the diagonal entries of Σ.
  MatT<d> D;
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) D(a, b) = M(a + d * a, b + d * b);
  if (!is_psd(D)) {
    Eigen::SelfAdjointEigenSolver<MatT<d>> eig_d;
    eig_d.computeDirect(D);  // closed form for 2×2 and 3×3
    if (eig_d.eigenvalues().minCoeff() < 0.0) {
      clamped = true;
      D = eig_d.eigenvectors() * eig_d.eigenvalues().cwiseMax(0.0).asDiagonal() * eig_d.eigenvectors().transpose();
    }
  }
  HessT<d> P = HessT<d>::Zero();
  for (int a = 0; a < d; ++a)
    for (int b = 0; b < d; ++b) P(a + d * a, b + d * b) = D(a, b);
  for (int p = 0; p < n_pairs; ++p) {
    const int i = pair_a[p], j = pair_b[p];
    Eigen::Matrix2d B;
    B << M(i, i), M(i, j), M(j, i), M(j, j);
    if (!is_psd(B)) {
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig_b;
      eig_b.computeDirect(B);
      clamped = true;
      B = eig_b.eigenvectors() * eig_b.eigenvalues().cwiseMax(0.0).asDiagonal() * eig_b.eigenvectors().transpose();
    }
    P(i, i) = B(0, 0);
    P(i, j) = B(0, 1);
    P(j, i) = B(1, 0);
    P(j, j) = B(1, 1);
  }
  if (clamped) H = kron_congruence<d>(V, U, P);
}

}  // namespace meshmorph::detail

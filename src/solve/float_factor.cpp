// SPDX-License-Identifier: MIT
#include "solve/detail/float_factor.h"

#include <algorithm>

namespace meshmorph::detail {
namespace {

// A supernode's columns go four at a time: their 4×4 diagonal block is solved first, then
// one pass over the rows below it (of the diagonal block and of the rows under the supernode)
// uses all four, so that each element of t is loaded once per four entries of L, as a blocked
// BLAS triangular solve would.

// t[r] −= Σ_{c<4} a_c[r] v_c for r in [from, nr).
void subtract4(const float* a0, const float* a1, const float* a2, const float* a3, const double* v, int from, int nr,
               double* t) {
  const double v0 = v[0], v1 = v[1], v2 = v[2], v3 = v[3];
#pragma omp simd
  for (int r = from; r < nr; ++r)
    t[r] -= static_cast<double>(a0[r]) * v0 + static_cast<double>(a1[r]) * v1 + static_cast<double>(a2[r]) * v2 +
            static_cast<double>(a3[r]) * v3;
}

// s_c = Σ_r a_c[r] t[r] over r in [from, nr), c < 4.
void dot4(const float* a0, const float* a1, const float* a2, const float* a3, const double* t, int from, int nr,
          double* s) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
#pragma omp simd reduction(+ : s0, s1, s2, s3)
  for (int r = from; r < nr; ++r) {
    const double tr = t[r];
    s0 += static_cast<double>(a0[r]) * tr;
    s1 += static_cast<double>(a1[r]) * tr;
    s2 += static_cast<double>(a2[r]) * tr;
    s3 += static_cast<double>(a3[r]) * tr;
  }
  s[0] = s0;
  s[1] = s1;
  s[2] = s2;
  s[3] = s3;
}

}  // namespace

void FloatFactor::assign(int n, int nsuper, const int* super, const int* pi, const int* px, const int* s_rows,
                         const double* x, const int* perm) {
  super_.assign(super, super + nsuper + 1);
  pi_.assign(pi, pi + nsuper + 1);
  px_.assign(px, px + nsuper + 1);
  rows_.assign(s_rows, s_rows + pi[nsuper]);
  x_.resize(static_cast<std::size_t>(px[nsuper]));
  std::transform(x, x + px[nsuper], x_.begin(), [](double v) { return static_cast<float>(v); });
  perm_.assign(perm, perm + n);
  int max_rows = 0;
  for (int s = 0; s < nsuper; ++s) max_rows = std::max(max_rows, pi[s + 1] - pi[s]);
  y_.resize(static_cast<std::size_t>(n));
  work_.resize(static_cast<std::size_t>(max_rows));
}

void FloatFactor::clear() {
  x_ = {};
  rows_ = {};
}

FloatFactor::Supernode FloatFactor::supernode(int s) const {
  return {super_[s], super_[s + 1] - super_[s], pi_[s + 1] - pi_[s], rows_.data() + pi_[s], x_.data() + px_[s]};
}

void FloatFactor::forward(int s) const {
  // Named copies, not a structured binding: clang before 16 cannot capture one in a lambda
  // or an OpenMP region.
  const Supernode sn = supernode(s);
  const int k1 = sn.k1, nc = sn.nc, nr = sn.nr;
  const int* rows = sn.rows;
  const float* L = sn.L;
  const auto col = [&](int j) { return L + static_cast<std::ptrdiff_t>(j) * nr; };
  double* y = y_.data();
  double* t = work_.data();
  std::copy(y + k1, y + k1 + nc, t);
  std::fill(t + nc, t + nr, 0.0);
  int j = 0;
  for (; j + 4 <= nc; j += 4) {
    const float* a[4] = {col(j), col(j + 1), col(j + 2), col(j + 3)};
    for (int c = 0; c < 4; ++c) {
      t[j + c] /= a[c][j + c];
      for (int e = c + 1; e < 4; ++e) t[j + e] -= static_cast<double>(a[c][j + e]) * t[j + c];
    }
    subtract4(a[0], a[1], a[2], a[3], t + j, j + 4, nr, t);
  }
  for (; j < nc; ++j) {
    const float* a = col(j);
    const double v = t[j] /= a[j];
#pragma omp simd
    for (int r = j + 1; r < nr; ++r) t[r] -= static_cast<double>(a[r]) * v;
  }
  std::copy(t, t + nc, y + k1);
  for (int r = nc; r < nr; ++r) y[rows[r]] += t[r];
}

void FloatFactor::backward(int s) const {
  const Supernode sn = supernode(s);
  const int k1 = sn.k1, nc = sn.nc, nr = sn.nr;
  const int* rows = sn.rows;
  const float* L = sn.L;
  const auto col = [&](int j) { return L + static_cast<std::ptrdiff_t>(j) * nr; };
  double* y = y_.data();
  double* t = work_.data();
  for (int r = 0; r < nr; ++r) t[r] = y[rows[r]];
  const int blocked = nc / 4 * 4;
  for (int j = nc - 1; j >= blocked; --j) {  // the columns past the last block of four first
    const float* a = col(j);
    double sum = 0.0;
#pragma omp simd reduction(+ : sum)
    for (int r = j + 1; r < nr; ++r) sum += static_cast<double>(a[r]) * t[r];
    t[j] = (t[j] - sum) / a[j];
  }
  for (int j = blocked - 4; j >= 0; j -= 4) {
    const float* a[4] = {col(j), col(j + 1), col(j + 2), col(j + 3)};
    double sum[4];
    dot4(a[0], a[1], a[2], a[3], t, j + 4, nr, sum);
    for (int c = 3; c >= 0; --c) {
      for (int e = c + 1; e < 4; ++e) sum[c] += static_cast<double>(a[c][j + e]) * t[j + e];
      t[j + c] = (t[j + c] - sum[c]) / a[c][j + c];
    }
  }
  std::copy(t, t + nc, y + k1);
}

void FloatFactor::solve(const double* b, double* x) const {
  const int nsuper = static_cast<int>(super_.size()) - 1;
  double* y = y_.data();
  const auto n = static_cast<int>(perm_.size());
  for (int k = 0; k < n; ++k) y[k] = b[perm_[k]];
  // L y = P b supernode by supernode, then Lᵀ z = y backwards.
  for (int s = 0; s < nsuper; ++s) forward(s);
  for (int s = nsuper - 1; s >= 0; --s) backward(s);
  for (int k = 0; k < n; ++k) x[perm_[k]] = y[k];
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
// The sum-factorized product of the Hessian action on hexahedra, k_lanes cells per SIMD lane.
#include "energy/detail/hessian_kernels.h"

namespace meshmorph::detail {
namespace {

// k_lanes doubles, one per cell of a batch: a GCC/Clang vector, so that every operation of
// hex_action is one SIMD instruction (or two, where registers are half as wide); unaligned
// and free to alias the doubles it is read from.
using Lanes = double __attribute__((vector_size(k_lanes * sizeof(double)), aligned(sizeof(double)), may_alias));
using FloatLanes = float __attribute__((vector_size(k_lanes * sizeof(float)), aligned(sizeof(float)), may_alias));

// hex_kernel's product: the gradients G_q of the three components at the m³ points in three
// 1D passes (x, y, then z), K_q point by point, and the transposed passes back; each value is
// Lanes, so each operation serves the k_lanes cells of the batch.
// P_ and m_ > 0 fix P and m at compile time (the loops unroll), 0 reads them from t.
template <int P_, int m_>
[[gnu::always_inline]] inline void hex_action(const TensorGrid& t, const float* K, HexScratch& s) {
  const int P = P_ > 0 ? P_ : t.basis->P, m = m_ > 0 ? m_ : t.m;
  const auto B = [&](int q, int i) { return t.B(q, i); };
  const auto D = [&](int q, int i) { return t.D(q, i); };
  // n values of 3 components; zeroed only where a pass scatters into them (E), the others are
  // summed in registers and stored.
  const auto field = [](std::vector<double>& v, int n, bool zeroed) {
    const auto size = static_cast<std::size_t>(3 * k_lanes * n);
    if (zeroed)
      v.assign(size, 0.0);
    else
      v.resize(size);
    return reinterpret_cast<Lanes*>(v.data());
  };
  Lanes* A0 = field(s.A0, m * P * P, false);
  Lanes* A1 = field(s.A1, m * P * P, false);
  const auto* u = reinterpret_cast<const Lanes*>(s.u.data());
  for (int iz = 0; iz < P; ++iz)
    for (int iy = 0; iy < P; ++iy)
      for (int qx = 0; qx < m; ++qx) {
        Lanes a0[3] = {}, a1[3] = {};
        for (int ix = 0; ix < P; ++ix) {
          const Lanes* ui = u + 3 * (ix + P * (iy + P * iz));
          const double b = B(qx, ix), dd = D(qx, ix);
          for (int k = 0; k < 3; ++k) a0[k] += b * ui[k], a1[k] += dd * ui[k];
        }
        const int o = 3 * (qx + m * (iy + P * iz));
        for (int k = 0; k < 3; ++k) A0[o + k] = a0[k], A1[o + k] = a1[k];
      }
  Lanes* C00 = field(s.C00, m * m * P, false);
  Lanes* C01 = field(s.C01, m * m * P, false);
  Lanes* C10 = field(s.C10, m * m * P, false);
  for (int iz = 0; iz < P; ++iz)
    for (int qy = 0; qy < m; ++qy)
      for (int qx = 0; qx < m; ++qx) {
        Lanes c00[3] = {}, c01[3] = {}, c10[3] = {};
        for (int iy = 0; iy < P; ++iy) {
          const Lanes* a0 = A0 + 3 * (qx + m * (iy + P * iz));
          const Lanes* a1 = A1 + 3 * (qx + m * (iy + P * iz));
          const double b = B(qy, iy), dd = D(qy, iy);
          for (int k = 0; k < 3; ++k) c00[k] += b * a0[k], c01[k] += dd * a0[k], c10[k] += b * a1[k];
        }
        const int o = 3 * (qx + m * (qy + m * iz));
        for (int k = 0; k < 3; ++k) C00[o + k] = c00[k], C01[o + k] = c01[k], C10[o + k] = c10[k];
      }
  Lanes* E00 = field(s.E00, m * m * P, true);
  Lanes* E01 = field(s.E01, m * m * P, true);
  Lanes* E10 = field(s.E10, m * m * P, true);
  for (int qz = 0; qz < m; ++qz)
    for (int qy = 0; qy < m; ++qy)
      for (int qx = 0; qx < m; ++qx) {
        Lanes g[9] = {};  // vec(G): G(k, j) = ∂_j u_k at g[k + 3j]
        for (int iz = 0; iz < P; ++iz) {
          const int o = 3 * (qx + m * (qy + m * iz));
          const double b = B(qz, iz), dd = D(qz, iz);
          for (int k = 0; k < 3; ++k) g[k] += b * C10[o + k], g[3 + k] += b * C01[o + k], g[6 + k] += dd * C00[o + k];
        }
        const auto* Kq = reinterpret_cast<const FloatLanes*>(K + k_packed(9) * k_lanes * (qx + m * (qy + m * qz)));
        Lanes h[9];
        for (int i = 0; i < 9; ++i) h[i] = Lanes{} + 0.0;
        for (int i = 0, e = 0; i < 9; ++i) {
          h[i] += __builtin_convertvector(Kq[e++], Lanes) * g[i];
          for (int j = i + 1; j < 9; ++j, ++e) {
            const Lanes k = __builtin_convertvector(Kq[e], Lanes);
            h[i] += k * g[j], h[j] += k * g[i];
          }
        }
        for (int iz = 0; iz < P; ++iz) {
          const int o = 3 * (qx + m * (qy + m * iz));
          const double b = B(qz, iz), dd = D(qz, iz);
          for (int k = 0; k < 3; ++k) E10[o + k] += b * h[k], E01[o + k] += b * h[3 + k], E00[o + k] += dd * h[6 + k];
        }
      }
  Lanes* F0 = field(s.F0, m * P * P, false);
  Lanes* F1 = field(s.F1, m * P * P, false);
  for (int iz = 0; iz < P; ++iz)
    for (int iy = 0; iy < P; ++iy)
      for (int qx = 0; qx < m; ++qx) {
        Lanes f0[3] = {}, f1[3] = {};
        for (int qy = 0; qy < m; ++qy) {
          const int o = 3 * (qx + m * (qy + m * iz));
          const double b = B(qy, iy), dd = D(qy, iy);
          for (int k = 0; k < 3; ++k) f0[k] += b * E00[o + k] + dd * E01[o + k], f1[k] += b * E10[o + k];
        }
        const int o = 3 * (qx + m * (iy + P * iz));
        for (int k = 0; k < 3; ++k) F0[o + k] = f0[k], F1[o + k] = f1[k];
      }
  Lanes* y = field(s.y, P * P * P, false);
  for (int iz = 0; iz < P; ++iz)
    for (int iy = 0; iy < P; ++iy)
      for (int ix = 0; ix < P; ++ix) {
        Lanes yi[3] = {};
        for (int qx = 0; qx < m; ++qx) {
          const Lanes* f0 = F0 + 3 * (qx + m * (iy + P * iz));
          const Lanes* f1 = F1 + 3 * (qx + m * (iy + P * iz));
          const double b = B(qx, ix), dd = D(qx, ix);
          for (int k = 0; k < 3; ++k) yi[k] += b * f0[k] + dd * f1[k];
        }
        for (int k = 0; k < 3; ++k) y[3 * (ix + P * (iy + P * iz)) + k] = yi[k];
      }
}

}  // namespace

// hex_action for t's sizes, compiled for the Lobatto rules of orders 1–4 (m = p + 2) and in
// general; on x86-64 also for x86-64-v3 (AVX2, FMA), taken at run time where the processor has it
// (the lanes then fill its 4-wide registers).
#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define MESHMORPH_VECTOR_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define MESHMORPH_VECTOR_CLONES
#endif
MESHMORPH_VECTOR_CLONES void hex_kernel(const TensorGrid& t, const float* K, HexScratch& s) {
  const int P = t.basis->P;
  if (P == 2 && t.m == 3) return hex_action<2, 3>(t, K, s);
  if (P == 3 && t.m == 4) return hex_action<3, 4>(t, K, s);
  if (P == 4 && t.m == 5) return hex_action<4, 5>(t, K, s);
  if (P == 5 && t.m == 6) return hex_action<5, 6>(t, K, s);
  hex_action<0, 0>(t, K, s);
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
// Partial assembly of EnergyAssembler's Hessian: K_q per quadrature point, and its action.
#include <algorithm>
#include <array>
#include <utility>
#include <cmath>
#include <limits>
#include <vector>

#include <omp.h>

#include "energy/detail/element_kernel.h"
#include "meshmorph/energy/assembler.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/tensor_basis.h"

namespace meshmorph {
namespace {

constexpr int k_sq(int d) { return d * d; }
// Entries of a symmetric dd × dd matrix packed by rows of its upper triangle.
constexpr int k_packed(int dd) { return dd * (dd + 1) / 2; }

// h = K g for K packed as k_packed(dd): K is read once, which bounds a matrix-free product (the
// K of every point are the bulk of its memory traffic).
template <int dd>
inline void packed_product(const float* K, const double* g, double* h) {
  for (int i = 0; i < dd; ++i) h[i] = 0.0;
  for (int i = 0, o = 0; i < dd; ++i) {
    h[i] += double(K[o++]) * g[i];
    for (int j = i + 1; j < dd; ++j, ++o) {
      const double k = K[o];
      h[i] += k * g[j];
      h[j] += k * g[i];
    }
  }
}

// h = K g for a packed symmetric n × n K (as packed_product, n at run time).
inline void packed_product(const float* K, const double* g, double* h, int n) {
  for (int i = 0; i < n; ++i) h[i] = 0.0;
  for (int i = 0; i < n; ++i) {
    const double gi = g[i];
    double hi = h[i] + double(K[0]) * gi;
    for (int j = i + 1; j < n; ++j) {
      const double k = K[j - i];
      hi += k * g[j];
      h[j] += k * gi;
    }
    h[i] = hi;
    K += n - i;
  }
}

// Entry (i, j), i ≤ j, of a packed dd × dd matrix.
constexpr int packed_index(int dd, int i, int j) { return i * dd - i * (i - 1) / 2 + (j - i); }

int threads_of(int requested) { return requested > 0 ? requested : omp_get_max_threads(); }

// Cells per dense product of apply_hessian: 16 cells give the products 3·16 rows in 3D, enough
// for the blocked kernel to amortise the packing of ∇N.
constexpr int k_batch = 16;

// The 1D factors of a hexahedral block whose table is a tensor grid (ShapeTable::tensor);
// null (dense products) elsewhere.
template <int d>
const TensorGrid* tensor_factors(const CellBlock& block, const ShapeTable& table) {
  return d == 3 && block.type == ElementType::Hexahedron ? table.tensor.get() : nullptr;
}

constexpr int k_lanes = HessianAction<3>::k_lanes;

// The packed K_q of cell c at point q in a block's K (HessianAction::K): its first entry and
// the stride between entries (k_lanes where the cells are interleaved by lanes, else 1).
template <int d, class T>
std::pair<T*, int> point_entries(T* K, bool lanes, std::size_t c, int Q, int q) {
  constexpr auto n = static_cast<std::size_t>(k_packed(d * d));
  if (!lanes) return {K + (c * static_cast<std::size_t>(Q) + static_cast<std::size_t>(q)) * n, 1};
  const std::size_t batch = c / k_lanes, lane = c % k_lanes;
  return {K + ((batch * static_cast<std::size_t>(Q) + static_cast<std::size_t>(q)) * n) * k_lanes + lane, k_lanes};
}

// Work space of hex_action: u, y and the 1D passes' fields, each entry k_lanes wide.
struct HexScratch {
  std::vector<double> u, y, A0, A1, C00, C01, C10, E00, E01, E10, F0, F1;
};

// k_lanes doubles, one per cell of a batch: a GCC/Clang vector, so that every operation of
// hex_action is one SIMD instruction (or two, where registers are half as wide); unaligned
// and free to alias the doubles it is read from.
using Lanes = double __attribute__((vector_size(k_lanes * sizeof(double)), aligned(sizeof(double)), may_alias));
using FloatLanes = float __attribute__((vector_size(k_lanes * sizeof(float)), aligned(sizeof(float)), may_alias));

// y_e = Σ_q mat(K_q vec(G_q)) ∇N_qᵀ on k_lanes hexahedra at once by sum factorization: the
// gradients G_q of the three components at the m³ points in three 1D passes (x, y, then z:
// O(m P³ + m² P² + m³ P) instead of O(m³ P³)), K_q point by point, and the transposed passes
// back; each value is Lanes. u and y: the nodal values in lattice order, then component, then
// lane; K: point, packed entry, lane (HessianAction::K).
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

}  // namespace

template <int d>
bool EnergyAssembler<d>::prepare_hessian(const Metric<d>& metric, const Eigen::MatrixXd& x, HessianMode mode, int threads,
                                         HessianAction<d>& out) const {
  constexpr int dd = k_sq(d);
  using Hess = Eigen::Matrix<double, dd, dd>;
  out.K.resize(mesh_->cells.size());
  out.element.resize(mesh_->cells.size());
  out.tensor.clear();
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi)
    out.tensor.push_back(tensor_factors<d>(mesh_->cells[bi], *targets_->blocks[bi].table));
  int finite = 1;
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const BlockTargets<d>& bt = targets_->blocks[bi];
    const ShapeTable& table = *bt.table;
    const int n = block.n_nodes_per_cell(), Q = bt.n_points();
    std::vector<float>& K = out.K[bi];
    std::vector<float>& E = out.element[bi];
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    if (is_simplex(block.type)) {
      // Element matrices (component-major, as detail::element_kernel): on simplices (d·n)² is
      // less than the per-point data and its products, e.g. 3600 against 46·45 + 2·3·20·138 for
      // a P3 tetrahedron at degree 8.
      K.clear();
      const int dn = d * n;
      E.resize(block.n_cells() * static_cast<std::size_t>(k_packed(dn)));
#pragma omp parallel for num_threads(threads_of(threads)) schedule(static) reduction(&& : finite)
      for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
        detail::NodalMatrix<d> X(d, n);
        detail::ElementScratch<d> scratch;
        const std::int32_t* nodes = block.cell(static_cast<std::size_t>(c));
        for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
        const double e = detail::element_kernel<d>(metric, table, bt.cell(static_cast<std::size_t>(c)), X, Want::Hessian, mode, scratch);
        if (!(e < std::numeric_limits<double>::infinity())) {
          finite = 0;
          continue;
        }
        float* packed = E.data() + static_cast<std::size_t>(c) * k_packed(dn);
        for (int i = 0; i < dn; ++i)
          for (int j = i; j < dn; ++j) *packed++ = static_cast<float>(scratch.H(i, j));  // exactly symmetric (complete_symmetric)
      }
      continue;
    }
    E.clear();
    // Cells in batches of k_lanes, interleaved, where hex_action takes them (HessianAction::K).
    const bool lanes = out.tensor[bi] != nullptr;
    const std::size_t padded = lanes ? (block.n_cells() + k_lanes - 1) / k_lanes * k_lanes : block.n_cells();
    K.assign(padded * static_cast<std::size_t>(Q) * k_packed(dd), 0.0f);
    const TensorGrid* grid = table.tensor && table.dim == d ? table.tensor.get() : nullptr;
#pragma omp parallel for num_threads(threads_of(threads)) schedule(static) reduction(&& : finite)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      detail::NodalMatrix<d> X(d, n);
      const std::int32_t* nodes = block.cell(static_cast<std::size_t>(c));
      for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
      const QuadratureTarget<d>* t = bt.cell(static_cast<std::size_t>(c));
      // The reference gradients at all points, by sum factorization where the table allows,
      // and T as element_kernel forms it.
      thread_local Eigen::MatrixXd Gs;
      Gs.resize(d, d * Q);
      if (grid)
        grid_gradients(*grid, X.data(), d, Gs.data());
      else
        for (int q = 0; q < Q; ++q) Gs.middleCols(q * d, d).noalias() = X.lazyProduct(table.grad(q));
      for (int q = 0; q < Q; ++q) {
        const MatT<d> T = Eigen::Map<const MatT<d>>(Gs.data() + d * d * q).lazyProduct(t[q].W_inv);
        const MetricEval<d> ev = metric.eval(T, Want::Hessian);
        if (!(ev.mu < std::numeric_limits<double>::infinity())) {
          finite = 0;
          continue;
        }
        Hess Hq = ev.d2mu_dT2;
        if (mode == HessianMode::Projected) detail::project_isotropic<d>(T, Hq);
        // M = W⁻¹ ⊗ I: M(k + dj, k + dm) = W⁻¹(j, m), so that vec(T) = Mᵀ vec(G). Ideal
        // targets of tensor cells have W⁻¹ = s I, where M Hq Mᵀ = s² Hq.
        const MatT<d>& W_inv = t[q].W_inv;
        Hess Kq;
        if (W_inv.isDiagonal(0.0) && (W_inv.diagonal().array() == W_inv(0, 0)).all()) {
          Kq = (t[q].weight * W_inv(0, 0) * W_inv(0, 0)) * Hq;
        } else {
          Hess M = Hess::Zero();
          for (int j = 0; j < d; ++j)
            for (int m = 0; m < d; ++m)
              for (int k = 0; k < d; ++k) M(k + d * j, k + d * m) = W_inv(j, m);
          Kq = t[q].weight * (M * Hq * M.transpose());
        }
        const auto [packed, stride] = point_entries<d>(K.data(), lanes, static_cast<std::size_t>(c), Q, q);
        for (int i = 0, e = 0; i < dd; ++i)
          for (int j = i; j < dd; ++j, ++e) packed[e * stride] = static_cast<float>(0.5 * (Kq(i, j) + Kq(j, i)));
      }
    }
  }
  return finite != 0;
}

template <int d>
template <class Store>
void EnergyAssembler<d>::gather(const std::vector<double>& local, int width, int threads, Store store) const {
  constexpr int max_width = k_packed(d);
  MESHMORPH_CHECK(width <= max_width, "EnergyAssembler::gather: too wide");
  const auto n_nodes = static_cast<std::ptrdiff_t>(mesh_->n_nodes());
#pragma omp parallel for num_threads(threads_of(threads)) schedule(static)
  for (std::ptrdiff_t i = 0; i < n_nodes; ++i) {
    // Slot by slot, all entries at once: each entry still sums its slots in slot order.
    double sum[max_width] = {};
    for (std::int64_t s = node_slot_offset_[static_cast<std::size_t>(i)]; s < node_slot_offset_[static_cast<std::size_t>(i) + 1]; ++s) {
      const double* l = local.data() + width * node_slots_[static_cast<std::size_t>(s)];
      for (int k = 0; k < width; ++k) sum[k] += l[k];
    }
    for (int k = 0; k < width; ++k) store(i, k, sum[k]);
  }
}

template <int d>
void EnergyAssembler<d>::apply_hessian(const HessianAction<d>& action, const Eigen::VectorXd& v, Eigen::VectorXd& y,
                                       int threads) const {
  constexpr int dd = k_sq(d);
  MESHMORPH_CHECK(action.K.size() == mesh_->cells.size() && v.size() == static_cast<Eigen::Index>(dofs_->n_free()),
                  "EnergyAssembler::apply_hessian: the action or v does not fit");
  std::vector<double>& local = action.local;
  local.resize(static_cast<std::size_t>(d) * node_slots_.size());
  const std::int32_t* red = dofs_->reduced_index().data();
#pragma omp parallel num_threads(threads_of(threads))
  {
    Eigen::MatrixXd V, R, Y;
    Eigen::VectorXd ue, ye;
    HexScratch hex;
    for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
      const CellBlock& block = mesh_->cells[bi];
      const Eigen::MatrixXd& dN = targets_->blocks[bi].table->dN;  // n × dQ
      const int n = block.n_nodes_per_cell(), Q = targets_->blocks[bi].n_points();
      const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
      const float* K = action.K[bi].data();
      const auto K_of = [&](std::size_t c) { return K + c * static_cast<std::size_t>(Q) * k_packed(dd); };
      // y_e of cell c, node a, component k.
      double* out = local.data() + d * blocks_[bi].first_slot;
      const auto y_of = [&](std::size_t c, int a, int k) -> double& { return out[(c * n + static_cast<std::size_t>(a)) * d + k]; };
      if constexpr (d == 3) {
        if (const TensorGrid* t = action.tensor[bi]) {
          const std::vector<std::int32_t>& lattice_node = t->basis->node;
          const std::ptrdiff_t n_batches = (n_cells + k_lanes - 1) / k_lanes;
#pragma omp for schedule(static) nowait
          for (std::ptrdiff_t batch = 0; batch < n_batches; ++batch) {
            const int lanes = static_cast<int>(std::min<std::ptrdiff_t>(k_lanes, n_cells - batch * k_lanes));
            hex.u.assign(static_cast<std::size_t>(3 * k_lanes * n), 0.0);
            for (int e = 0; e < lanes; ++e) {
              const std::int32_t* nodes = block.cell(static_cast<std::size_t>(batch * k_lanes + e));
              for (int l = 0; l < n; ++l)
                for (int k = 0; k < 3; ++k)
                  if (const std::int32_t r = red[3 * nodes[lattice_node[static_cast<std::size_t>(l)]] + k]; r >= 0)
                    hex.u[static_cast<std::size_t>((3 * l + k) * k_lanes + e)] = v[r];
            }
            hex_kernel(*t, K + static_cast<std::size_t>(batch) * Q * k_packed(dd) * k_lanes, hex);
            for (int e = 0; e < lanes; ++e) {
              const auto c = static_cast<std::size_t>(batch * k_lanes + e);
              for (int l = 0; l < n; ++l)
                for (int k = 0; k < 3; ++k)
                  y_of(c, lattice_node[static_cast<std::size_t>(l)], k) = hex.y[static_cast<std::size_t>((3 * l + k) * k_lanes + e)];
            }
          }
          continue;
        }
      }
      if (const std::vector<float>& E = action.element[bi]; !E.empty()) {
        const int dn = d * n;
        ue.resize(dn);
        ye.resize(dn);
#pragma omp for schedule(static) nowait
        for (std::ptrdiff_t ci = 0; ci < n_cells; ++ci) {
          const auto c = static_cast<std::size_t>(ci);
          const std::int32_t* nodes = block.cell(c);
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) {
              const std::int32_t r = red[d * nodes[a] + k];
              ue[k * n + a] = r >= 0 ? v[r] : 0.0;
            }
          packed_product(E.data() + c * static_cast<std::size_t>(k_packed(dn)), ue.data(), ye.data(), dn);
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) y_of(c, a, k) = ye[k * n + a];
        }
        continue;
      }
      // Dense: k_batch cells at a time, their nodal values stacked as the d·b rows of V, so
      // that one product R = V ∇N over all points (the reference gradients G_q of cell e in
      // rows d·e .. d·e + d − 1, column block q) and one back share the packing of ∇N; K_q
      // applied per cell and point in between.
      const std::ptrdiff_t n_batches = (n_cells + k_batch - 1) / k_batch;
#pragma omp for schedule(static) nowait
      for (std::ptrdiff_t batch = 0; batch < n_batches; ++batch) {
        const std::size_t first = static_cast<std::size_t>(batch) * k_batch;
        const int b = static_cast<int>(std::min<std::ptrdiff_t>(k_batch, n_cells - batch * k_batch));
        V.resize(d * b, n);
        for (int e = 0; e < b; ++e) {
          const std::int32_t* nodes = block.cell(first + static_cast<std::size_t>(e));
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) {
              const std::int32_t r = red[d * nodes[a] + k];
              V(d * e + k, a) = r >= 0 ? v[r] : 0.0;
            }
        }
        R.noalias() = V * dN;
        for (int e = 0; e < b; ++e) {
          const float* Kc = K_of(first + static_cast<std::size_t>(e));
          for (int q = 0; q < Q; ++q) {
            Eigen::Matrix<double, dd, 1> g;
            for (int j = 0; j < d; ++j)
              for (int k = 0; k < d; ++k) g[k + d * j] = R(d * e + k, q * d + j);
            Eigen::Matrix<double, dd, 1> h;
            packed_product<dd>(Kc + q * k_packed(dd), g.data(), h.data());
            for (int j = 0; j < d; ++j)
              for (int k = 0; k < d; ++k) R(d * e + k, q * d + j) = h[k + d * j];
          }
        }
        Y.noalias() = R * dN.transpose();
        for (int e = 0; e < b; ++e)
          for (int a = 0; a < n; ++a)
            for (int k = 0; k < d; ++k) y_of(first + static_cast<std::size_t>(e), a, k) = Y(d * e + k, a);
      }
    }
  }
  y.setZero(static_cast<Eigen::Index>(dofs_->n_free()));
  gather(local, d, threads, [&](std::ptrdiff_t i, int k, double sum) {
    if (const std::int32_t r = red[d * i + k]; r >= 0) y[r] = sum;
  });
}

template <int d>
std::vector<double> EnergyAssembler<d>::hessian_blocks(const HessianAction<d>& action, int threads) const {
  constexpr int dd = k_sq(d), pairs = k_packed(d);
  MESHMORPH_CHECK(action.K.size() == mesh_->cells.size(), "EnergyAssembler::hessian_blocks: the action does not fit");
  // Per cell and node the pairs (k, l), k ≤ l, of its block, packed by rows.
  std::vector<double>& local = action.local;
  local.resize(static_cast<std::size_t>(pairs) * node_slots_.size());
  // S_jm^kl = K(k + dj, l + dm) + K(k + dm, l + dj) for j < m, K(k + dj, l + dj) for j = m:
  // the block (k, l) of node a is Σ_q Σ_{j ≤ m} ∂_j N_a ∂_m N_a S_jm^kl.
  const auto fields = [](std::pair<const float*, int> Kq, int j, int m, double* S) {
    const auto at = [&](int r, int c) { return double(Kq.first[Kq.second * (r <= c ? packed_index(dd, r, c) : packed_index(dd, c, r))]); };
    for (int k = 0, o = 0; k < d; ++k)
      for (int l = k; l < d; ++l, ++o) S[o] = at(k + d * j, l + d * m) + (j < m ? at(k + d * m, l + d * j) : 0.0);
  };
#pragma omp parallel num_threads(threads_of(threads))
  for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const ShapeTable& table = *targets_->blocks[bi].table;
    const int n = block.n_nodes_per_cell(), Q = table.n_points();
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    const float* K = action.K[bi].data();
    const std::vector<float>& E = action.element[bi];
    double* out = local.data() + pairs * blocks_[bi].first_slot;
    const TensorGrid* t = action.tensor[bi];
    // Sum factorization on hexahedra: ∂_j N_a ∂_m N_a at point q is a product of 1D tables,
    // l_i l_i, l_i l_i' or l_i' l_i' in each direction, so each field is contracted in three
    // 1D passes (O(m³P + m²P² + mP³) instead of O(m³P³)).
    std::array<Eigen::MatrixXd, 3> table1d;  // l l, l l', l' l' (m × P)
    if (t) table1d = {t->B.cwiseProduct(t->B), t->B.cwiseProduct(t->D), t->D.cwiseProduct(t->D)};
    std::vector<double> S, A, C;
    Eigen::Matrix<double, pairs, Eigen::Dynamic> h;
#pragma omp for schedule(static) nowait
    for (std::ptrdiff_t ci = 0; ci < n_cells; ++ci) {
      const auto c = static_cast<std::size_t>(ci);
      double* y = out + c * static_cast<std::size_t>(n * pairs);  // node a, pair o at pairs·a + o
      if (!E.empty()) {
        const int dn = d * n;
        const float* Ec = E.data() + c * static_cast<std::size_t>(k_packed(dn));
        for (int a = 0; a < n; ++a)
          for (int k = 0, o = 0; k < d; ++k)
            for (int l = k; l < d; ++l, ++o) y[pairs * a + o] = Ec[packed_index(dn, k * n + a, l * n + a)];
        continue;
      }
      const auto Kq = [&](int q) { return point_entries<d>(K, t != nullptr, c, Q, q); };
      h.setZero(pairs, n);
      if (t) {
        if constexpr (d == 3) {
          const int P = t->basis->P, m = t->m;
          S.resize(static_cast<std::size_t>(pairs * Q));
          A.resize(static_cast<std::size_t>(pairs * m * m * P));
          C.resize(static_cast<std::size_t>(pairs * m * P * P));
          for (int j = 0; j < d; ++j)
            for (int mm = j; mm < d; ++mm) {
              for (int q = 0; q < Q; ++q) fields(Kq(q), j, mm, &S[static_cast<std::size_t>(pairs * q)]);
              const Eigen::MatrixXd& X = table1d[static_cast<std::size_t>((j == 0) + (mm == 0))];
              const Eigen::MatrixXd& Y = table1d[static_cast<std::size_t>((j == 1) + (mm == 1))];
              const Eigen::MatrixXd& Z = table1d[static_cast<std::size_t>((j == 2) + (mm == 2))];
              std::fill(A.begin(), A.end(), 0.0);  // A(qx, qy, iz)
              for (int qz = 0; qz < m; ++qz)
                for (int iz = 0; iz < P; ++iz) {
                  const double z = Z(qz, iz);
                  for (int qxy = 0; qxy < m * m; ++qxy)
                    for (int o = 0; o < pairs; ++o)
                      A[static_cast<std::size_t>(pairs * (qxy + m * m * iz) + o)] += z * S[static_cast<std::size_t>(pairs * (qxy + m * m * qz) + o)];
                }
              std::fill(C.begin(), C.end(), 0.0);  // C(qx, iy, iz)
              for (int iz = 0; iz < P; ++iz)
                for (int qy = 0; qy < m; ++qy)
                  for (int iy = 0; iy < P; ++iy) {
                    const double yv = Y(qy, iy);
                    for (int qx = 0; qx < m; ++qx)
                      for (int o = 0; o < pairs; ++o)
                        C[static_cast<std::size_t>(pairs * (qx + m * (iy + P * iz)) + o)] +=
                            yv * A[static_cast<std::size_t>(pairs * (qx + m * (qy + m * iz)) + o)];
                  }
              for (int iz = 0; iz < P; ++iz)
                for (int iy = 0; iy < P; ++iy)
                  for (int ix = 0; ix < P; ++ix) {
                    const int a = t->basis->node[static_cast<std::size_t>(ix + P * (iy + P * iz))];
                    for (int qx = 0; qx < m; ++qx) {
                      const double xv = X(qx, ix);
                      for (int o = 0; o < pairs; ++o) h(o, a) += xv * C[static_cast<std::size_t>(pairs * (qx + m * (iy + P * iz)) + o)];
                    }
                  }
            }
        }
      } else {
        double Sq[pairs];
        for (int q = 0; q < Q; ++q) {
          const double* dNq = table.dN.data() + static_cast<std::ptrdiff_t>(q) * d * n;  // column q·d + j at j·n
          for (int j = 0; j < d; ++j)
            for (int mm = j; mm < d; ++mm) {
              fields(Kq(q), j, mm, Sq);
              for (int a = 0; a < n; ++a) {
                const double w = dNq[j * n + a] * dNq[mm * n + a];
                for (int o = 0; o < pairs; ++o) h(o, a) += w * Sq[o];
              }
            }
        }
      }
      for (int a = 0; a < n; ++a)
        for (int o = 0; o < pairs; ++o) y[pairs * a + o] = h(o, a);
    }
  }
  std::vector<double> blocks(mesh_->n_nodes() * static_cast<std::size_t>(dd));
  std::array<std::array<int, 2>, pairs> pair;  // pair o = (k, l), packed by rows
  for (int k = 0, o = 0; k < d; ++k)
    for (int l = k; l < d; ++l, ++o) pair[static_cast<std::size_t>(o)] = {k, l};
  gather(local, pairs, threads, [&](std::ptrdiff_t i, int o, double sum) {
    const auto [k, l] = pair[static_cast<std::size_t>(o)];
    double* b = blocks.data() + static_cast<std::size_t>(i) * dd;
    b[k + d * l] = b[l + d * k] = sum;
  });
  return blocks;
}

// Ac += Σ_q G_q K_q^{kl} G_qᵀ over the pairs k ≤ l of the cell's points (the blocks (k, l)
// of the local coarse matrix, corners × corners, v·d + k order), from the hats' gradients G_q
// (C × d) and the packed K_q; C fixed at compile time (8: hexahedra) or at run time (0).
template <int d, int C_>
void coarse_points(const std::vector<Eigen::MatrixXd>& gradients, int corners, const float* K, bool lanes, std::size_t c,
                   int Q, Eigen::MatrixXd& Ac) {
  constexpr int dd = k_sq(d);
  constexpr int C = C_ > 0 ? C_ : Eigen::Dynamic;
  constexpr int max_c = C_ > 0 ? C_ : 8;  // hexahedra have the most corners
  using Grad = Eigen::Matrix<double, C, d, Eigen::ColMajor, max_c, d>;
  using Block = Eigen::Matrix<double, C, C, Eigen::ColMajor, max_c, max_c>;
  std::array<Block, k_packed(d)> blocks;
  for (Block& b : blocks) b.setZero(corners, corners);
  for (int q = 0; q < Q; ++q) {
    const auto [entry, stride] = point_entries<d>(K, lanes, c, Q, q);
    const auto Kq = [&](int i, int j) {  // K_q(i, j) from the packed upper triangle
      return static_cast<double>(entry[(i <= j ? packed_index(dd, i, j) : packed_index(dd, j, i)) * stride]);
    };
    const Grad G = gradients[static_cast<std::size_t>(q)];
    for (int k = 0, o = 0; k < d; ++k)
      for (int l = k; l < d; ++l, ++o) {
        Eigen::Matrix<double, d, d> Kkl;  // (j, m) ↦ K_q(k + d j, l + d m)
        for (int j = 0; j < d; ++j)
          for (int m = 0; m < d; ++m) Kkl(j, m) = Kq(k + d * j, l + d * m);
        const Grad GK = G.lazyProduct(Kkl);
        blocks[static_cast<std::size_t>(o)].noalias() += GK.lazyProduct(G.transpose());
      }
  }
  for (int k = 0, o = 0; k < d; ++k)
    for (int l = k; l < d; ++l, ++o)
      for (int v = 0; v < corners; ++v)
        for (int w = 0; w < corners; ++w) {
          Ac(v * d + k, w * d + l) = blocks[static_cast<std::size_t>(o)](v, w);
          Ac(w * d + l, v * d + k) = blocks[static_cast<std::size_t>(o)](v, w);
        }
}

template <int d>
Eigen::SparseMatrix<double> EnergyAssembler<d>::coarse_hessian(const HessianAction<d>& action, const CoarseSpace<d>& coarse,
                                                               int threads) const {
  Eigen::SparseMatrix<double> A = coarse.pattern();
  double* values = A.valuePtr();
  for (std::size_t bi = 0; bi < blocks_.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const typename CoarseSpace<d>::Block& cb = coarse.block(bi);
    const int n = block.n_nodes_per_cell(), Q = targets_->blocks[bi].n_points(), m = d * cb.corners;
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    const std::vector<float>& E = action.element[bi];
    const float* K = action.K[bi].data();
    const bool lanes = action.tensor[bi] != nullptr;
    // The cells' coarse matrices (local coarse DOF v·d + k), then added in cell order.
    std::vector<double> local(static_cast<std::size_t>(n_cells) * m * m);
#pragma omp parallel num_threads(threads_of(threads))
    {
      Eigen::MatrixXd Ac(m, m), Ed, T;
#pragma omp for schedule(static)
      for (std::ptrdiff_t ci = 0; ci < n_cells; ++ci) {
        const auto c = static_cast<std::size_t>(ci);
        if (!E.empty()) {
          // R_eᵀ H_e R_e with H_e component-major (k·n + a) and R_e the hats at the nodes.
          const int dn = d * n;
          Ed.resize(dn, dn);
          const float* packed = E.data() + c * static_cast<std::size_t>(k_packed(dn));
          for (int i = 0; i < dn; ++i)
            for (int j = i; j < dn; ++j) Ed(i, j) = Ed(j, i) = *packed++;
          for (int l = 0; l < d; ++l) {
            T.noalias() = Ed.middleCols(l * n, n) * cb.values;  // dn × corners
            for (int k = 0; k < d; ++k) {
              const Eigen::MatrixXd Akl = cb.values.transpose() * T.middleRows(k * n, n);
              for (int v = 0; v < cb.corners; ++v)
                for (int w = 0; w < cb.corners; ++w) Ac(v * d + k, w * d + l) = Akl(v, w);
            }
          }
          Ac = 0.5 * (Ac + Ac.transpose()).eval();
        } else if (d == 3 && cb.corners == 8) {
          coarse_points<d, 8>(cb.gradients, cb.corners, K, lanes, c, Q, Ac);
        } else {
          coarse_points<d, 0>(cb.gradients, cb.corners, K, lanes, c, Q, Ac);
        }
        std::copy(Ac.data(), Ac.data() + m * m, local.data() + c * static_cast<std::size_t>(m * m));
      }
    }
    for (std::size_t c = 0; c < static_cast<std::size_t>(n_cells); ++c) {
      const double* a = local.data() + c * static_cast<std::size_t>(m * m);
      const std::int32_t* off = coarse.scatter(bi, c);
      for (int i = 0; i < m * m; ++i)
        if (off[i] >= 0) values[off[i]] += a[i];
    }
  }
  return A;
}

template <int d>
Eigen::VectorXd EnergyAssembler<d>::hessian_diagonal(const HessianAction<d>& action, int threads) const {
  const std::vector<double> blocks = hessian_blocks(action, threads);
  Eigen::VectorXd diagonal(static_cast<Eigen::Index>(dofs_->n_free()));
  const std::int32_t* red = dofs_->reduced_index().data();
  for (std::size_t i = 0; i < mesh_->n_nodes(); ++i)
    for (int k = 0; k < d; ++k)
      if (const std::int32_t r = red[d * i + k]; r >= 0) diagonal[r] = blocks[i * d * d + static_cast<std::size_t>(k * (d + 1))];
  return diagonal;
}

template class EnergyAssembler<2>;
template class EnergyAssembler<3>;

}  // namespace meshmorph

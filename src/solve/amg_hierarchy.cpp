// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "solve/detail/amg.h"

namespace meshmorph::detail {
namespace {

// ρ(D⁻¹A) by power iteration on D⁻¹A, reported as the Rayleigh quotient vᵀAv / vᵀDv (the
// quotient of the symmetric D^{-1/2} A D^{-1/2}, a lower bound that converges from below).
double spectral_radius_estimate(const SparseView& A, int block, const std::vector<double>& inv_diag, int iterations,
                                int threads) {
  const int n = A.n;
  std::vector<double> v(static_cast<std::size_t>(n)), w(static_cast<std::size_t>(n));
  std::uint64_t state = 0x9E3779B97F4A7C15ull;  // fixed seed: deterministic set-up
  for (double& e : v) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    e = static_cast<double>(state >> 11) * 0x1.0p-53 - 0.5;
  }
  double rho = 0.0;
  for (int it = 0; it < iterations; ++it) {
    spmv(A, block, v.data(), w.data(), threads);
    double vAv = 0.0, vDv = 0.0, ww = 0.0;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(+ : vAv, vDv, ww)
    for (int i = 0; i < n; ++i) {
      vAv += v[i] * w[i];
      vDv += v[i] * v[i] / inv_diag[i];
      w[i] *= inv_diag[i];
      ww += w[i] * w[i];
    }
    rho = vAv / vDv;
    const double scale = 1.0 / std::sqrt(ww);
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int i = 0; i < n; ++i) v[i] = w[i] * scale;
  }
  return rho;
}

}  // namespace

double AmgHierarchy::operator_complexity() const {
  double total = 0.0;
  for (const Level& L : levels_) total += static_cast<double>(L.A.nnz());
  return levels_.empty() ? 0.0 : total / static_cast<double>(levels_.front().A.nnz());
}

bool AmgHierarchy::setup(const SparseView& A) {
  const int block = options_.block_size > 0 && A.n % options_.block_size == 0 ? options_.block_size : 1;
  levels_.clear();
  levels_.emplace_back();
  levels_[0].A = A;
  levels_[0].block = block;
  // Near-null space: the `block` constant vectors, one per component. Per aggregate its QR
  // is Q = the aggregate's entries / their norm, R = the norm times I, so the coarse
  // near-null space keeps that form: a weight per node, the same for every component.
  std::vector<double> weights(static_cast<std::size_t>(A.n / block), 1.0);
  given_ = first_.cols > 0 && first_.rows == A.n && A.n > options_.coarse_size ? 1 : 0;
  for (std::size_t l = 0;; ++l) {
    if (!prepare_level(levels_[l])) return false;
    if (l == 0 && given_) {
      build_given_level(weights);
      continue;
    }
    const bool last = levels_[l].A.n <= options_.coarse_size || l + 1 >= static_cast<std::size_t>(options_.max_levels) ||
                      !build_level(l, weights);
    if (last) return coarse_.factorize(levels_[l].A);
  }
}

void AmgHierarchy::set_first_prolongator(Csr P) {
  first_ = std::move(P);
  levels_.clear();
}

void AmgHierarchy::build_given_level(std::vector<double>& weights) {
  const int threads = std::max(1, options_.threads);
  Level& L = levels_[0];
  L.P = first_;
  L.R = transpose(L.P, threads);
  Level next;
  L.product_block = product_block(L);
  galerkin(L.A, L.P, L.R, L.row_block, L.product_block, next.own, L.ap_blocks, false, threads);
  const int b = options_.block_size > 0 && first_.cols % options_.block_size == 0 ? options_.block_size : 1;
  next.block = b;
  levels_.push_back(std::move(next));
  levels_.back().A = levels_.back().own.view();
  // The hats sum to one at every node: the coarse constants are the fine ones.
  weights.assign(static_cast<std::size_t>(first_.cols / b), 1.0);
}

bool AmgHierarchy::rebind(const SparseView& A) {
  if (levels_.empty() || A.n != levels_[0].A.n || levels_.size() == 1) return false;  // one level: A is the coarse factor's
  levels_[0].A = A;
  return prepare_level(levels_[0]);
}

bool AmgHierarchy::refresh(const SparseView& A) {
  if (!rebind(A)) return false;
  const int threads = std::max(1, options_.threads);
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    Level& L = levels_[l];
    if (!galerkin(L.A, L.P, L.R, L.row_block, L.product_block, levels_[l + 1].own, L.ap_blocks, true, threads))
      return false;
    if (!prepare_level(levels_[l + 1])) return false;
  }
  return coarse_.factorize(levels_.back().A);
}

int AmgHierarchy::product_block(const Level& L) {
  const int b = L.block;
  // A P has block rows where A and P have (multiply's node-by-node pattern).
  return L.row_block == b && has_block_rows(L.P, b) && has_block_rows(L.R, b) ? b : 1;
}

bool AmgHierarchy::prepare_level(Level& L) {
  const int threads = std::max(1, options_.threads);
  const int n = L.A.n;
  // Checked at every rebind too: a new matrix of the same size may have another pattern.
  L.row_block = has_block_rows(L.A, L.block) ? L.block : 1;
  L.inv_diag.assign(static_cast<std::size_t>(n), 0.0);
  L.inv_l1.assign(static_cast<std::size_t>(n), 0.0);
  bool positive = true;
#pragma omp parallel for num_threads(threads) schedule(static) reduction(&& : positive)
  for (int i = 0; i < n; ++i) {
    double a = 0.0, l1 = 0.0;
    for (int k = L.A.outer[i]; k < L.A.outer[i + 1]; ++k) {
      if (L.A.inner[k] == i) a += L.A.values[k];
      l1 += std::abs(L.A.values[k]);
    }
    positive = positive && a > 0.0;
    L.inv_diag[i] = a > 0.0 ? 1.0 / a : 0.0;
    L.inv_l1[i] = a > 0.0 ? 1.0 / l1 : 0.0;
  }
  if (!positive) return false;
  for (auto* v : {&L.x, &L.b, &L.r, &L.d}) v->assign(static_cast<std::size_t>(n), 0.0);
  return true;
}

bool AmgHierarchy::build_level(std::size_t l, std::vector<double>& weights) {
  const int threads = std::max(1, options_.threads);
  const int b = levels_[l].block;
  const SparseView A = levels_[l].A;
  const double theta = options_.strength * std::pow(0.5, static_cast<double>(l - given_));  // θ halves per aggregation
  int n_agg = 0;
  const std::vector<int> agg = aggregate_nodes(A, b, theta, threads, n_agg);
  const int n_nodes = A.n / b;
  if (n_agg == 0 || static_cast<double>(n_agg) > 0.8 * n_nodes) return false;  // coarsening stalls

  // Tentative prolongator: node I, component k → coarse unknown b·agg(I) + k, value w_I/‖w‖_agg.
  std::vector<double> norm(static_cast<std::size_t>(n_agg), 0.0);
  for (int I = 0; I < n_nodes; ++I) norm[agg[I]] += weights[I] * weights[I];
  for (double& v : norm) v = std::sqrt(v);
  Csr T;
  T.rows = A.n;
  T.cols = b * n_agg;
  T.ptr.resize(static_cast<std::size_t>(A.n) + 1);
  T.idx.resize(static_cast<std::size_t>(A.n));
  T.val.resize(static_cast<std::size_t>(A.n));
  for (int i = 0; i < A.n; ++i) {
    T.ptr[i + 1] = i + 1;
    T.idx[i] = b * agg[i / b] + i % b;
    T.val[i] = weights[i / b] / norm[agg[i / b]];
  }
  // Smoothed prolongator P = (I − ω D⁻¹A) T with ω = 4/(3ρ(D⁻¹A)). Row i of AT contains
  // T's single column of row i (through a_ii), so P has the pattern of AT.
  Level& L = levels_[l];
  const double rho = spectral_radius_estimate(A, L.row_block, L.inv_diag, options_.power_iterations, threads);
  const double omega = 4.0 / (3.0 * rho);
  L.P = multiply(A, T, 1, threads);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int i = 0; i < A.n; ++i) {
    const double s = -omega * L.inv_diag[i];
    for (int k = L.P.ptr[i]; k < L.P.ptr[i + 1]; ++k) {
      L.P.val[k] *= s;
      if (L.P.idx[k] == T.idx[i]) L.P.val[k] += T.val[i];
    }
  }
  L.R = transpose(L.P, threads);
  L.product_block = product_block(L);
  Level next;
  galerkin(A, L.P, L.R, L.row_block, L.product_block, next.own, L.ap_blocks, false, threads);
  next.block = b;
  levels_.push_back(std::move(next));
  levels_.back().A = levels_.back().own.view();
  weights = std::move(norm);
  return true;
}

// Chebyshev iteration for A x = b preconditioned by the ℓ1 diagonal D₁ (row sums of |A|) on
// [1/ratio, 1] (Saad, Iterative Methods, Alg. 12.1 with M = D₁). D₁ − A is diagonally dominant,
// so the spectrum of D₁⁻¹A lies in (0, 1]: the interval's top is a bound, not an estimate
// (Baker, Falgout, Kolev, Yang 2011). An estimate of ρ(D⁻¹A) by a few power or Lanczos steps
// missed localized outliers or, once it found them, left the bulk unsmoothed (the 213k
// shell's CG iterations tripled). The same polynomial before and after the coarse correction
// keeps the V-cycle symmetric.
void AmgHierarchy::smooth(Level& L, bool zero_guess) {
  const int threads = std::max(1, options_.threads);
  const int n = L.A.n;
  const double upper = 1.0, lower = upper / options_.smoother_ratio;
  const double theta = 0.5 * (upper + lower), delta = 0.5 * (upper - lower), sigma = theta / delta;
  double rho = 1.0 / sigma;
  if (zero_guess) {
    std::fill(L.x.begin(), L.x.end(), 0.0);
    std::copy(L.b.begin(), L.b.end(), L.r.begin());
  } else {
    residual_of(L);
  }
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int i = 0; i < n; ++i) L.d[i] = L.inv_l1[i] * L.r[i] / theta;
  for (int k = 1;; ++k) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int i = 0; i < n; ++i) L.x[i] += L.d[i];
    if (k >= options_.smoother_degree) return;
    residual_of(L);
    const double rho_new = 1.0 / (2.0 * sigma - rho);
    const double c1 = rho_new * rho, c2 = 2.0 * rho_new / delta;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (int i = 0; i < n; ++i) L.d[i] = c1 * L.d[i] + c2 * L.inv_l1[i] * L.r[i];
    rho = rho_new;
  }
}

void AmgHierarchy::cycle(std::size_t l) {
  Level& L = levels_[l];
  if (l + 1 == levels_.size()) {
    coarse_.solve(L.b.data(), L.x.data());
    return;
  }
  const int threads = std::max(1, options_.threads);
  Level& C = levels_[l + 1];
  smooth(L, true);
  residual_of(L);
  spmv(L.R, L.product_block, L.r.data(), C.b.data(), threads);
  cycle(l + 1);
  spmv(L.P, L.product_block, C.x.data(), L.d.data(), threads);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int i = 0; i < L.A.n; ++i) L.x[i] += L.d[i];
  smooth(L, false);
}

void AmgHierarchy::residual_of(Level& L) const {
  residual(L.A, L.row_block, L.b.data(), L.x.data(), L.r.data(), std::max(1, options_.threads));
}

void AmgHierarchy::apply_operator(const double* x, double* y) const {
  const Level& L = levels_.front();
  spmv(L.A, L.row_block, x, y, std::max(1, options_.threads));
}

void AmgHierarchy::apply(const double* r, double* z) {
  Level& L = levels_.front();
  std::copy(r, r + L.A.n, L.b.begin());
  cycle(0);
  std::copy(L.x.begin(), L.x.end(), z);
}

}  // namespace meshmorph::detail

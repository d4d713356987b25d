// SPDX-License-Identifier: MIT
#pragma once
#include <vector>

namespace meshmorph::detail {

/// A single-precision copy of a supernodal Cholesky factor P A Pᵀ = L Lᵀ, for preconditioning.
///
/// CG preconditioned by the factor of an earlier Newton matrix spends its time in the two
/// triangular solves, which stream L through memory: in single precision they read half the
/// bytes (3.4k-node shell: 13.5 MB instead of 27, inside this machine's 32 MB L3). The
/// rounding changes the preconditioner by ~1e-7 relative per entry, far less than the earlier
/// iterate already does; the products with A and the CG recurrences stay in double, and so does
/// every solve through a fresh factorization.
///
/// The layout is CHOLMOD's supernodal one: supernode s holds columns super[s] to super[s+1]−1,
/// its row indices are s_rows[pi[s] .. pi[s+1]) (the first ones its own columns), its values a
/// column-major block from x[px[s]] with one row per row index.
class FloatFactor {
 public:
  /// Copies a factor of n unknowns with nsuper supernodes; perm[k] is the row of A that is row k
  /// of P A Pᵀ.
  void assign(int n, int nsuper, const int* super, const int* pi, const int* px, const int* s_rows, const double* x,
              const int* perm);
  /// x = (Lᵀ)⁻¹ L⁻¹ b in the unknowns of A; b and x may alias. Accumulates in double.
  void solve(const double* b, double* x) const;
  bool empty() const { return x_.empty(); }
  void clear();

 private:
  // Supernode s: its first column, columns, rows, row indices and column-major values.
  struct Supernode {
    int k1, nc, nr;
    const int* rows;
    const float* L;
  };
  Supernode supernode(int s) const;
  // One supernode's part of L y = b (its columns solved, the rows below updated) and of
  // Lᵀ z = y (its columns solved from the rows below), in y_.
  void forward(int s) const;
  void backward(int s) const;

  std::vector<int> super_, pi_, px_, rows_, perm_;
  std::vector<float> x_;
  mutable std::vector<double> y_, work_;
};

}  // namespace meshmorph::detail

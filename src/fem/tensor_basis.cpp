// SPDX-License-Identifier: MIT
#include "meshmorph/fem/tensor_basis.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "meshmorph/fem/reference_element.h"

namespace meshmorph {
namespace {

TensorBasis make_tensor_basis(ElementType type, int order) {
  TensorBasis t;
  if (type != ElementType::Quadrilateral && type != ElementType::Hexahedron) return t;
  const ReferenceElement& ref = reference_element(type, order);
  const int dim = ref.dim, n = ref.n_nodes();
  std::vector<double> xs(ref.nodes.row(0).begin(), ref.nodes.row(0).end());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }), xs.end());
  const int P = static_cast<int>(xs.size());
  if (static_cast<int>(std::lround(std::pow(P, dim))) != n) return t;
  std::vector<std::int32_t> node(static_cast<std::size_t>(n), -1);
  for (int a = 0; a < n; ++a) {
    int lattice = 0;
    for (int k = dim - 1; k >= 0; --k) {
      const auto at = std::find_if(xs.begin(), xs.end(), [&](double v) { return std::abs(v - ref.nodes(k, a)) < 1e-12; });
      if (at == xs.end()) return t;
      lattice = lattice * P + static_cast<int>(at - xs.begin());
    }
    node[static_cast<std::size_t>(lattice)] = a;
  }
  if (std::count(node.begin(), node.end(), -1) > 0) return t;
  t.P = P;
  t.nodes = std::move(xs);
  t.node = std::move(node);
  return t;
}

}  // namespace

void TensorBasis::tabulate(const std::vector<double>& x, Eigen::MatrixXd& B, Eigen::MatrixXd& D) const {
  const auto m = static_cast<Eigen::Index>(x.size());
  B.resize(m, P);
  D.resize(m, P);
  for (Eigen::Index q = 0; q < m; ++q)
    for (int i = 0; i < P; ++i) {
      double value = 1.0, slope = 0.0;
      for (int j = 0; j < P; ++j) {
        if (j == i) continue;
        const double h = nodes[static_cast<std::size_t>(i)] - nodes[static_cast<std::size_t>(j)];
        const double f = (x[static_cast<std::size_t>(q)] - nodes[static_cast<std::size_t>(j)]) / h;
        slope = slope * f + value / h;  // product rule
        value *= f;
      }
      B(q, i) = value;
      D(q, i) = slope;
    }
}

TensorGrid tensor_grid(ElementType type, int order, const std::vector<double>& x) {
  TensorGrid g;
  const TensorBasis& basis = tensor_basis(type, order);
  if (basis.P == 0) return g;
  g.basis = &basis;
  g.dim = topological_dim(type);
  g.m = static_cast<int>(x.size());
  basis.tabulate(x, g.B, g.D);
  return g;
}

namespace {

// Work space of the 1D passes, per thread: no allocation per cell once grown.
std::vector<double>& scratch(int i, std::size_t size) {
  thread_local std::vector<double> buffers[5];
  std::vector<double>& b = buffers[i];
  if (b.size() < size) b.resize(size);
  return b;
}

}  // namespace

void grid_gradients(const TensorGrid& g, const double* X, int c, double* G) {
  const int P = g.basis->P, m = g.m;
  const auto& node = g.basis->node;
  const auto B = [&](int q, int i) { return g.B(q, i); };
  const auto D = [&](int q, int i) { return g.D(q, i); };
  // u at lattice index l, component k: X(k, node[l]).
  const auto u = [&](int l, int k) { return X[k + c * node[static_cast<std::size_t>(l)]]; };
  const int rest = g.dim == 3 ? P * P : P;  // lattice indices after x
  double* A0 = scratch(0, static_cast<std::size_t>(c * m * rest)).data();
  double* A1 = scratch(1, static_cast<std::size_t>(c * m * rest)).data();
  for (int r = 0; r < rest; ++r)
    for (int qx = 0; qx < m; ++qx)
      for (int k = 0; k < c; ++k) {
        double a0 = 0.0, a1 = 0.0;
        for (int ix = 0; ix < P; ++ix) {
          const double v = u(ix + P * r, k);
          a0 += B(qx, ix) * v;
          a1 += D(qx, ix) * v;
        }
        A0[k + c * (qx + m * r)] = a0;
        A1[k + c * (qx + m * r)] = a1;
      }
  if (g.dim == 2) {
    for (int qy = 0; qy < m; ++qy)
      for (int qx = 0; qx < m; ++qx)
        for (int k = 0; k < c; ++k) {
          double g0 = 0.0, g1 = 0.0;
          for (int iy = 0; iy < P; ++iy) {
            g0 += B(qy, iy) * A1[k + c * (qx + m * iy)];
            g1 += D(qy, iy) * A0[k + c * (qx + m * iy)];
          }
          const int q = qx + m * qy;
          G[k + c * (2 * q)] = g0;
          G[k + c * (2 * q + 1)] = g1;
        }
    return;
  }
  // y pass at (qx, qy, iz): C00 = B_y A0, C01 = D_y A0, C10 = B_y A1.
  const auto size = static_cast<std::size_t>(c * m * m * P);
  double* C00 = scratch(2, size).data();
  double* C01 = scratch(3, size).data();
  double* C10 = scratch(4, size).data();
  for (int iz = 0; iz < P; ++iz)
    for (int qy = 0; qy < m; ++qy)
      for (int qx = 0; qx < m; ++qx)
        for (int k = 0; k < c; ++k) {
          double c00 = 0.0, c01 = 0.0, c10 = 0.0;
          for (int iy = 0; iy < P; ++iy) {
            const int i = k + c * (qx + m * (iy + P * iz));
            c00 += B(qy, iy) * A0[i];
            c01 += D(qy, iy) * A0[i];
            c10 += B(qy, iy) * A1[i];
          }
          const int o = k + c * (qx + m * (qy + m * iz));
          C00[o] = c00;
          C01[o] = c01;
          C10[o] = c10;
        }
  for (int qz = 0; qz < m; ++qz)
    for (int qy = 0; qy < m; ++qy)
      for (int qx = 0; qx < m; ++qx)
        for (int k = 0; k < c; ++k) {
          double g0 = 0.0, g1 = 0.0, g2 = 0.0;
          for (int iz = 0; iz < P; ++iz) {
            const int o = k + c * (qx + m * (qy + m * iz));
            g0 += B(qz, iz) * C10[o];
            g1 += B(qz, iz) * C01[o];
            g2 += D(qz, iz) * C00[o];
          }
          const int q = qx + m * (qy + m * qz);
          G[k + c * (3 * q)] = g0;
          G[k + c * (3 * q + 1)] = g1;
          G[k + c * (3 * q + 2)] = g2;
        }
}

void grid_gradients_transpose(const TensorGrid& g, const double* R, int c, double* Y) {
  const int P = g.basis->P, m = g.m;
  const auto& node = g.basis->node;
  const auto B = [&](int q, int i) { return g.B(q, i); };
  const auto D = [&](int q, int i) { return g.D(q, i); };
  const int rest = g.dim == 3 ? P * P : P;
  // The adjoints of grid_gradients' x-pass outputs A0, A1, at (qx, lattice rest).
  double* F0 = scratch(0, static_cast<std::size_t>(c * m * rest)).data();
  double* F1 = scratch(1, static_cast<std::size_t>(c * m * rest)).data();
  if (g.dim == 2) {
    for (int iy = 0; iy < P; ++iy)
      for (int qx = 0; qx < m; ++qx)
        for (int k = 0; k < c; ++k) {
          double f0 = 0.0, f1 = 0.0;
          for (int qy = 0; qy < m; ++qy) {
            const int q = qx + m * qy;
            f0 += D(qy, iy) * R[k + c * (2 * q + 1)];
            f1 += B(qy, iy) * R[k + c * (2 * q)];
          }
          F0[k + c * (qx + m * iy)] = f0;
          F1[k + c * (qx + m * iy)] = f1;
        }
  } else {
    // The adjoints of C10, C01, C00 at (qx, qy, iz).
    const auto size = static_cast<std::size_t>(c * m * m * P);
    double* E10 = scratch(2, size).data();
    double* E01 = scratch(3, size).data();
    double* E00 = scratch(4, size).data();
    for (int iz = 0; iz < P; ++iz)
      for (int qy = 0; qy < m; ++qy)
        for (int qx = 0; qx < m; ++qx)
          for (int k = 0; k < c; ++k) {
            double e10 = 0.0, e01 = 0.0, e00 = 0.0;
            for (int qz = 0; qz < m; ++qz) {
              const int q = qx + m * (qy + m * qz);
              e10 += B(qz, iz) * R[k + c * (3 * q)];
              e01 += B(qz, iz) * R[k + c * (3 * q + 1)];
              e00 += D(qz, iz) * R[k + c * (3 * q + 2)];
            }
            const int o = k + c * (qx + m * (qy + m * iz));
            E10[o] = e10;
            E01[o] = e01;
            E00[o] = e00;
          }
    for (int iz = 0; iz < P; ++iz)
      for (int iy = 0; iy < P; ++iy)
        for (int qx = 0; qx < m; ++qx)
          for (int k = 0; k < c; ++k) {
            double f0 = 0.0, f1 = 0.0;
            for (int qy = 0; qy < m; ++qy) {
              const int o = k + c * (qx + m * (qy + m * iz));
              f0 += B(qy, iy) * E00[o] + D(qy, iy) * E01[o];
              f1 += B(qy, iy) * E10[o];
            }
            F0[k + c * (qx + m * (iy + P * iz))] = f0;
            F1[k + c * (qx + m * (iy + P * iz))] = f1;
          }
  }
  for (int r = 0; r < rest; ++r)
    for (int ix = 0; ix < P; ++ix)
      for (int k = 0; k < c; ++k) {
        double y = 0.0;
        for (int qx = 0; qx < m; ++qx) y += B(qx, ix) * F0[k + c * (qx + m * r)] + D(qx, ix) * F1[k + c * (qx + m * r)];
        Y[k + c * node[static_cast<std::size_t>(ix + P * r)]] = y;
      }
}

const TensorBasis& tensor_basis(ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<TensorBasis>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (!slot) slot = std::make_unique<TensorBasis>(make_tensor_basis(type, order));
  return *slot;
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "energy/detail/hessian_kernels.h"

#include <cstring>
#include <random>
#include <set>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include "meshmorph/fem/shape_table.h"

namespace meshmorph::detail {
namespace {

// A random symmetric n × n matrix in single precision, packed by rows of its upper triangle.
std::vector<float> random_packed(int n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  std::vector<float> K(static_cast<std::size_t>(k_packed(n)));
  for (float& k : K) k = u(rng);
  return K;
}

// Entry (i, j) of a packed symmetric n × n matrix whose entries are `stride` apart.
double unpacked(const float* K, int n, int i, int j, int stride = 1) {
  return K[stride * (i <= j ? packed_index(n, i, j) : packed_index(n, j, i))];
}

TEST(HessianKernels, PackedIndexFollowsThePackingOrder) {
  for (int n : {1, 4, 9, 30})
    for (int i = 0, o = 0; i < n; ++i)
      for (int j = i; j < n; ++j, ++o) EXPECT_EQ(packed_index(n, i, j), o);
}

// h = K g to rounding, and the run-time size gives the compile-time one's h bit for bit.
TEST(HessianKernels, PackedProductIsTheSymmetricProduct) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const std::vector<float> K = random_packed(9, rng);
  Eigen::Matrix<double, 9, 1> g, h, h_n;
  for (int i = 0; i < 9; ++i) g[i] = u(rng);
  packed_product<9>(K.data(), g.data(), h.data());
  packed_product(K.data(), g.data(), h_n.data(), 9);
  Eigen::Matrix<double, 9, 9> dense;
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) dense(i, j) = unpacked(K.data(), 9, i, j);
  EXPECT_LE((h - dense * g).norm(), 1e-14 * (dense * g).norm());
  EXPECT_EQ(std::memcmp(h.data(), h_n.data(), sizeof(double) * 9), 0);
}

// Every (cell, point, entry) of a block has its own place in K, inside the padded block; cells
// of a batch sit side by side where they are interleaved by lanes.
TEST(HessianKernels, PointEntriesPlaceEveryEntryOnce) {
  constexpr int n = k_packed(9), Q = 5, n_cells = 7, padded = 8;
  const std::vector<float> block(static_cast<std::size_t>(padded * Q * n));
  const float* K = block.data();
  for (bool lanes : {false, true}) {
    std::set<std::ptrdiff_t> offsets;
    for (std::size_t c = 0; c < n_cells; ++c)
      for (int q = 0; q < Q; ++q) {
        const auto [first, stride] = point_entries<3>(K, lanes, c, Q, q);
        EXPECT_EQ(stride, lanes ? k_lanes : 1);
        if (lanes && c % k_lanes != 0) {
          EXPECT_EQ(first - point_entries<3>(K, lanes, c - 1, Q, q).first, 1);
        }
        for (int e = 0; e < n; ++e) offsets.insert(first + e * stride - K);
      }
    EXPECT_EQ(offsets.size(), static_cast<std::size_t>(n_cells * Q * n));
    EXPECT_GE(*offsets.begin(), 0);
    EXPECT_LT(*offsets.rbegin(), (lanes ? padded : n_cells) * Q * n);
  }
}

// hex_kernel's sum factorization against the dense y_e = Σ_q mat(K_q vec(U_e ∇N_q)) ∇N_qᵀ, per
// lane: Lobatto rules with m = P + 1 (the compiled sizes) and Gauss rules with m = P (general).
TEST(HessianKernels, HexKernelIsTheDenseProduct) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (QuadratureFamily family : {QuadratureFamily::Lobatto, QuadratureFamily::Gauss})
    for (int order = 1; order <= 4; ++order) {
      SCOPED_TRACE("order " + std::to_string(order));
      const ShapeTable& table = shape_table(ElementType::Hexahedron, order, 2 * order + 1, family);
      ASSERT_NE(table.tensor, nullptr);
      const TensorGrid& t = *table.tensor;
      const int n = table.n_nodes(), Q = table.n_points();
      EXPECT_EQ(t.m, order + (family == QuadratureFamily::Lobatto ? 2 : 1));
      HexScratch s;
      s.u.resize(static_cast<std::size_t>(3 * n * k_lanes));
      for (double& x : s.u) x = u(rng);
      std::vector<float> K;
      for (int i = 0; i < Q * k_packed(9) * k_lanes; ++i) K.push_back(static_cast<float>(u(rng)));
      hex_kernel(t, K.data(), s);
      ASSERT_EQ(s.y.size(), s.u.size());
      for (int e = 0; e < k_lanes; ++e) {
        Eigen::MatrixXd U(3, n), Y = Eigen::MatrixXd::Zero(3, n);
        for (int l = 0; l < n; ++l)
          for (int k = 0; k < 3; ++k) U(k, t.basis->node[static_cast<std::size_t>(l)]) = s.u[static_cast<std::size_t>((3 * l + k) * k_lanes + e)];
        for (int q = 0; q < Q; ++q) {
          const Eigen::Matrix3d G = U * table.grad(q);
          Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
          for (int i = 0; i < 9; ++i)
            for (int j = 0; j < 9; ++j) H(i % 3, i / 3) += unpacked(K.data() + (q * k_packed(9)) * k_lanes + e, 9, i, j, k_lanes) * G(j % 3, j / 3);
          Y += H * table.grad(q).transpose();
        }
        double error = 0.0;
        for (int l = 0; l < n; ++l)
          for (int k = 0; k < 3; ++k)
            error = std::max(error, std::abs(s.y[static_cast<std::size_t>((3 * l + k) * k_lanes + e)] - Y(k, t.basis->node[static_cast<std::size_t>(l)])));
        EXPECT_LE(error, 1e-12 * Y.cwiseAbs().maxCoeff());
      }
    }
}

}  // namespace
}  // namespace meshmorph::detail

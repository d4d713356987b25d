// SPDX-License-Identifier: MIT
#include "meshmorph/energy/assembler.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "energy/detail/pattern.h"
#include "energy/energy_fixtures.h"
#include "meshmorph/fem/trace.h"
#include "support/derivative_check.h"
#include "support/element_cases.h"

namespace meshmorph {
namespace {

struct MeshCase {
  ElementType type;
  int order;
  int n;  // cells per side of structured_mesh
};

std::string mesh_case_name(const ::testing::TestParamInfo<MeshCase>& p) {
  return std::string(name_of(p.param.type)) + "_p" + std::to_string(p.param.order) + "_n" + std::to_string(p.param.n);
}

// A perturbed structured mesh, its topology, input targets, a metric and an assembler.
template <int d>
struct Problem {
  Mesh mesh;
  Topology topology;
  TargetField<d> targets;
  DofMap dofs;
  std::unique_ptr<Metric<d>> metric;
  std::unique_ptr<EnergyAssembler<d>> assembler;

  Problem(const MeshCase& c, const std::string& metric_name = "distortion2", bool fix_boundary = false)
      : mesh(test::perturbed_mesh(c.type, c.order, c.n, 17)),
        topology(build_topology(mesh)),
        targets(build_targets<d>(mesh, mesh.x, TargetKind::Input)),
        dofs(fix_boundary ? DofMap::fixing_boundary(mesh, topology) : DofMap::all_free(d, mesh.n_nodes())),
        metric(test::test_metric<d>(metric_name)),
        assembler(std::make_unique<EnergyAssembler<d>>(mesh, topology, targets, dofs)) {}

  Assembly assemble(const Eigen::MatrixXd& x, Want want, HessianMode mode = HessianMode::Projected, int threads = 0,
                    std::span<const double> weights = {}) const {
    Assembly out;
    AssemblyOptions options;
    options.want = want;
    options.hessian = mode;
    options.threads = threads;
    options.weights = weights;
    assembler->assemble(*metric, x, options, out);
    return out;
  }
};

class AssemblerOnMesh : public ::testing::TestWithParam<MeshCase> {
 protected:
  // A valid state other than the input: the interior nodes moved at random once more.
  Eigen::MatrixXd state() const {
    const MeshCase c = GetParam();
    return test::perturbed_mesh(c.type, c.order, c.n, 23).x;
  }

  template <int d>
  void matches_sum_of_elements() {
    const Problem<d> p(GetParam());
    const Eigen::MatrixXd x = state();
    std::vector<double> w(p.mesh.n_cells());
    std::mt19937 rng(5);
    for (double& v : w) v = std::uniform_real_distribution<double>(1.0, 2.0)(rng);
    for (HessianMode mode : {HessianMode::Exact, HessianMode::Projected}) {
      const Assembly a = p.assemble(x, Want::Hessian, mode, 0, w);
      const auto n_dofs = static_cast<Eigen::Index>(d * p.mesh.n_nodes());
      Eigen::VectorXd g = Eigen::VectorXd::Zero(n_dofs);
      Eigen::MatrixXd H = Eigen::MatrixXd::Zero(n_dofs, n_dofs);
      double value = 0.0;
      std::size_t global = 0;
      for (std::size_t bi = 0; bi < p.mesh.cells.size(); ++bi) {
        const CellBlock& block = p.mesh.cells[bi];
        const BlockTargets<d>& bt = p.targets.blocks[bi];
        const int n = block.n_nodes_per_cell();
        for (std::size_t c = 0; c < block.n_cells(); ++c, ++global) {
          Eigen::Matrix<double, d, Eigen::Dynamic> X(d, n);
          for (int i = 0; i < n; ++i) X.col(i) = x.col(block.cell(c)[i]);
          const ElementEnergy e = element_energy<d>(*p.metric, *bt.table, {bt.cell(c), std::size_t(bt.n_points())}, X,
                                                    Want::Hessian, mode);
          EXPECT_EQ(a.element_values[global], e.value);
          value += w[global] * e.value;
          for (int i = 0; i < d * n; ++i) {
            const Eigen::Index gi = d * block.cell(c)[i / d] + i % d;
            g[gi] += w[global] * e.gradient[i];
            for (int j = 0; j < d * n; ++j) H(gi, d * block.cell(c)[j / d] + j % d) += w[global] * e.hessian(i, j);
          }
        }
      }
      EXPECT_NEAR(a.value, value, 1e-13 * value);
      EXPECT_LE((a.gradient - g).norm(), 1e-13 * g.norm());
      const Eigen::MatrixXd Ha(a.hessian);
      EXPECT_LE((Ha - H).norm(), 1e-13 * H.norm());
      EXPECT_EQ((Ha - Ha.transpose()).norm(), 0.0);  // exactly symmetric
    }
  }

  template <int d>
  void matches_finite_differences() {
    const Problem<d> p(GetParam());
    const Eigen::MatrixXd x = state();
    const Assembly a = p.assemble(x, Want::Hessian, HessianMode::Exact);
    const Eigen::VectorXd v = Eigen::Map<const Eigen::VectorXd>(x.data(), x.size());
    auto at = [&](const Eigen::VectorXd& y) { return Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(y.data(), d, y.size() / d)); };
    const double h = test::fd_step(0.1 / (GetParam().n * GetParam().order));
    test::expect_gradient_matches_fd([&](const Eigen::VectorXd& y) { return p.assembler->value(*p.metric, at(y)); }, v,
                                     a.gradient, h, 1e-6);
    test::expect_hessian_matches_fd([&](const Eigen::VectorXd& y) { return p.assemble(at(y), Want::Gradient).gradient; }, v,
                                    Eigen::MatrixXd(a.hessian), h, 1e-6);
    // The line-search entry point and the assembly agree bit for bit.
    EXPECT_EQ(p.assembler->value(*p.metric, x), a.value);
  }

  template <int d>
  void projected_is_psd() {
    const Problem<d> p(GetParam());
    const Eigen::MatrixXd H(p.assemble(state(), Want::Hessian, HessianMode::Projected).hessian);
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(H);
    EXPECT_GE(eig.eigenvalues().minCoeff(), -1e-12 * H.cwiseAbs().maxCoeff());
  }

  template <int d>
  void fixed_dofs_give_the_submatrix() {
    const MeshCase c = GetParam();
    const Problem<d> full(c);
    const Problem<d> reduced(c, "distortion2", true);
    const Eigen::MatrixXd x = state();
    const Assembly a = full.assemble(x, Want::Hessian);
    const Eigen::MatrixXd H(a.hessian);
    auto check = [&](const DofMap& dofs) {
      ASSERT_GT(dofs.n_free(), 0u);
      const EnergyAssembler<d> assembler(reduced.mesh, reduced.topology, reduced.targets, dofs);
      Assembly r;
      assembler.assemble(*full.metric, x, {}, r);
      EXPECT_EQ(r.value, a.value);
      ASSERT_EQ(r.gradient.size(), static_cast<Eigen::Index>(dofs.n_free()));
      const Eigen::MatrixXd Hr(r.hessian);
      for (std::size_t i = 0; i < dofs.n_free(); ++i) {
        const auto fi = static_cast<Eigen::Index>(i);
        EXPECT_EQ(r.gradient[fi], a.gradient[dofs.free_dofs()[i]]);
        for (std::size_t j = 0; j < dofs.n_free(); ++j)
          EXPECT_EQ(Hr(fi, static_cast<Eigen::Index>(j)), H(dofs.free_dofs()[i], dofs.free_dofs()[j]));
      }
    };
    EXPECT_LT(reduced.dofs.n_free(), full.dofs.n_free());
    check(reduced.dofs);
    std::vector<std::uint8_t> mask(full.dofs.n_dofs());  // any mask: single components too
    std::mt19937 rng(3);
    for (auto& m : mask) m = std::uniform_int_distribution<int>(0, 2)(rng) == 0;
    check(DofMap::from_mask(d, mask));
  }

  template <int d>
  void thread_counts_agree_bit_for_bit() {
    const Problem<d> p(GetParam());
    const Eigen::MatrixXd x = state();
    const Assembly one = p.assemble(x, Want::Hessian, HessianMode::Projected, 1);
    const Assembly two = p.assemble(x, Want::Hessian, HessianMode::Projected, 2);
    EXPECT_EQ(std::memcmp(&one.value, &two.value, sizeof(double)), 0);
    ASSERT_EQ(one.gradient.size(), two.gradient.size());
    EXPECT_EQ(std::memcmp(one.gradient.data(), two.gradient.data(), sizeof(double) * std::size_t(one.gradient.size())), 0);
    ASSERT_EQ(one.hessian.nonZeros(), two.hessian.nonZeros());
    EXPECT_EQ(std::memcmp(one.hessian.valuePtr(), two.hessian.valuePtr(), sizeof(double) * std::size_t(one.hessian.nonZeros())), 0);
    EXPECT_EQ(p.assembler->value(*p.metric, x, {}, 1), p.assembler->value(*p.metric, x, {}, 2));
    // Reusing an Assembly (pattern kept, values rewritten) gives the same numbers again.
    Assembly reused = two;
    AssemblyOptions options;
    options.threads = 2;
    p.assembler->assemble(*p.metric, x, options, reused);
    EXPECT_EQ(std::memcmp(one.hessian.valuePtr(), reused.hessian.valuePtr(), sizeof(double) * std::size_t(one.hessian.nonZeros())), 0);
  }

  template <int d>
  void similarity_has_zero_gradient() {
    // Against the input target the distortion is 1 at every point of any similarity of the
    // input: E = Σ_e |e| (the domain's volume, 1) and ∇E = 0.
    const Problem<d> p(GetParam(), "distortion");
    Eigen::MatrixXd R = Eigen::MatrixXd::Identity(d, d);
    R.topLeftCorner(2, 2) << std::cos(1.1), -std::sin(1.1), std::sin(1.1), std::cos(1.1);
    Eigen::MatrixXd x = 0.6 * R * p.mesh.x;
    x.colwise() += Eigen::VectorXd::Constant(d, -2.0);
    const Assembly a = p.assemble(x, Want::Gradient);
    EXPECT_NEAR(a.value, 1.0, 1e-12);
    EXPECT_LE(a.gradient.cwiseAbs().maxCoeff(), 1e-12);
    const Assembly moved = p.assemble(state(), Want::Gradient);
    EXPECT_GT(moved.value, 1.0 + 1e-6);  // and a non-similar state is worse
    EXPECT_GT(moved.gradient.cwiseAbs().maxCoeff(), 1e-6);
  }

  template <int d>
  void inverted_element_gives_infinity() {
    const Problem<d> p(GetParam());
    Eigen::MatrixXd x = p.mesh.x;
    const std::int32_t* cell = p.mesh.cells[0].cell(0);
    x.col(cell[0]) = x.col(cell[1]) + 1.5 * (x.col(cell[1]) - x.col(cell[0]));  // corner 0 through corner 1
    EXPECT_EQ(p.assembler->value(*p.metric, x), std::numeric_limits<double>::infinity());
    const Assembly a = p.assemble(x, Want::Hessian);
    EXPECT_EQ(a.value, std::numeric_limits<double>::infinity());
    EXPECT_EQ(a.element_values[0], std::numeric_limits<double>::infinity());
  }

  template <int d>
  void run(void (AssemblerOnMesh::*f2)(), void (AssemblerOnMesh::*f3)()) {
    (this->*(topological_dim(GetParam().type) == 2 ? f2 : f3))();
  }
};

#define MESHMORPH_BOTH_DIMS(fn) run<2>(&AssemblerOnMesh::fn<2>, &AssemblerOnMesh::fn<3>)

TEST_P(AssemblerOnMesh, MatchesSumOfElementEnergies) { MESHMORPH_BOTH_DIMS(matches_sum_of_elements); }
TEST_P(AssemblerOnMesh, MatchesFiniteDifferencesOfTheEnergy) { MESHMORPH_BOTH_DIMS(matches_finite_differences); }
TEST_P(AssemblerOnMesh, ProjectedHessianIsPsd) { MESHMORPH_BOTH_DIMS(projected_is_psd); }
TEST_P(AssemblerOnMesh, FixedDofEliminationGivesTheSubmatrix) { MESHMORPH_BOTH_DIMS(fixed_dofs_give_the_submatrix); }
TEST_P(AssemblerOnMesh, OneAndTwoThreadsAgreeBitForBit) { MESHMORPH_BOTH_DIMS(thread_counts_agree_bit_for_bit); }
TEST_P(AssemblerOnMesh, SimilarityOfTheInputHasZeroGradient) { MESHMORPH_BOTH_DIMS(similarity_has_zero_gradient); }
TEST_P(AssemblerOnMesh, InvertedElementGivesInfiniteEnergy) { MESHMORPH_BOTH_DIMS(inverted_element_gives_infinity); }

INSTANTIATE_TEST_SUITE_P(Small, AssemblerOnMesh,
                         ::testing::Values(MeshCase{ElementType::Triangle, 2, 2}, MeshCase{ElementType::Quadrilateral, 3, 1},
                                           MeshCase{ElementType::Tetrahedron, 1, 2}, MeshCase{ElementType::Tetrahedron, 2, 1},
                                           MeshCase{ElementType::Hexahedron, 2, 1}, MeshCase{ElementType::Triangle, 1, 3}),
                         mesh_case_name);

// Meshes of many patches (the suite's meshes have one): 1 and 2 threads still agree bit for bit.
template <int d>
void many_patches_agree_across_threads(ElementType type, int order, int n) {
  const Problem<d> p(MeshCase{type, order, n});
  const Eigen::MatrixXd x = test::perturbed_mesh(type, order, n, 23).x;
  for (HessianMode mode : {HessianMode::Exact, HessianMode::Projected}) {
    const Assembly one = p.assemble(x, Want::Hessian, mode, 1);
    const Assembly two = p.assemble(x, Want::Hessian, mode, 2);
    EXPECT_EQ(std::memcmp(&one.value, &two.value, sizeof(double)), 0);
    EXPECT_EQ(std::memcmp(one.gradient.data(), two.gradient.data(), sizeof(double) * std::size_t(one.gradient.size())), 0);
    EXPECT_EQ(std::memcmp(one.hessian.valuePtr(), two.hessian.valuePtr(), sizeof(double) * std::size_t(one.hessian.nonZeros())), 0);
    const Eigen::SparseMatrix<double> Ht = one.hessian.transpose();
    EXPECT_EQ((one.hessian - Ht).norm(), 0.0);  // exactly symmetric
  }
}

TEST(EnergyAssembler, ManyPatchesAgreeAcrossThreadCounts) {
  many_patches_agree_across_threads<2>(ElementType::Triangle, 1, 24);
  many_patches_agree_across_threads<3>(ElementType::Tetrahedron, 1, 6);
  many_patches_agree_across_threads<3>(ElementType::Tetrahedron, 2, 3);
}

TEST(EnergyAssembler, PatchesOfOneColourShareNoNode) {
  const Mesh mesh = structured_mesh(ElementType::Tetrahedron, 2, 4);
  const Topology topology = build_topology(mesh);
  const CellBlock& block = mesh.cells[0];
  const int patch_size = 16;
  const detail::CellPatches p = detail::patch_cells(block, topology, 0, patch_size);
  ASSERT_EQ(p.order.size(), block.n_cells());
  std::vector<int> seen(block.n_cells(), 0);
  for (std::int32_t c : p.order) ++seen[static_cast<std::size_t>(c)];
  EXPECT_TRUE(std::all_of(seen.begin(), seen.end(), [](int k) { return k == 1; }));  // every cell once
  const auto n_colors = static_cast<std::int32_t>(p.color_offset.size()) - 1;
  EXPECT_GE(n_colors, 2);
  std::vector<std::int32_t> owner(mesh.n_nodes());  // patch of the colour that touches each node
  for (std::int32_t k = 0; k < n_colors; ++k) {
    std::fill(owner.begin(), owner.end(), -1);
    for (std::int32_t q = p.color_offset[k]; q < p.color_offset[k + 1]; ++q) {
      EXPECT_LE(p.patch_offset[q + 1] - p.patch_offset[q], patch_size);
      for (std::int32_t i = p.patch_offset[q]; i < p.patch_offset[q + 1]; ++i)
        for (int a = 0; a < block.n_nodes_per_cell(); ++a) {
          std::int32_t& o = owner[static_cast<std::size_t>(block.cell(static_cast<std::size_t>(p.order[static_cast<std::size_t>(i)]))[a])];
          EXPECT_TRUE(o < 0 || o == q);
          o = q;
        }
    }
  }
}

}  // namespace
}  // namespace meshmorph

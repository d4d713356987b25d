// SPDX-License-Identifier: MIT
// EnergyAssembler's matrix-free Hessian (prepare_hessian, apply_hessian, hessian_blocks)
// against the assembled one.
#include <cstring>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "energy/energy_fixtures.h"
#include "meshmorph/energy/assembler.h"
#include "meshmorph/energy/coarse_space.h"
#include "meshmorph/energy/hessian_action.h"

namespace meshmorph {
namespace {

// Every cell type and order 1–3, 2 cells per side, interior nodes jittered by up to 0.1 of the
// node spacing; the TMOP shape metric of the dimension and the ideal target, with the boundary
// fixed or not; exact and projected Hessians.
template <int d>
void action_matches_assembly(ElementType type, int order, bool fix_boundary,
                             QuadratureFamily family = QuadratureFamily::Lobatto) {
  SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order) + (fix_boundary ? ", fixed boundary" : ""));
  const Mesh mesh = test::perturbed_mesh(type, order, 2, 5, 0.1);
  const Topology topology = build_topology(mesh);
  const TargetField<d> targets = build_targets<d>(mesh, mesh.x, TargetKind::Ideal, 0, family);
  const DofMap dofs = fix_boundary ? DofMap::fixing_boundary(mesh, topology) : DofMap::all_free(d, mesh.n_nodes());
  const std::unique_ptr<Metric<d>> metric = test::test_metric<d>(d == 2 ? "mu2" : "mu303");
  const EnergyAssembler<d> assembler(mesh, topology, targets, dofs);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  Eigen::VectorXd v(static_cast<Eigen::Index>(dofs.n_free()));
  for (Eigen::Index i = 0; i < v.size(); ++i) v[i] = u(rng);
  for (HessianMode mode : {HessianMode::Exact, HessianMode::Projected}) {
    Assembly a;
    AssemblyOptions o;
    o.hessian = mode;
    assembler.assemble(*metric, mesh.x, o, a);
    HessianAction<d> action;
    ASSERT_TRUE(assembler.prepare_hessian(*metric, mesh.x, mode, 0, action));
    EXPECT_EQ(action.sum_factorized(0), type == ElementType::Hexahedron);  // sum factorization there
    EXPECT_EQ(action.element_matrices(0), is_simplex(type));               // element matrices there
    Eigen::VectorXd y;
    assembler.apply_hessian(action, v, y);
    const Eigen::VectorXd expected = a.hessian * v;
    // K_q and the element matrices are stored in single precision (2⁻²⁴ ≈ 6e-8 per entry).
    EXPECT_LE((y - expected).norm(), 1e-6 * expected.norm());
    const Eigen::VectorXd diagonal = assembler.hessian_diagonal(action);
    EXPECT_LE((diagonal - Eigen::VectorXd(a.hessian.diagonal())).norm(), 1e-6 * diagonal.norm());
    // The node blocks: the assembled Hessian's d × d blocks of free DOFs.
    const std::vector<double> blocks = assembler.hessian_blocks(action);
    double block_error = 0.0;
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
      for (int k = 0; k < d; ++k)
        for (int l = 0; l < d; ++l) {
          const std::int32_t r = dofs.reduced(d * i + k), c = dofs.reduced(d * i + l);
          if (r >= 0 && c >= 0) block_error = std::max(block_error, std::abs(blocks[i * d * d + k + d * l] - a.hessian.coeff(r, c)));
        }
    EXPECT_LE(block_error, 1e-6 * diagonal.cwiseAbs().maxCoeff());
    // The coarse matrix is the Galerkin restriction Rᵀ H R, exactly symmetric; R's hats are a
    // partition of unity where no coarse DOF is dropped.
    const CoarseSpace<d> coarse(mesh, dofs, targets);
    ASSERT_GT(coarse.size(), 0);
    const Eigen::MatrixXd Ac(assembler.coarse_hessian(action, coarse));
    const Eigen::MatrixXd galerkin(Eigen::SparseMatrix<double>(coarse.R().transpose() * a.hessian * coarse.R()));
    EXPECT_LE((Ac - galerkin).norm(), 1e-6 * galerkin.norm());
    EXPECT_EQ((Ac - Ac.transpose()).norm(), 0.0);
    if (!fix_boundary) {
      std::set<std::int32_t> corners;
      for (std::size_t c = 0; c < mesh.cells[0].n_cells(); ++c)
        for (int corner = 0; corner < n_corners_of(type); ++corner) corners.insert(mesh.cells[0].cell(c)[corner]);
      EXPECT_EQ(coarse.size(), static_cast<Eigen::Index>(d * corners.size()));
      const Eigen::VectorXd sums = coarse.R() * Eigen::VectorXd::Ones(coarse.size());
      EXPECT_LE((sums - Eigen::VectorXd::Ones(sums.size())).cwiseAbs().maxCoeff(), 1e-14);
    }
    // Gathered node by node in cell order: the thread count does not change a bit.
    Eigen::VectorXd y1, y2;
    assembler.apply_hessian(action, v, y1, 1);
    assembler.apply_hessian(action, v, y2, 2);
    EXPECT_EQ(std::memcmp(y1.data(), y2.data(), sizeof(double) * static_cast<std::size_t>(y1.size())), 0);
  }
}

TEST(HessianAction, MatchesTheAssembledHessian) {
  for (int order : {1, 2, 3})
    for (bool fixed : {false, true}) {
      action_matches_assembly<2>(ElementType::Triangle, order, fixed);
      action_matches_assembly<2>(ElementType::Quadrilateral, order, fixed);
      action_matches_assembly<3>(ElementType::Tetrahedron, order, fixed);
      action_matches_assembly<3>(ElementType::Hexahedron, order, fixed);
    }
  // Gauss points: point counts the sum-factorized kernel is not compiled for.
  action_matches_assembly<3>(ElementType::Hexahedron, 2, true, QuadratureFamily::Gauss);
}

// The solver's hats: with nothing fixed they equal CoarseSpace's R and interpolate every
// linear function exactly (on an affine mesh); a fixed boundary drops whole vertices (every
// column block of d complete) and exactly those whose hats reach a fixed DOF.
template <int d>
void vertex_hats_span_linear_functions(ElementType type, int order) {
  SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order));
  const Mesh mesh = structured_mesh(type, order, 3);
  const Topology topology = build_topology(mesh);
  const TargetField<d> targets = build_targets<d>(mesh, mesh.x, TargetKind::Ideal);
  const DofMap free = DofMap::all_free(d, mesh.n_nodes());
  const Eigen::SparseMatrix<double> R = vertex_hats<d>(mesh, free);
  EXPECT_EQ((Eigen::MatrixXd(R) - Eigen::MatrixXd(CoarseSpace<d>(mesh, free, targets).R())).norm(), 0.0);
  // Each column's vertex: the node where its hat is 1.
  const auto vertices_of = [](const Eigen::SparseMatrix<double>& M, const DofMap& dofs) {
    std::vector<std::int32_t> v(static_cast<std::size_t>(M.cols()), -1);
    for (Eigen::Index j = 0; j < M.outerSize(); ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(M, j); it; ++it)
        if (std::abs(it.value() - 1.0) < 1e-14) v[static_cast<std::size_t>(j)] = dofs.free_dofs()[static_cast<std::size_t>(it.row())] / d;
    return v;
  };
  const std::vector<std::int32_t> vertex = vertices_of(R, free);
  // f(x) = A x + c component by component, at the vertices (coarse) and at every node (fine).
  Eigen::MatrixXd A(d, d);
  A.setRandom();
  const Eigen::VectorXd c = Eigen::VectorXd::LinSpaced(d, 0.5, 1.5);
  Eigen::VectorXd coarse(R.cols()), fine(R.rows());
  for (Eigen::Index j = 0; j < R.cols(); ++j) {
    ASSERT_GE(vertex[static_cast<std::size_t>(j)], 0);
    coarse[j] = (A * mesh.x.col(vertex[static_cast<std::size_t>(j)]) + c)[j % d];
  }
  for (Eigen::Index i = 0; i < R.rows(); ++i) fine[i] = (A * mesh.x.col(i / d) + c)[i % d];
  EXPECT_LE((R * coarse - fine).cwiseAbs().maxCoeff(), 1e-12);

  const DofMap fixed = DofMap::fixing_boundary(mesh, topology);
  const Eigen::SparseMatrix<double> Rb = vertex_hats<d>(mesh, fixed);
  ASSERT_GT(Rb.cols(), 0);
  EXPECT_EQ(Rb.cols() % d, 0);
  EXPECT_EQ(Rb.rows(), static_cast<Eigen::Index>(fixed.n_free()));
  // A vertex is kept, with its d components in a row, exactly when its hat (the all-free
  // column) is zero at every fixed DOF; the kept columns are the all-free ones restricted.
  std::set<std::int32_t> kept;
  const std::vector<std::int32_t> kept_vertex = vertices_of(Rb, fixed);
  for (Eigen::Index j = 0; j < Rb.cols(); ++j) {
    EXPECT_EQ(kept_vertex[static_cast<std::size_t>(j)], kept_vertex[static_cast<std::size_t>(j - j % d)]);
    kept.insert(kept_vertex[static_cast<std::size_t>(j)]);
  }
  EXPECT_EQ(static_cast<Eigen::Index>(kept.size() * d), Rb.cols());
  Eigen::Index next = 0;
  bool touches_fixed = false;
  for (Eigen::Index j = 0; j < R.cols(); ++j) {
    if (j % d == 0) touches_fixed = false;
    for (Eigen::SparseMatrix<double>::InnerIterator it(R, j); it; ++it)
      touches_fixed = touches_fixed || !fixed.is_free(static_cast<std::size_t>(it.row()));
    const bool is_kept = kept.count(vertex[static_cast<std::size_t>(j)]) > 0;
    if (j % d == d - 1) {
      EXPECT_EQ(is_kept, !touches_fixed) << "vertex " << vertex[static_cast<std::size_t>(j)];
    }
    if (!is_kept) continue;
    for (Eigen::SparseMatrix<double>::InnerIterator it(R, j); it; ++it)
      if (const std::int32_t row = fixed.reduced(static_cast<std::size_t>(it.row())); row >= 0) {
        EXPECT_EQ(Rb.coeff(row, next), it.value());
      }
    ++next;
  }
  EXPECT_EQ(next, Rb.cols());
  // Only the first component fixed on the boundary: the vertices next to it are still
  // dropped whole, so the columns still come in complete blocks of d.
  std::vector<std::uint8_t> mask(static_cast<std::size_t>(d) * mesh.n_nodes(), 0);
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) mask[d * i] = fixed.is_free(d * i) ? 0 : 1;
  const DofMap partial = DofMap::from_mask(d, mask);
  const Eigen::SparseMatrix<double> Rp = vertex_hats<d>(mesh, partial);
  EXPECT_EQ(Rp.cols(), Rb.cols());
  const std::vector<std::int32_t> partial_vertex = vertices_of(Rp, partial);
  for (Eigen::Index j = 0; j < Rp.cols(); ++j)
    EXPECT_EQ(partial_vertex[static_cast<std::size_t>(j)], kept_vertex[static_cast<std::size_t>(j)]);
}

TEST(VertexHats, SpanLinearFunctionsAndDropWholeVertices) {
  for (int order : {1, 2, 3}) {
    vertex_hats_span_linear_functions<2>(ElementType::Triangle, order);
    vertex_hats_span_linear_functions<2>(ElementType::Quadrilateral, order);
    vertex_hats_span_linear_functions<3>(ElementType::Tetrahedron, order);
    vertex_hats_span_linear_functions<3>(ElementType::Hexahedron, order);
  }
}

// An inverted cell: no action, as assemble() gives F = +∞.
TEST(HessianAction, RefusesAnInvertedMesh) {
  const Mesh mesh = test::perturbed_mesh(ElementType::Quadrilateral, 2, 2, 5);
  const Topology topology = build_topology(mesh);
  const TargetField<2> targets = build_targets<2>(mesh, mesh.x, TargetKind::Ideal);
  const DofMap dofs = DofMap::all_free(2, mesh.n_nodes());
  const EnergyAssembler<2> assembler(mesh, topology, targets, dofs);
  Eigen::MatrixXd x = mesh.x;
  const std::int32_t* cell = mesh.cells[0].cell(0);
  x.col(cell[0]) = x.col(cell[1]) + 1.5 * (x.col(cell[1]) - x.col(cell[0]));  // corner 0 through corner 1
  HessianAction<2> action;
  EXPECT_FALSE(assembler.prepare_hessian(*test::test_metric<2>("mu2"), x, HessianMode::Projected, 0, action));
}

}  // namespace
}  // namespace meshmorph

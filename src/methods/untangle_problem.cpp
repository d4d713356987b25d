// SPDX-License-Identifier: MIT
#include "methods/detail/untangle_problem.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <string>

#include <Eigen/LU>

#include "meshmorph/error.h"
#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/threads.h"

namespace meshmorph {
namespace {

template <int d>
Eigen::Matrix<double, d, Eigen::Dynamic> gather(const Eigen::MatrixXd& x, const std::int32_t* nodes, int n) {
  Eigen::Matrix<double, d, Eigen::Dynamic> X(d, n);
  for (int a = 0; a < n; ++a) X.col(a) = x.col(nodes[a]);
  return X;
}

}  // namespace

template <int d>
UntangleProblem<d>::UntangleProblem(const Mesh& input, const Topology& topology, const BoundaryTargets& bc,
                                    UntangleReference reference, double n, int threads,
                                    const std::vector<FitTerm>& surfaces)
    : input_(&input), mesh_(&input), input_topology_(&topology), topology_(&topology), bc_(&bc), reference_(reference), threads_(threads), n_(n),
      metric_({0.0, n}) {
  // The regular reference has one size for the whole mesh, the input's mean cell volume, so
  // that δ compares with volumes of the mesh's own scale (the paper's h(V) up to a constant).
  double volume_sum = 0.0;
  for (const CellBlock& block : input.cells) {
    const ShapeTable& table = shape_table(block.type, block.order, metric_quadrature_degree(block.type, block.order));
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const auto X = gather<d>(input.x, block.cell(c), block.n_nodes_per_cell());
      for (int q = 0; q < table.n_points(); ++q) volume_sum += table.weights[q] * std::abs((X * table.grad(q)).determinant());
    }
    n_cells_ += block.n_cells();
  }
  if (reference == UntangleReference::Regular && !(volume_sum > 0.0))
    throw InputError("untangle: every cell of the input mesh has zero volume");
  mean_volume_ = volume_sum / static_cast<double>(std::max<std::size_t>(n_cells_, 1));

  // Unknowns: every DOF of the free, slide and surface nodes; SlideConstraints holds the
  // slide nodes on their planes, one level set per distinct plane (normal and offset), and the
  // surface nodes on their level sets.
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(d) * input.n_nodes(), 0), wide(fixed.size(), 0);
  std::map<std::array<double, d + 1>, std::size_t> plane_of;
  std::vector<FitTerm> slides = surfaces;
  std::vector<std::uint8_t> on_surface(input.n_nodes(), 0);
  for (const FitTerm& t : surfaces)
    for (std::int32_t node : t.nodes) on_surface[static_cast<std::size_t>(node)] = 1;
  for (std::size_t i = 0; i < input.n_nodes(); ++i) {
    const bool orphan = topology.node_cell_offset[i + 1] == topology.node_cell_offset[i];
    const NodeRole role = on_surface[i] ? NodeRole::Free : bc.role[i];
    for (int k = 0; k < d; ++k) {
      const std::size_t dof = static_cast<std::size_t>(d) * i + static_cast<std::size_t>(k);
      fixed[dof] = orphan || role == NodeRole::Fixed || role == NodeRole::Prescribed;
      wide[dof] = orphan || role == NodeRole::Fixed;
    }
    if (orphan || role != NodeRole::Slide) continue;
    const auto col = static_cast<Eigen::Index>(i);
    const Eigen::VectorXd normal = bc.normal.col(col), point = bc.target.col(col);
    std::array<double, d + 1> key{};
    for (int k = 0; k < d; ++k) key[static_cast<std::size_t>(k)] = normal[k];
    key[d] = normal.dot(point);
    const auto [at, added] = plane_of.try_emplace(key, slides.size());
    if (added) slides.push_back({LevelSetFunction(LevelSet{PlaneLevelSet{point, normal}, "slide plane"}, d), {}});
    slides[at->second].nodes.push_back(static_cast<std::int32_t>(i));
  }
  dofs_ = DofMap::from_mask(d, fixed);
  wide_dofs_ = DofMap::from_mask(d, wide);
  slides_ = SlideConstraints<d>(slides, dofs_);
  component_.resize(dofs_.n_free());
  for (std::size_t j = 0; j < dofs_.n_free(); ++j) component_[j] = dofs_.free_dofs()[j] % d;
  x_ = input.x;
  build();
}

template <int d>
void UntangleProblem<d>::build() {
  corner_tables_.clear();
  targets_.kind = reference_ == UntangleReference::Regular ? TargetKind::Ideal : TargetKind::Input;
  targets_.blocks.assign(mesh_->cells.size(), {});
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    // Linear simplices: their one point. Linear quadrilaterals: the corners, whose Jacobians
    // are the corner triangles' (eq. 5), and det A is smallest at a corner. Hexahedra and
    // curved cells: the points of the validity test, so that the functional sees every
    // inversion that test sees.
    const ShapeTable* table = nullptr;
    if (bi < fold_tables_.size() && fold_tables_[bi]) {
      table = fold_tables_[bi].get();
    } else if (block.order == 1 && block.type == ElementType::Quadrilateral) {
      corner_tables_.push_back(std::make_unique<ShapeTable>(tabulate(block.type, 1, reference_element(block.type, 1).nodes)));
      table = corner_tables_.back().get();
    } else if (block.order == 1 && is_simplex(block.type)) {
      table = &shape_table(block.type, 1, metric_quadrature_degree(block.type, 1));
    } else {
      table = &validity_samples(block.type, block.order);
    }
    BlockTargets<d>& bt = targets_.blocks[bi];
    bt.table = table;
    const int Q = table->n_points();
    // F_e is the mean over the points (quadrature weights normalized; corners alike).
    Eigen::VectorXd w = table->weights.size() == Q ? table->weights : Eigen::VectorXd::Ones(Q);
    w /= w.sum();
    bt.points.resize(block.n_cells() * static_cast<std::size_t>(Q));
    const MatT<d> W_ideal_inv = ideal_jacobian<d>(block.type, mean_volume_ > 0.0 ? mean_volume_ : 1.0).inverse();
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const auto X = gather<d>(mesh_->x, block.cell(c), block.n_nodes_per_cell());
      // InputWhereValid: the cells valid by the Bernstein bounds (a fold between the points
      // would otherwise keep its input shape as target).
      const bool regular = reference_ == UntangleReference::Regular ||
                           (reference_ == UntangleReference::InputWhereValid &&
                            !(min_jacobian_det(block.type, block.order, X) > 0.0));
      for (int q = 0; q < Q; ++q) {
        QuadratureTarget<d>& t = bt.points[c * static_cast<std::size_t>(Q) + static_cast<std::size_t>(q)];
        t.weight = w[q];
        if (regular) {
          t.W_inv = W_ideal_inv;
          continue;
        }
        const MatT<d> A = X * table->grad(q);
        if (!(A.determinant() > 0.0))
          throw InputError("untangle: cell " + std::to_string(c) + " of cell block " + std::to_string(bi) +
                           " of the input mesh is inverted or degenerate, so it cannot be the reference element"
                           " (\"reference\": \"regular\" untangles such a mesh)");
        t.W_inv = A.inverse();
      }
    }
  }

  assembler_ = std::make_unique<EnergyAssembler<d>>(*mesh_, *topology_, targets_, dofs_);
  wide_assembler_.reset();
  all_fixed_.clear();
  for (const CellBlock& block : mesh_->cells)
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      bool none = true;
      for (int a = 0; a < block.n_nodes_per_cell(); ++a) none = none && dofs_.first(block.cell(c)[a]) == dofs_.first(block.cell(c)[a] + 1);
      all_fixed_.push_back(none);
    }
}

template <int d>
std::size_t UntangleProblem<d>::sample_folds(bool add) {
  // The cells valid at every point whose Bernstein bounds still find det A ≤ 0 (in parallel:
  // the bounds cost a few lattices a cell), then the lattices of their folds, in cell order.
  std::vector<std::pair<std::size_t, std::size_t>> cells;  // (block, cell) of the layout
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi)
    for (std::size_t c = 0; c < mesh_->cells[bi].n_cells(); ++c) cells.emplace_back(bi, c);
  std::vector<std::uint8_t> folded(cells.size(), 0);
  const auto n_cells = static_cast<std::ptrdiff_t>(cells.size());
#pragma omp parallel for num_threads(resolve_threads(threads_)) schedule(dynamic, 64)
  for (std::ptrdiff_t k = 0; k < n_cells; ++k) {
    const CellBlock& block = mesh_->cells[cells[static_cast<std::size_t>(k)].first];
    const std::size_t c = cells[static_cast<std::size_t>(k)].second;
    folded[static_cast<std::size_t>(k)] =
        !(min_jacobian_det(block.type, block.order, gather<d>(x_, block.cell(c), block.n_nodes_per_cell())) > 0.0);
  }
  if (!add) return static_cast<std::size_t>(std::count(folded.begin(), folded.end(), 1));
  std::size_t found = 0;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    if (!folded[k]) continue;
    const auto [bi, c] = cells[k];
    const CellBlock& block = mesh_->cells[bi];
    const Eigen::MatrixXd points = fold_samples(block.type, block.order, gather<d>(x_, block.cell(c), block.n_nodes_per_cell()));
    if (points.cols() == 0) continue;
    const std::int32_t cell = cell_of_.empty() ? static_cast<std::int32_t>(k) : cell_of_[k];
    Eigen::MatrixXd& extra = fold_points_[cell];
    extra.conservativeResize(d, extra.cols() + points.cols());
    extra.rightCols(points.cols()) = points;
    ++found;
  }
  if (found == 0) return 0;
  // The layout: the input's blocks without the cells sampled at their folds, then each of
  // those as a block of its own, its table the validity samples and the folds' points.
  layout_ = *input_;
  std::vector<std::uint8_t> apart(n_cells_, 0);
  for (const auto& [cell, points] : fold_points_) apart[static_cast<std::size_t>(cell)] = 1;
  cell_of_.clear();
  fold_tables_.clear();
  std::size_t cell = 0;
  for (CellBlock& block : layout_.cells) {
    CellBlock kept{block.type, block.order, {}, {}, {}};
    for (std::size_t c = 0; c < block.n_cells(); ++c, ++cell)
      if (!apart[cell]) {
        kept.push_back(block.cell(c), 0);
        cell_of_.push_back(static_cast<std::int32_t>(cell));
      }
    block = std::move(kept);
  }
  std::erase_if(layout_.cells, [](const CellBlock& block) { return block.nodes.empty(); });
  fold_tables_.resize(layout_.cells.size());
  for (const auto& [global, points] : fold_points_) {
    const auto [b, c] = input_topology_->locate(global);
    const CellBlock& source = input_->cells[b];
    CellBlock own{source.type, source.order, {}, {}, {}};
    own.push_back(source.cell(c), 0);
    layout_.cells.push_back(std::move(own));
    const ShapeTable& samples = validity_samples(source.type, source.order);
    Eigen::MatrixXd all(d, samples.n_points() + points.cols());
    all << samples.points, points;
    fold_tables_.push_back(std::make_unique<ShapeTable>(tabulate(source.type, source.order, all)));
    cell_of_.push_back(global);
  }
  layout_topology_ = build_topology(layout_);
  mesh_ = &layout_;
  topology_ = &layout_topology_;
  build();
  return found;
}

template <int d>
void UntangleProblem<d>::scale_off_diagonal(Assembly& out) const {
  // γ relaxes the couplings between different coordinates (paper 001 §4): a convex
  // combination of the Hessian and its coordinate-block diagonal, so PSD stays PSD.
  if (gamma_ == 1.0) return;
  Eigen::SparseMatrix<double>& H = out.hessian;
  for (Eigen::Index j = 0; j < H.outerSize(); ++j)
    for (Eigen::SparseMatrix<double>::InnerIterator it(H, j); it; ++it)
      if (component_[static_cast<std::size_t>(it.row())] != component_[static_cast<std::size_t>(j)]) it.valueRef() *= gamma_;
}

template <int d>
void UntangleProblem<d>::set_state(const Eigen::MatrixXd& x) {
  x_ = x;
  if (!slides_.empty()) slides_.project(x_, threads_);
}

template <int d>
void UntangleProblem<d>::evaluate(HessianMode mode, Assembly& out) {
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = mode;
  o.threads = threads_;
  assembler_->assemble(metric_, x_, o, out);
  if (!std::isfinite(out.value)) return;
  // γ first: the frames' P H P + c N Nᵀ keeps a slide node's normal step exactly 0.
  scale_off_diagonal(out);
  if (!slides_.empty()) slides_.constrain(x_, mode, out, threads_);
}

template <int d>
double UntangleProblem<d>::trial_value(const Eigen::VectorXd& p, double alpha) {
  trial_ = x_;
  dofs_.add_step(p, alpha, trial_);
  if (!slides_.empty() && !slides_.project(trial_, threads_)) return std::numeric_limits<double>::infinity();
  const double value = assembler_->value(metric_, trial_, {}, threads_);
  return !std::isfinite(value) || !certify_ || bounds_valid(trial_) ? value : std::numeric_limits<double>::infinity();
}

template <int d>
bool UntangleProblem<d>::bounds_valid(const Eigen::MatrixXd& x) const {
  bool valid = true;
  for (const CellBlock& block : mesh_->cells) {
    // det A of a linear simplex is its one point's; of a linear quadrilateral, least at a corner.
    if (block.order == 1 && (is_simplex(block.type) || block.type == ElementType::Quadrilateral)) continue;
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
#pragma omp parallel for num_threads(resolve_threads(threads_)) reduction(&& : valid) schedule(dynamic, 64)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c)
      valid = valid && min_jacobian_det(block.type, block.order,
                                        gather<d>(x, block.cell(static_cast<std::size_t>(c)), block.n_nodes_per_cell())) > 0.0;
  }
  return valid;
}

template <int d>
void UntangleProblem<d>::accept(const Eigen::VectorXd& p, double alpha) {
  dofs_.add_step(p, alpha, x_);
  if (!slides_.empty()) slides_.project(x_, threads_);
  last_step_ = alpha * p;
}

template <int d>
typename UntangleProblem<d>::Measures UntangleProblem<d>::measure() const {
  const EdgeQuality<d> plain({0.0, n_});
  double v_min = std::numeric_limits<double>::infinity(), q_min = 1.0;
  std::size_t inverted = 0;
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const BlockTargets<d>& bt = targets_.blocks[bi];
    const ShapeTable& table = *bt.table;
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    const int n = block.n_nodes_per_cell();
#pragma omp parallel for num_threads(resolve_threads(threads_)) reduction(min : v_min, q_min) reduction(+ : inverted) schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      const auto X = gather<d>(x_, block.cell(static_cast<std::size_t>(c)), n);
      bool bad = false;
      for (int q = 0; q < table.n_points(); ++q) {
        const MatT<d> T = X * table.grad(q) * bt.cell(static_cast<std::size_t>(c))[q].W_inv;
        const double V = EdgeQuality<d>::volume(T);
        v_min = std::min(v_min, V);
        const double F = plain.eval(T, Want::Value).mu;
        q_min = std::min(q_min, std::isfinite(F) ? std::pow(F, 1.0 / n_) : 0.0);
        bad = bad || !(V > 0.0);
      }
      inverted += bad ? 1 : 0;
    }
  }
  return {v_min, q_min, inverted};
}

template <int d>
std::size_t UntangleProblem<d>::stuck_inverted() const {
  std::size_t count = 0, cell = 0;
  for (const CellBlock& block : mesh_->cells)
    for (std::size_t c = 0; c < block.n_cells(); ++c, ++cell)
      if (all_fixed_[cell] && !(min_jacobian_det(block.type, block.order, gather<d>(x_, block.cell(c), block.n_nodes_per_cell())) > 0.0))
        ++count;
  return count;
}

template <int d>
double UntangleProblem<d>::delta_increment(const Eigen::VectorXd& dx) const {
  Eigen::MatrixXd dX = Eigen::MatrixXd::Zero(d, x_.cols());
  if (dx.size() > 0) dofs_.add_step(dx, 1.0, dX);
  // A serial sum: the same δ for every thread count.
  double F_d = 0.0, F_dd = 0.0, F_dx = 0.0;
  for (std::size_t bi = 0; bi < mesh_->cells.size(); ++bi) {
    const CellBlock& block = mesh_->cells[bi];
    const BlockTargets<d>& bt = targets_.blocks[bi];
    const ShapeTable& table = *bt.table;
    const int n = block.n_nodes_per_cell();
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const auto X = gather<d>(x_, block.cell(c), n);
      const auto dXc = gather<d>(dX, block.cell(c), n);
      for (int q = 0; q < table.n_points(); ++q) {
        const QuadratureTarget<d>& t = bt.cell(c)[q];
        const Eigen::Matrix<double, Eigen::Dynamic, d> B = table.grad(q) * t.W_inv;
        const auto D = metric_.delta_derivatives(X * B, dXc * B);
        F_d += t.weight * D.d_delta;
        F_dd += t.weight * D.d2_delta;
        F_dx += t.weight * D.d2_delta_dT;
      }
    }
  }
  // Without positive curvature in δ the Newton estimate means nothing: the caller's β bound
  // then decides alone.
  if (!(F_dd > 0.0) || !std::isfinite(F_d + F_dx)) return std::numeric_limits<double>::infinity();
  return -(F_d + F_dx) / F_dd;
}

template <int d>
bool UntangleProblem<d>::predict(const Eigen::MatrixXd& target, LinearSolver& solver, Eigen::MatrixXd& increment) {
  if (dofs_.n_free() == 0) return false;
  if (!wide_assembler_) wide_assembler_ = std::make_unique<EnergyAssembler<d>>(*mesh_, *topology_, targets_, wide_dofs_);
  // K_ib Δx_b: the Hessian over the free and the prescribed DOFs times the boundary motion.
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = HessianMode::Exact;
  o.threads = threads_;
  Assembly wide;
  wide_assembler_->assemble(metric_, x_, o, wide);
  if (!std::isfinite(wide.value)) return false;
  Eigen::VectorXd motion = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(wide_dofs_.n_free()));
  for (std::size_t i = 0; i < bc_->n_nodes(); ++i) {
    if (bc_->role[i] != NodeRole::Prescribed) continue;
    for (int k = 0; k < d; ++k) {
      const std::int32_t w = wide_dofs_.reduced(static_cast<std::size_t>(d) * i + static_cast<std::size_t>(k));
      if (w >= 0) motion[w] = target(k, static_cast<Eigen::Index>(i)) - x_(k, static_cast<Eigen::Index>(i));
    }
  }
  const Eigen::VectorXd coupling = wide.hessian * motion;
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(dofs_.n_free()));
  for (std::size_t j = 0; j < dofs_.n_free(); ++j) rhs[static_cast<Eigen::Index>(j)] = -coupling[wide_dofs_.reduced(static_cast<std::size_t>(dofs_.free_dofs()[j]))];
  // K_ii: the exact Hessian, or its SPD projection where the exact one is not positive
  // definite; at slide nodes in their frames, with the tangential part of the right side, so
  // that they move along their planes.
  Assembly a;
  o.want = Want::Hessian;
  auto assemble = [&] {
    assembler_->assemble(metric_, x_, o, a);
    if (!slides_.empty()) slides_.constrain(x_, o.hessian, a, threads_);
  };
  assemble();
  if (!solver.factorize(a.hessian)) {
    o.hessian = HessianMode::Projected;
    assemble();
    if (!solver.factorize(a.hessian)) return false;
  }
  for (std::int32_t node : slides_.nodes()) {
    const std::int32_t first = dofs_.first(static_cast<std::size_t>(node));
    auto r = rhs.segment<d>(first);
    r = slides_.frame_of_row(first)->P * r;
  }
  Eigen::VectorXd dx;
  if (!solver.solve(rhs, dx).ok) return false;
  increment = Eigen::MatrixXd::Zero(d, x_.cols());
  dofs_.add_step(dx, 1.0, increment);
  return true;
}

template class UntangleProblem<2>;
template class UntangleProblem<3>;

}  // namespace meshmorph

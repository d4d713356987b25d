// SPDX-License-Identifier: MIT
#include "methods/detail/fit_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "meshmorph/energy/metric_summary.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/quality/metric_registry.h"
#include "meshmorph/threads.h"

namespace meshmorph {

template <int d>
FitProblem<d>::FitProblem(const Mesh& mesh, const Topology& topology, const std::vector<FitTerm>& terms,
                          const std::vector<std::uint8_t>& fixed, const FitOptions& options, const Eigen::MatrixXd& x,
                          const std::vector<FitTerm>& slides, bool matrix_free)
    : mesh_(&mesh), options_(options), penalty_(terms, dofs_), x_(x) {
  targets_ = build_targets<d>(mesh, x, options.target, options.quadrature_degree, options.quadrature);
  dofs_ = DofMap::from_mask(d, fixed);
  slides_ = SlideConstraints<d>(slides, dofs_);
  MESHMORPH_CHECK(slides_.project(x_, options_.threads), "FitProblem: a slide node cannot be projected onto its surface");
  assembler_ = std::make_unique<EnergyAssembler<d>>(mesh, topology, targets_, dofs_, !matrix_free);
  // Not with sliding nodes: with the coarse level the P2 sphere sliding on its own facets
  // (OptimizeSlide) stalled at |∇F| = 1.2e-8 |∇F₀|, its line search finding no step, where
  // block Jacobi alone converges.
  if (matrix_free && slides_.empty()) {
    coarse_ = std::make_unique<CoarseSpace<d>>(mesh, dofs_, targets_);
    if (coarse_->size() == 0) coarse_.reset();
  }
  metric_ = make_metric<d>(options.metric.empty() ? default_shape_metric(d) : options.metric);
  if (options.flat_edges) flat_ = flat_edges(mesh, penalty_.fitted(mesh.n_nodes()));
  min_det0_ = min_det(x);
}

template <int d>
double FitProblem<d>::cell_min_det(std::size_t b, std::size_t c, const Eigen::MatrixXd& x, bool all) const {
  const CellBlock& block = mesh_->cells[b];
  const int n = block.n_nodes_per_cell();
  Eigen::MatrixXd X(d, n);
  for (int a = 0; a < n; ++a) X.col(a) = x.col(block.nodes[c * n + a]);
  const std::int32_t k = flat_.mask_of_cell.empty() || all ? -1 : flat_.mask_of_cell[b][c];
  return k < 0 ? min_jacobian_det(block.type, block.order, X)
               : min_jacobian_det(block.type, block.order, X, flat_.masks[static_cast<std::size_t>(k)]);
}

template <int d>
double FitProblem<d>::min_det(const Eigen::MatrixXd& x) const {
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < mesh_->cells.size(); ++b) {
    const auto n_cells = static_cast<std::ptrdiff_t>(mesh_->cells[b].n_cells());
#pragma omp parallel for num_threads(resolve_threads(options_.threads)) reduction(min : m) schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) m = std::min(m, cell_min_det(b, static_cast<std::size_t>(c), x, false));
  }
  return m;
}

template <int d>
std::array<std::size_t, 2> FitProblem<d>::invalid_cells(const Eigen::MatrixXd& x) const {
  std::size_t inverted = 0, flat = 0;
  for (std::size_t b = 0; b < mesh_->cells.size(); ++b)
    for (std::size_t c = 0; c < mesh_->cells[b].n_cells(); ++c) {
      if (!(cell_min_det(b, c, x, false) > 0.0)) ++inverted;
      else if (!(cell_min_det(b, c, x, true) > 0.0)) ++flat;
    }
  return {inverted, flat};
}

template <int d>
double FitProblem<d>::target_measure() const {
  double v = 0.0;
  for (const BlockTargets<d>& b : targets_.blocks)
    for (const QuadratureTarget<d>& t : b.points) v += t.weight;
  return v;
}

template <int d>
std::array<double, 3> FitProblem<d>::metric_range() const {
  const MetricSummary s = metric_summary(*mesh_, targets_, *metric_, x_, options_.threads);
  return {s.min, s.mean(), s.max};
}

template <int d>
bool FitProblem<d>::step_to(const Eigen::VectorXd& p, double alpha, Eigen::MatrixXd& out) const {
  out = x_;
  dofs_.add_step(p, alpha, out);
  return slides_.empty() || slides_.project(out, options_.threads);
}

template <int d>
double FitProblem<d>::metric_stiffness() {
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = HessianMode::Projected;
  o.threads = options_.threads;
  Assembly a;
  assembler_->assemble(*metric_, x_, o, a);
  return penalty_.mean_at_nodes(a.hessian.diagonal());
}

template <int d>
void FitProblem<d>::evaluate(HessianMode mode, Assembly& out) {
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = mode;
  o.threads = options_.threads;
  assembler_->assemble(*metric_, x_, o, out);
  if (!std::isfinite(out.value)) return;
  penalty_.add_to(x_, Want::Hessian, mode, out);
  if (!slides_.empty()) slides_.constrain(x_, mode, out, options_.threads);
}

template <int d>
void FitProblem<d>::evaluate_action(HessianMode mode, Assembly& out) {
  MESHMORPH_CHECK(penalty_.terms().empty(), "FitProblem: the matrix-free Hessian has no fitted nodes");
  if (metric_at_current_.gradient.size() != static_cast<Eigen::Index>(dofs_.n_free())) remember_current();
  out.value = metric_at_current_.value;  // F and ∇F as remember_current() or accept() measured them
  out.gradient = metric_at_current_.gradient;
  out.element_values = metric_at_current_.element_values;
  if (std::isfinite(out.value) && !assembler_->prepare_hessian(*metric_, x_, mode, options_.threads, action_))
    out.value = std::numeric_limits<double>::infinity();
  if (!std::isfinite(out.value)) return;
  node_blocks_ = assembler_->hessian_blocks(action_, options_.threads);
  if (!slides_.empty()) slides_.constrain(x_, node_blocks_, mode, out.gradient);
}

template <int d>
void FitProblem<d>::apply_hessian(const Eigen::VectorXd& v, Eigen::VectorXd& y) {
  if (slides_.empty()) {
    assembler_->apply_hessian(action_, v, y, options_.threads);
    return;
  }
  slides_.tangential(v, slide_v_);
  assembler_->apply_hessian(action_, slide_v_, y, options_.threads);
  slides_.finish_action(v, y);
}

template <int d>
HessianBlocks FitProblem<d>::hessian_blocks() {
  HessianBlocks b;
  b.size = d;
  const std::int32_t* red = dofs_.reduced_index().data();
  for (std::size_t i = 0; i < mesh_->n_nodes(); ++i) {
    int free[d], m = 0;
    for (int k = 0; k < d; ++k)
      if (red[d * i + k] >= 0) free[m++] = k;
    if (m == 0) continue;
    b.first.push_back(red[d * i + free[0]]);
    Eigen::Matrix<double, d, d> B = Eigen::Map<const Eigen::Matrix<double, d, d>>(node_blocks_.data() + i * d * d);
    // A slide node has all its DOFs free: its first one finds its slot.
    if (const auto* f = m == d ? slides_.frame_of_row(b.first.back()) : nullptr) B = f->P * B * f->P + f->add;
    const std::size_t at = b.values.size();
    b.values.resize(at + d * d, 0.0);
    for (int l = 0; l < m; ++l)
      for (int r = 0; r < m; ++r) b.values[at + static_cast<std::size_t>(r + d * l)] = B(free[r], free[l]);
  }
  b.first.push_back(static_cast<std::int32_t>(dofs_.n_free()));
  return b;
}

template <int d>
bool FitProblem<d>::coarse_hessian(CoarseHessian& out) {
  if (!coarse_) return false;
  out.R = &coarse_->R();
  out.A = assembler_->coarse_hessian(action_, *coarse_, options_.threads);
  return true;
}

template <int d>
double FitProblem<d>::gradient_norm(const Eigen::MatrixXd& x, Assembly& metric) {
  AssemblyOptions o;
  o.want = Want::Gradient;
  o.threads = options_.threads;
  assembler_->assemble(*metric_, x, o, metric);
  Assembly a = metric;
  penalty_.add_to(x, Want::Gradient, HessianMode::Projected, a);
  const double on_one = slides_.tangential_gradient(x, a.gradient);
  return std::sqrt(a.gradient.squaredNorm() + on_one);
}

template <int d>
void FitProblem<d>::remember_current() {
  gradient_norm_ = gradient_norm(x_, metric_at_current_);
  error_ = fit_error(x_);
}

template <int d>
double FitProblem<d>::trial_value(const Eigen::VectorXd& p, double alpha) {
  admitted_ = {};
  if (!step_to(p, alpha, trial_)) return std::numeric_limits<double>::infinity();
  const double v = assembler_->value(*metric_, trial_, {}, options_.threads);
  admitted_.alpha = alpha;
  admitted_.energy = std::isfinite(v) ? v + penalty_.value(trial_) : v;
  return admitted_.energy;
}

template <int d>
bool FitProblem<d>::admissible(const Eigen::VectorXd& p, double alpha) {
  Measured m = admitted_.alpha == alpha ? admitted_ : Measured{};  // F from trial_value() at this point
  admitted_ = {};
  if (!step_to(p, alpha, trial_)) return false;
  m.min_det = min_det(trial_);
  if (!(m.min_det > std::max(0.0, options_.det_floor * min_det0_))) return false;  // det A > 0, eq. 15
  if (error_ > 0.0 && !(fit_error(trial_) < options_.growth * error_)) return false;  // eq. 14
  m.gradient_norm = gradient_norm(trial_, metric_at_trial_);
  if (!(m.gradient_norm < options_.growth * gradient_norm_)) return false;  // §2.2
  if (m.alpha != alpha) m = {alpha, assembler_->value(*metric_, trial_, {}, options_.threads) + penalty_.value(trial_), m.min_det, m.gradient_norm};
  m.admitted = true;
  admitted_ = m;
  return true;
}

template <int d>
void FitProblem<d>::accept(const Eigen::VectorXd& p, double alpha) {
  // newton() accepts the point that admissible() passed last: trial_ holds it, measured.
  if (!(admitted_.admitted && admitted_.alpha == alpha)) {
    step_to(p, alpha, trial_);
    admitted_ = {alpha, assembler_->value(*metric_, trial_, {}, options_.threads) + penalty_.value(trial_), min_det(trial_),
                 gradient_norm(trial_, metric_at_trial_), true};
  }
  x_.swap(trial_);
  std::swap(metric_at_current_, metric_at_trial_);
  gradient_norm_ = admitted_.gradient_norm;
  error_ = fit_error(x_);
  current_ = admitted_;
  admitted_ = {};
}

template class FitProblem<2>;
template class FitProblem<3>;

}  // namespace meshmorph

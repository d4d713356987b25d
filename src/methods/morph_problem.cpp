// SPDX-License-Identifier: MIT
#include "methods/detail/morph_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <span>

#include "meshmorph/error.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/quality/metric_registry.h"
#include "meshmorph/threads.h"

namespace meshmorph {

template <int d>
MorphProblem<d>::MorphProblem(const Mesh& input, const Topology& topology, const BoundaryTargets& bc, int threads)
    : mesh_(&input), topology_(&topology), bc_(&bc), threads_(threads), guard_(input, dofs_) {
  targets_ = build_targets<d>(input, input.x, TargetKind::Input);
  std::vector<std::uint8_t> fixed(static_cast<std::size_t>(d) * input.n_nodes(), 0);
  std::vector<std::int32_t> constrained;
  std::vector<FitTerm> slides;  // a plane per slide node, through its own bc.target
  for (std::size_t i = 0; i < input.n_nodes(); ++i) {
    // Nodes in no cell (e.g. the centre points of Gmsh circle arcs) have no energy: not unknowns.
    const bool orphan = topology.node_cell_offset[i + 1] == topology.node_cell_offset[i];
    if (bc.role[i] == NodeRole::Fixed || orphan) std::fill_n(fixed.begin() + static_cast<std::ptrdiff_t>(d * i), d, std::uint8_t{1});
    if (orphan) continue;
    const auto node = static_cast<std::int32_t>(i);
    if (bc.role[i] == NodeRole::Prescribed) constrained.push_back(node);
    if (bc.role[i] == NodeRole::Slide)
      slides.push_back({LevelSetFunction(LevelSet{PlaneLevelSet{bc.target.col(node), bc.normal.col(node)}, "slide"}, d), {node}});
  }
  dofs_ = DofMap::from_mask(d, fixed);
  slides_ = SlideConstraints<d>(slides, dofs_);
  assembler_ = std::make_unique<EnergyAssembler<d>>(input, topology, targets_, dofs_);
  metric_ = make_metric<d>("distortion2");
  mass_ = boundary_mass(input, topology, input.x);
  penalty_ = std::make_unique<BoundaryPenalty<d>>(mass_, std::move(constrained));

  weights_.assign(input.n_cells(), 1.0);
  volumes_.reserve(input.n_cells());
  for (const BlockTargets<d>& block : targets_.blocks)
    for (std::size_t c = 0; c < block.points.size() / static_cast<std::size_t>(block.n_points()); ++c) {
      double v = 0.0;
      for (int q = 0; q < block.n_points(); ++q) v += block.cell(c)[q].weight;
      volumes_.push_back(v);
    }
  {
    std::vector<std::uint8_t> near(input.n_cells(), 0);
    for (std::int32_t node : penalty_->nodes())
      for (std::int32_t cell : topology.cells_of(static_cast<std::size_t>(node))) near[static_cast<std::size_t>(cell)] = 1;
    for (std::size_t e = 0; e < near.size(); ++e)
      if (near[e]) boundary_cells_.push_back(static_cast<std::uint32_t>(e));
  }
  weights_changed();
  for (const CellBlock& block : input.cells)
    if (block.order > 1 || !is_simplex(block.type)) dense_validity_ = true;
  length_scale_ = (input.x.rowwise().maxCoeff() - input.x.rowwise().minCoeff()).norm();
  set_state(input.x);
}

template <int d>
void MorphProblem<d>::set_state(const Eigen::MatrixXd& x) {
  x_ = x;
  MESHMORPH_CHECK(slides_.project(x_, threads_), "MorphProblem: a slide node cannot be projected onto its plane");
  ++version_;
}

template <int d>
bool MorphProblem<d>::step_to(const Eigen::VectorXd& p, double alpha, Eigen::MatrixXd& out) const {
  out = x_;
  dofs_.add_step(p, alpha, out);
  return slides_.empty() || slides_.project(out, threads_);
}

template <int d>
Eigen::MatrixXd MorphProblem<d>::gather_targets(const Eigen::MatrixXd& target) const {
  const std::vector<std::int32_t>& nodes = penalty_->nodes();
  Eigen::MatrixXd g(d, static_cast<Eigen::Index>(nodes.size()));
  for (std::size_t a = 0; a < nodes.size(); ++a) g.col(static_cast<Eigen::Index>(a)) = target.col(nodes[a]);
  return g;
}

template <int d>
void MorphProblem<d>::assemble(Want want, HessianMode mode, Assembly& out) {
  AssemblyOptions o;
  o.want = want;
  o.hessian = mode;
  o.weights = weights_;
  o.threads = threads_;
  assembler_->assemble(*metric_, x_, o, out);
  if (std::isfinite(out.value) && !guard_.empty()) guard_.add_to(*metric_, x_, weights_, want, mode, out);
  if (std::isfinite(out.value)) penalty_->add_to(*assembler_, x_, want, out);
}

template <int d>
void MorphProblem<d>::evaluate(HessianMode mode, Assembly& out) {
  assemble(Want::Hessian, mode, out);
  if (std::isfinite(out.value) && !slides_.empty()) slides_.constrain(x_, mode, out, threads_);
}

template <int d>
bool MorphProblem<d>::evaluate_gradient(Assembly& out) {
  // A slide node's frame comes from its Hessian block (energy/slide_constraints.h).
  if (!slides_.empty()) return false;
  assemble(Want::Gradient, HessianMode::Projected, out);
  return true;
}

template <int d>
double MorphProblem<d>::trial_value(const Eigen::VectorXd& p, double alpha) {
  if (!step_to(p, alpha, trial_)) return std::numeric_limits<double>::infinity();
  double v = assembler_->value(*metric_, trial_, weights_, threads_);
  if (std::isfinite(v) && !guard_.empty()) v += guard_.value(*metric_, trial_, weights_);
  return std::isfinite(v) ? v + penalty_->value(trial_) : v;
}

template <int d>
bool MorphProblem<d>::admissible(const Eigen::VectorXd& p, double alpha) {
  if (!dense_validity_) return true;  // linear simplices: a finite energy means det A > 0
  if (!step_to(p, alpha, trial_)) return false;
  bool valid = true;
  std::size_t first = 0;
  for (const CellBlock& block : mesh_->cells) {
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    const int n = block.n_nodes_per_cell();
#pragma omp parallel for num_threads(resolve_threads(threads_)) reduction(&& : valid) schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      Eigen::MatrixXd X(d, n);
      for (int a = 0; a < n; ++a) X.col(a) = trial_.col(block.nodes[static_cast<std::size_t>(c) * n + a]);
      if (min_jacobian_det(block.type, block.order, X) > 0.0) continue;
      valid = false;
#pragma omp critical(meshmorph_morph_blocking)
      blocking_.push_back(first + static_cast<std::size_t>(c));
    }
    first += block.n_cells();
  }
  return valid;
}

template <int d>
bool MorphProblem<d>::refine() {
  if (blocking_.empty()) return false;
  if (widen_guard_) {
    std::vector<std::uint8_t> mark(mesh_->n_cells(), 0);  // the cells of the blocking cells' nodes
    for (std::size_t c : blocking_) {
      const auto [block, local] = topology_->locate(static_cast<std::int32_t>(c));
      for (const std::int32_t node : std::span(mesh_->cells[block].cell(local), mesh_->cells[block].n_nodes_per_cell()))
        for (std::int32_t cell : topology_->cells_of(static_cast<std::size_t>(node))) mark[static_cast<std::size_t>(cell)] = 1;
    }
    blocking_.clear();
    for (std::size_t c = 0; c < mark.size(); ++c)
      if (mark[c]) blocking_.push_back(c);
  }
  std::sort(blocking_.begin(), blocking_.end());
  blocking_.erase(std::unique(blocking_.begin(), blocking_.end()), blocking_.end());
  const bool added = guard_.add(blocking_) > 0;
  blocking_.clear();
  return added;
}

template <int d>
void MorphProblem<d>::accept(const Eigen::VectorXd& p, double alpha) {
  dofs_.add_step(p, alpha, x_);
  // trial_value() returned this point: its slide nodes return.
  if (!slides_.empty()) slides_.project(x_, threads_);
  ++version_;
}

template <int d>
double MorphProblem<d>::distortion_stiffness() {
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = HessianMode::Projected;
  o.threads = threads_;
  Assembly a;
  assembler_->assemble(*metric_, x_, o, a);
  const Eigen::VectorXd diagonal = a.hessian.diagonal();
  double sum = 0.0;
  int count = 0;
  for (std::int32_t node : penalty_->nodes())
    for (int k = 0; k < d; ++k) {
      const std::int32_t i = dofs_.reduced(static_cast<std::size_t>(d) * node + k);
      if (i >= 0) sum += diagonal[i], ++count;
    }
  MESHMORPH_CHECK(count > 0 && sum > 0.0, "MorphProblem: the constrained nodes have no stiffness");
  return sum / count;
}

template <int d>
const std::vector<double>& MorphProblem<d>::distortions() {
  // update_weights() and min_quality() both read η_e at the end of an AL iteration: one assembly.
  if (eta_version_ == version_) return eta_;
  AssemblyOptions o;
  o.want = Want::Gradient;
  o.threads = threads_;
  Assembly a;
  assembler_->assemble(*metric_, x_, o, a);
  eta_.resize(volumes_.size());
  for (std::size_t e = 0; e < eta_.size(); ++e) eta_[e] = std::sqrt(a.element_values[e] / volumes_[e]);
  eta_version_ = version_;
  return eta_;
}

template <int d>
bool MorphProblem<d>::update_weights(double alpha, double beta, double max_weight) {
  const std::vector<double>& eta = distortions();
  bool changed = false;
  for (std::size_t e = 0; e < eta.size(); ++e) {
    const double w = weights_[e];
    const double w_hat = std::max(w, std::exp(std::min(alpha * (eta[e] - 1.0), 700.0)));
    const double w_new = std::max(w, std::min({beta * w, w_hat, max_weight}));
    if (w_new > w * (1.0 + 1e-12)) changed = true;
    weights_[e] = w_new;
  }
  if (changed) weights_changed();
  return changed;
}

template <int d>
void MorphProblem<d>::weights_changed() {
  reference_energy_ = 0.0;
  for (std::size_t e = 0; e < volumes_.size(); ++e) reference_energy_ += weights_[e] * volumes_[e];
  double wv = 0.0, v = 0.0;
  for (std::uint32_t e : boundary_cells_) wv += weights_[e] * volumes_[e], v += volumes_[e];
  boundary_weight_ = v > 0.0 ? wv / v : 1.0;
}

template <int d>
std::size_t MorphProblem<d>::stuck_inverted(const Eigen::MatrixXd& target) const {
  std::size_t count = 0;
  for (const CellBlock& block : mesh_->cells) {
    const int n = block.n_nodes_per_cell();
    Eigen::MatrixXd X(d, n);
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      bool stuck = true;
      for (int a = 0; a < n && stuck; ++a) {
        const std::int32_t node = block.cell(c)[a];
        const NodeRole role = bc_->role[node];
        stuck = role == NodeRole::Fixed || role == NodeRole::Prescribed;
        X.col(a) = role == NodeRole::Prescribed ? target.col(node) : x_.col(node);
      }
      if (stuck && !(min_jacobian_det(block.type, block.order, X) > 0.0)) ++count;
    }
  }
  return count;
}

template <int d>
double MorphProblem<d>::min_quality() {
  const std::vector<double>& eta = distortions();
  double q = 1.0;
  for (double v : eta) q = std::min(q, std::isfinite(v) && v > 0.0 ? 1.0 / v : 0.0);
  return q;
}

template class MorphProblem<2>;
template class MorphProblem<3>;

}  // namespace meshmorph

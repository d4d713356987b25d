// SPDX-License-Identifier: MIT
#include "methods/detail/fit_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <omp.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/quality/metric_registry.h"

namespace meshmorph {

template <int d>
FitProblem<d>::FitProblem(const Mesh& mesh, const Topology& topology, const std::vector<FitTerm>& terms,
                          const std::vector<std::uint8_t>& fixed, const FitOptions& options, const Eigen::MatrixXd& x)
    : mesh_(&mesh), terms_(&terms), options_(options), x_(x) {
  targets_ = build_targets<d>(mesh, x, options.target);
  dofs_ = DofMap::from_mask(d, fixed);
  assembler_ = std::make_unique<EnergyAssembler<d>>(mesh, topology, targets_, dofs_);
  metric_ = make_metric<d>(options.metric.empty() ? (d == 2 ? "mu2" : "mu303") : options.metric);
  min_det0_ = min_det(x);
}

template <int d>
double FitProblem<d>::fit_error(const Eigen::MatrixXd& x) const {
  double e = 0.0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) e = std::max(e, std::abs(t.sigma.value(x.col(s))));
  return e;
}

template <int d>
double FitProblem<d>::min_det(const Eigen::MatrixXd& x) const {
  double m = std::numeric_limits<double>::infinity();
  for (const CellBlock& block : mesh_->cells) {
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    const int n = block.n_nodes_per_cell();
#pragma omp parallel for num_threads(options_.threads > 0 ? options_.threads : omp_get_max_threads()) reduction(min : m) schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      Eigen::MatrixXd X(d, n);
      for (int a = 0; a < n; ++a) X.col(a) = x.col(block.nodes[static_cast<std::size_t>(c) * n + a]);
      m = std::min(m, min_jacobian_det(block.type, block.order, X));
    }
  }
  return m;
}

template <int d>
void FitProblem<d>::bind_blocks(const Eigen::SparseMatrix<double>& H) {
  block_offsets_.clear();
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes)
      for (int l = 0; l < d; ++l)
        for (int k = 0; k < d; ++k) {
          const std::int32_t row = dofs_.reduced(static_cast<std::size_t>(d) * s + k);
          const std::int32_t col = dofs_.reduced(static_cast<std::size_t>(d) * s + l);
          std::int64_t offset = -1;
          if (row >= 0 && col >= 0) {
            const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[col];
            const int* end = H.innerIndexPtr() + H.outerIndexPtr()[col + 1];
            const int* it = std::lower_bound(begin, end, row);
            MESHMORPH_CHECK(it != end && *it == row, "FitProblem: a node block is missing from the Hessian pattern");
            offset = it - H.innerIndexPtr();
          }
          block_offsets_.push_back(offset);
        }
}

template <int d>
double FitProblem<d>::penalty_value(const Eigen::MatrixXd& x) const {
  double v = 0.0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) {
      const double sigma = t.sigma.value(x.col(s));
      v += sigma * sigma;
    }
  return weight * v;
}

template <int d>
void FitProblem<d>::add_penalty(const Eigen::MatrixXd& x, Want want, HessianMode mode, Assembly& out) {
  out.value += penalty_value(x);
  if (want == Want::Value) return;
  if (want == Want::Hessian && block_offsets_.empty()) bind_blocks(out.hessian);
  double* values = want == Want::Hessian ? out.hessian.valuePtr() : nullptr;
  std::size_t e = 0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) {
      const Eigen::Matrix<double, d, 1> p = x.col(s);
      const double sigma = t.sigma.value(p);
      const Eigen::Matrix<double, d, 1> g = t.sigma.gradient(p);
      for (int k = 0; k < d; ++k) {
        const std::int32_t i = dofs_.reduced(static_cast<std::size_t>(d) * s + k);
        if (i >= 0) out.gradient[i] += 2.0 * weight * sigma * g(k);
      }
      if (!values) continue;
      Eigen::Matrix<double, d, d> H = 2.0 * weight * (g * g.transpose() + sigma * Eigen::Matrix<double, d, d>(t.sigma.hessian(p)));
      if (mode == HessianMode::Projected) {
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, d, d>> eig(H);
        H = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
      }
      for (int l = 0; l < d; ++l)
        for (int k = 0; k < d; ++k, ++e)
          if (block_offsets_[e] >= 0) values[block_offsets_[e]] += H(k, l);
    }
}

template <int d>
double FitProblem<d>::metric_stiffness() {
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = HessianMode::Projected;
  o.threads = options_.threads;
  Assembly a;
  assembler_->assemble(*metric_, x_, o, a);
  const Eigen::VectorXd diagonal = a.hessian.diagonal();
  double sum = 0.0;
  int count = 0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes)
      for (int k = 0; k < d; ++k)
        if (const std::int32_t i = dofs_.reduced(static_cast<std::size_t>(d) * s + k); i >= 0) sum += diagonal[i], ++count;
  return count > 0 && sum > 0.0 ? sum / count : 1.0;
}

template <int d>
void FitProblem<d>::evaluate(HessianMode mode, Assembly& out) {
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = mode;
  o.threads = options_.threads;
  assembler_->assemble(*metric_, x_, o, out);
  if (std::isfinite(out.value)) add_penalty(x_, Want::Hessian, mode, out);
}

template <int d>
double FitProblem<d>::gradient_norm(const Eigen::MatrixXd& x) {
  AssemblyOptions o;
  o.want = Want::Gradient;
  o.threads = options_.threads;
  Assembly a;
  assembler_->assemble(*metric_, x, o, a);
  add_penalty(x, Want::Gradient, HessianMode::Projected, a);
  return a.gradient.norm();
}

template <int d>
void FitProblem<d>::remember_current() {
  gradient_norm_ = gradient_norm(x_);
  error_ = fit_error(x_);
}

template <int d>
double FitProblem<d>::trial_value(const Eigen::VectorXd& p, double alpha) {
  trial_ = x_;
  dofs_.add_step(p, alpha, trial_);
  const double v = assembler_->value(*metric_, trial_, {}, options_.threads);
  return std::isfinite(v) ? v + penalty_value(trial_) : v;
}

template <int d>
bool FitProblem<d>::admissible(const Eigen::VectorXd& p, double alpha) {
  trial_ = x_;
  dofs_.add_step(p, alpha, trial_);
  if (!(min_det(trial_) > std::max(0.0, options_.det_floor * min_det0_))) return false;  // det A > 0, eq. 15
  if (error_ > 0.0 && !(fit_error(trial_) < options_.growth * error_)) return false;      // eq. 14
  return gradient_norm(trial_) < options_.growth * gradient_norm_;  // §2.2
}

template <int d>
void FitProblem<d>::accept(const Eigen::VectorXd& p, double alpha) {
  dofs_.add_step(p, alpha, x_);
  remember_current();
}

template class FitProblem<2>;
template class FitProblem<3>;

}  // namespace meshmorph

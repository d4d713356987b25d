// SPDX-License-Identifier: MIT
#include "meshmorph/energy/level_set_penalty.h"

#include <algorithm>
#include <cmath>

#include "meshmorph/energy/block_offsets.h"
#include "meshmorph/quality/spd_projection.h"

namespace meshmorph {

double fit_error(const std::vector<FitTerm>& terms, const Eigen::MatrixXd& x) {
  double e = 0.0;
  for (const FitTerm& t : terms)
    for (std::int32_t s : t.nodes) e = std::max(e, std::abs(t.sigma.value(x.col(s))));
  return e;
}

template <int d>
double LevelSetPenalty<d>::value(const Eigen::MatrixXd& x) const {
  double v = 0.0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) {
      const double sigma = t.sigma.value(x.col(s));
      v += sigma * sigma;
    }
  return weight * v;
}

template <int d>
void LevelSetPenalty<d>::add_to(const Eigen::MatrixXd& x, Want want, HessianMode mode, Assembly& out) {
  out.value += value(x);
  if (want == Want::Value) return;
  if (want == Want::Hessian && block_offsets_.empty())
    for (const FitTerm& t : *terms_) {
      const std::vector<std::int64_t> o = diagonal_block_offsets(*dofs_, out.hessian, t.nodes);
      block_offsets_.insert(block_offsets_.end(), o.begin(), o.end());
    }
  double* values = want == Want::Hessian ? out.hessian.valuePtr() : nullptr;
  std::size_t e = 0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) {
      const Eigen::Matrix<double, d, 1> p = x.col(s);
      const LevelSetPoint at = t.sigma.at(p);  // one search for all three on a facet surface
      const double sigma = at.value();
      const Eigen::Matrix<double, d, 1> g = at.gradient();
      for (int k = 0; k < d; ++k) {
        const std::int32_t i = dofs_->reduced(static_cast<std::size_t>(d) * s + k);
        if (i >= 0) out.gradient[i] += 2.0 * weight * sigma * g(k);
      }
      if (!values) continue;
      Eigen::Matrix<double, d, d> H = 2.0 * weight * (g * g.transpose() + sigma * Eigen::Matrix<double, d, d>(at.hessian()));
      if (mode == HessianMode::Projected) project_spd(H);
      for (int l = 0; l < d; ++l)
        for (int k = 0; k < d; ++k, ++e)
          if (block_offsets_[e] >= 0) values[block_offsets_[e]] += H(k, l);
    }
}

template <int d>
double LevelSetPenalty<d>::mean_at_nodes(const Eigen::VectorXd& diagonal) const {
  double sum = 0.0;
  int count = 0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes)
      for (int k = 0; k < d; ++k)
        if (const std::int32_t i = dofs_->reduced(static_cast<std::size_t>(d) * s + k); i >= 0) sum += diagonal[i], ++count;
  return count > 0 && sum > 0.0 ? sum / count : 1.0;
}

template <int d>
std::vector<std::uint8_t> LevelSetPenalty<d>::fitted(std::size_t n_nodes) const {
  std::vector<std::uint8_t> mask(n_nodes, 0);
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) mask[static_cast<std::size_t>(s)] = 1;
  return mask;
}

template class LevelSetPenalty<2>;
template class LevelSetPenalty<3>;

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// TMOP size metric μ77(T) = ½(τ − 1/τ)², τ = det T (paper 003, §2.2), 2D and 3D. Zero
/// exactly when τ = 1; depends on the volume ratio only. +∞ for τ ≤ 0 (barrier, as for
/// the shape metrics). docs/metrics.md#mu77.
template <int d>
class TmopMu77 final : public Metric<d> {
 public:
  MetricEval<d> eval(const MatT<d>& T, Want want) const override;
  std::string_view name() const override { return "mu77"; }
};

/// TMOP shape+size metric μ80(T) = γ μ_shape(T) + (1 − γ) μ77(T) (paper 003, §2.2), with
/// μ_shape = μ2 in 2D and μ303 in 3D. Zero exactly on rotations; +∞ for τ ≤ 0.
/// docs/metrics.md#mu80.
template <int d>
class TmopMu80 final : public Metric<d> {
 public:
  /// γ ∈ [0, 1] weighs shape against size; throws std::invalid_argument outside.
  explicit TmopMu80(double gamma = 0.5);
  MetricEval<d> eval(const MatT<d>& T, Want want) const override;
  std::string_view name() const override { return "mu80"; }
  double gamma() const { return gamma_; }

 private:
  double gamma_;
};

extern template class TmopMu77<2>;
extern template class TmopMu77<3>;
extern template class TmopMu80<2>;
extern template class TmopMu80<3>;

}  // namespace meshmorph

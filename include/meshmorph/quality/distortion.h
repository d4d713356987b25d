// SPDX-License-Identifier: MIT
#pragma once
#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// Regularized shape distortion η₀(T) = |T|² / (d · σ₀(τ)^{2/d}), σ₀ = ½(τ + |τ|)
/// (paper 000, eq. 2–4). Equal to 1 exactly on similarities T = sR (s > 0, R a rotation),
/// > 1 otherwise; +∞ for τ ≤ 0 (the σ₀ barrier), so no line search accepts an inversion.
/// Invariant under T → RT, T → TR and T → sT. d = 2 or 3. Derivatives: docs/metrics.md#distortion.
template <int d>
class Distortion final : public Metric<d> {
 public:
  MetricEval<d> eval(const MatT<d>& T, Want want) const override;
  std::string_view name() const override { return "distortion"; }
};

/// η₀(T)², the integrand of the morphing energy (paper 000, eq. 7) and of the element
/// distortion η_e (eq. 9). 1 on similarities, +∞ for τ ≤ 0. docs/metrics.md#distortion2.
template <int d>
class DistortionSquared final : public Metric<d> {
 public:
  MetricEval<d> eval(const MatT<d>& T, Want want) const override;
  std::string_view name() const override { return "distortion2"; }
};

extern template class Distortion<2>;
extern template class Distortion<3>;
extern template class DistortionSquared<2>;
extern template class DistortionSquared<3>;

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// TMOP shape metric μ2(T) = |T|²/(2τ) − 1, τ = det T (2D; paper 003, eq. 17).
/// Zero exactly on similarities sR; invariant under T → RT, TR, sT; +∞ for τ ≤ 0, so no
/// line search accepts an inversion. Equals η₀ − 1 of the distortion metric in 2D.
/// Derivatives: docs/metrics.md#mu2.
class TmopMu2 final : public Metric<2> {
 public:
  MetricEval<2> eval(const MatT<2>& T, Want want) const override;
  std::string_view name() const override { return "mu2"; }
};

/// TMOP shape metric μ303(T) = |T|²/(3τ^{2/3}) − 1 (3D; paper 003, eq. 17). Zero exactly
/// on similarities; +∞ for τ ≤ 0. Equals η₀ − 1 in 3D. docs/metrics.md#mu303.
class TmopMu303 final : public Metric<3> {
 public:
  MetricEval<3> eval(const MatT<3>& T, Want want) const override;
  std::string_view name() const override { return "mu303"; }
};

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>

#include "quality/detail/jet.h"

namespace meshmorph::detail {

/// η(T) = f·p/d with f = |T|², p = τ^e, e = −2/d, for τ > 0 (the caller handles τ ≤ 0).
/// Written out instead of composed from generic jets (the hot path of the morph energy):
///   ∇η  = (2p t + f p′ c) / d,                       t = vec T, c = vec cof T = ∇τ,
///   ∇²η = (2p I + f p″ c cᵀ + f p′ ∇²τ + 2p′ (t cᵀ + c tᵀ)) / d.
template <int d>
Jet<d> distortion_jet(const MatT<d>& T, const Jet<d>& tau, Want want) {
  constexpr double e = -2.0 / d;
  const double f = T.squaredNorm();
  const double p = std::pow(tau.v, e);
  Jet<d> j;
  j.v = f * p / d;
  if (!needs_gradient(want)) return j;
  const auto t = T.reshaped();
  const double dp = e * p / tau.v;
  j.g = (2.0 * p / d) * t + (f * dp / d) * tau.g;
  if (!needs_hessian(want)) return j;
  const double d2p = e * (e - 1.0) * p / (tau.v * tau.v);
  j.H.noalias() = (f * d2p / d) * tau.g * tau.g.transpose();
  j.H.noalias() += (2.0 * dp / d) * (t * tau.g.transpose() + tau.g * t.transpose());
  j.H.noalias() += (f * dp / d) * tau.H;
  j.H.diagonal().array() += 2.0 * p / d;
  return j;
}

}  // namespace meshmorph::detail

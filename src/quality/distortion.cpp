// SPDX-License-Identifier: MIT
#include "meshmorph/quality/distortion.h"

#include "quality/detail/distortion_jet.h"

namespace meshmorph {

template <int d>
MetricEval<d> Distortion<d>::eval(const MatT<d>& T, Want want) const {
  const detail::Jet<d> tau = detail::determinant(T, want);
  if (!(tau.v > 0.0)) return detail::infinite_eval<d>();  // σ₀(τ) = 0: the barrier
  return detail::to_eval(detail::distortion_jet(T, tau, want));
}

template <int d>
MetricEval<d> DistortionSquared<d>::eval(const MatT<d>& T, Want want) const {
  const detail::Jet<d> tau = detail::determinant(T, want);
  if (!(tau.v > 0.0)) return detail::infinite_eval<d>();
  const detail::Jet<d> eta = detail::distortion_jet(T, tau, want);
  return detail::to_eval(detail::compose(eta, eta.v * eta.v, 2.0 * eta.v, 2.0, want));
}

template class Distortion<2>;
template class Distortion<3>;
template class DistortionSquared<2>;
template class DistortionSquared<3>;

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/quality/tmop_shape.h"

#include "quality/detail/distortion_jet.h"

namespace meshmorph {

// μ2 and μ303 are η − 1 with η = |T|²/(d τ^{2/d}): one kernel for both.
MetricEval<2> TmopMu2::eval(const MatT<2>& T, Want want) const {
  const detail::Jet<2> tau = detail::determinant(T, want);
  if (!(tau.v > 0.0)) return detail::infinite_eval<2>();
  return detail::to_eval(detail::affine(detail::distortion_jet(T, tau, want), 1.0, -1.0, want));
}

MetricEval<3> TmopMu303::eval(const MatT<3>& T, Want want) const {
  const detail::Jet<3> tau = detail::determinant(T, want);
  if (!(tau.v > 0.0)) return detail::infinite_eval<3>();
  return detail::to_eval(detail::affine(detail::distortion_jet(T, tau, want), 1.0, -1.0, want));
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/quality/tmop_shape_size.h"

#include <stdexcept>
#include <string>

#include "meshmorph/error.h"
#include "quality/detail/distortion_jet.h"

namespace meshmorph {
namespace {

// μ77 = ½ u² with u = τ − 1/τ: φ' = u u', φ'' = u'² + u u'' where u' = 1 + τ⁻², u'' = −2τ⁻³.
template <int d>
detail::Jet<d> mu77_jet(const detail::Jet<d>& tau, Want want) {
  const double t = tau.v;
  const double u = t - 1.0 / t;
  const double u1 = 1.0 + 1.0 / (t * t);
  const double u2 = -2.0 / (t * t * t);
  return detail::compose(tau, 0.5 * u * u, u * u1, u1 * u1 + u * u2, want);
}

}  // namespace

template <int d>
MetricEval<d> TmopMu77<d>::eval(const MatT<d>& T, Want want) const {
  const detail::Jet<d> tau = detail::determinant(T, want);
  if (!(tau.v > 0.0)) return detail::infinite_eval<d>();
  return detail::to_eval(mu77_jet(tau, want));
}

template <int d>
TmopMu80<d>::TmopMu80(double gamma) : gamma_(gamma) {
  MESHMORPH_CHECK(gamma >= 0.0 && gamma <= 1.0, "mu80: gamma must lie in [0, 1], got " + std::to_string(gamma));
}

template <int d>
MetricEval<d> TmopMu80<d>::eval(const MatT<d>& T, Want want) const {
  const detail::Jet<d> tau = detail::determinant(T, want);
  if (!(tau.v > 0.0)) return detail::infinite_eval<d>();
  // The shape part is μ2 (2D) or μ303 (3D), both η − 1.
  const detail::Jet<d> shape = detail::affine(detail::distortion_jet(T, tau, want), 1.0, -1.0, want);
  return detail::to_eval(detail::combine(gamma_, shape, 1.0 - gamma_, mu77_jet(tau, want), want));
}

template class TmopMu77<2>;
template class TmopMu77<3>;
template class TmopMu80<2>;
template class TmopMu80<3>;

}  // namespace meshmorph

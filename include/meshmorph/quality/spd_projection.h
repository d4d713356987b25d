// SPDX-License-Identifier: MIT
#pragma once
#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// Projects a metric Hessian d²μ/dT² (d² × d², symmetric) onto the positive semi-definite
/// cone, in place: H = V Λ Vᵀ, eigenvalues below `floor` are raised to `floor` (DESIGN §2:
/// projecting per quadrature point keeps every element and assembled Hessian PSD, whatever
/// the element order, since the T → nodes map is linear). A matrix whose eigenvalues are all
/// ≥ `floor` is left bit-for-bit unchanged. Returns true when something was clamped.
/// Only the lower triangle of H is read. `floor` ≥ 0 is absolute.
template <int d>
bool project_spd(HessT<d>& H, double floor = 0.0);

extern template bool project_spd<2>(HessT<2>&, double);
extern template bool project_spd<3>(HessT<3>&, double);

}  // namespace meshmorph

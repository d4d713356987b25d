// SPDX-License-Identifier: MIT
#pragma once
#include <Eigen/Core>

namespace meshmorph {

/// Projects a symmetric n × n matrix onto the positive semi-definite cone, in place:
/// H = V Λ Vᵀ, eigenvalues below `floor` are raised to `floor`. For a metric Hessian
/// d²μ/dT² (HessT<d>, DESIGN §2) projecting per quadrature point keeps every element and
/// assembled Hessian PSD, whatever the element order, since the T → nodes map is linear; the
/// d × d blocks of the level-set penalty and of the slide constraints take it too. A matrix
/// whose eigenvalues are all ≥ `floor` is left bit-for-bit unchanged. Returns true when
/// something was clamped. Only the lower triangle of H is read. `floor` ≥ 0 is absolute.
/// Instantiated for n = 2, 3, 4, 9 and Eigen::Dynamic.
template <int n>
bool project_spd(Eigen::Matrix<double, n, n>& H, double floor = 0.0);

extern template bool project_spd<2>(Eigen::Matrix<double, 2, 2>&, double);
extern template bool project_spd<3>(Eigen::Matrix<double, 3, 3>&, double);
extern template bool project_spd<4>(Eigen::Matrix<double, 4, 4>&, double);
extern template bool project_spd<9>(Eigen::Matrix<double, 9, 9>&, double);
extern template bool project_spd<Eigen::Dynamic>(Eigen::MatrixXd&, double);

}  // namespace meshmorph

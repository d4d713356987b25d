// SPDX-License-Identifier: MIT
#include "meshmorph/quality/spd_projection.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "meshmorph/error.h"

namespace meshmorph {

template <int d>
bool project_spd(HessT<d>& H, double floor) {
  MESHMORPH_CHECK(floor >= 0.0, "project_spd: floor must be >= 0");
  // Fast path: a Cholesky factorization of H − floor·I exists iff every eigenvalue exceeds
  // floor; most quadrature points of a good mesh take it, and H stays untouched.
  const HessT<d> shifted = H - floor * HessT<d>::Identity();
  if (Eigen::LLT<HessT<d>>(shifted).info() == Eigen::Success) return false;

  const Eigen::SelfAdjointEigenSolver<HessT<d>> eig(H);
  auto lambda = eig.eigenvalues().eval();
  bool clamped = false;
  for (int i = 0; i < lambda.size(); ++i) {
    if (lambda(i) < floor || !(lambda(i) == lambda(i))) {
      lambda(i) = floor;
      clamped = true;
    }
  }
  if (clamped) H = eig.eigenvectors() * lambda.asDiagonal() * eig.eigenvectors().transpose();
  return clamped;
}

template bool project_spd<2>(HessT<2>&, double);
template bool project_spd<3>(HessT<3>&, double);

}  // namespace meshmorph

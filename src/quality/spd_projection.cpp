// SPDX-License-Identifier: MIT
#include "meshmorph/quality/spd_projection.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

#include "meshmorph/error.h"

namespace meshmorph {

template <int n>
bool project_spd(Eigen::Matrix<double, n, n>& H, double floor) {
  using Matrix = Eigen::Matrix<double, n, n>;
  MESHMORPH_CHECK(floor >= 0.0, "project_spd: floor must be >= 0");
  // Fast path: a Cholesky factorization of H − floor·I exists iff every eigenvalue exceeds
  // floor; most quadrature points of a good mesh take it, and H stays untouched.
  const Matrix shifted = H - floor * Matrix::Identity(H.rows(), H.cols());
  if (Eigen::LLT<Matrix>(shifted).info() == Eigen::Success) return false;

  const Eigen::SelfAdjointEigenSolver<Matrix> eig(H);
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

template bool project_spd<2>(Eigen::Matrix<double, 2, 2>&, double);
template bool project_spd<3>(Eigen::Matrix<double, 3, 3>&, double);
template bool project_spd<4>(Eigen::Matrix<double, 4, 4>&, double);
template bool project_spd<9>(Eigen::Matrix<double, 9, 9>&, double);
template bool project_spd<Eigen::Dynamic>(Eigen::MatrixXd&, double);

}  // namespace meshmorph

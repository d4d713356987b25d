// SPDX-License-Identifier: MIT
#pragma once
#include <cmath>

#include "meshmorph/fem/structured.h"

namespace meshmorph::testing {

/// The unit disk (2D) or ball (3D) of radius 1 centred at the origin: structured_mesh on the
/// unit square/cube mapped by the square-to-disk map x·√(1 − y²/2) (and its 3D analogue),
/// which takes the boundary onto the unit sphere exactly, curved nodes included.
inline Mesh ball_mesh(ElementType type, int order, int n) {
  Mesh mesh = structured_mesh(type, order, n);
  for (Eigen::Index j = 0; j < mesh.x.cols(); ++j) {
    const Eigen::VectorXd u = 2.0 * mesh.x.col(j).array() - 1.0;
    if (mesh.dim == 2) {
      mesh.x(0, j) = u[0] * std::sqrt(1.0 - u[1] * u[1] / 2);
      mesh.x(1, j) = u[1] * std::sqrt(1.0 - u[0] * u[0] / 2);
    } else {
      const Eigen::Vector3d s = u.array().square();
      for (int k = 0; k < 3; ++k) {
        const double a = s[(k + 1) % 3], b = s[(k + 2) % 3];
        mesh.x(k, j) = u[k] * std::sqrt(1.0 - a / 2 - b / 2 + a * b / 3);
      }
    }
  }
  return mesh;
}

}  // namespace meshmorph::testing

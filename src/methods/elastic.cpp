// SPDX-License-Identifier: MIT
#include <cmath>
#include <string>

#include "meshmorph/error.h"
#include "meshmorph/methods/baselines.h"
#include "methods/detail/stiffness.h"

namespace meshmorph {

BaselineResult elastic_morph(const Mesh& mesh, const Topology& topology, const BoundaryTargets& bc,
                             const BaselineOptions& options) {
  const double chi = options.stiffening;
  const double nu = options.poisson_ratio;
  if (!(std::isfinite(chi) && chi >= 0.0))
    throw InputError("elastic: options.stiffening must be a finite number >= 0, got " + std::to_string(chi));
  if (!(nu > -1.0 && nu < 0.5))
    throw InputError("elastic: options.poisson_ratio must lie in (-1, 0.5), got " + std::to_string(nu));
  constexpr double young = 1.0;  // scales K uniformly: the displacement does not depend on it
  detail::StiffnessParams params;
  params.kind = detail::StiffnessKind::Elastic;
  params.lambda = young * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  params.mu = young / (2.0 * (1.0 + nu));
  params.chi = chi;
  params.threads = options.threads;
  const Eigen::SparseMatrix<double> K = detail::assemble_stiffness(mesh, topology, params, "elastic");
  return detail::solve_constrained(mesh, bc, K, true, options, "elastic");
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/methods/baselines.h"

#include "methods/detail/stiffness.h"

namespace meshmorph {

BaselineResult laplace_morph(const Mesh& mesh, const Topology& topology, const BoundaryTargets& bc,
                             const BaselineOptions& options) {
  detail::StiffnessParams params;
  params.kind = detail::StiffnessKind::Laplace;
  params.threads = options.threads;
  const Eigen::SparseMatrix<double> K = detail::assemble_stiffness(mesh, topology, params, "laplace");
  return detail::solve_constrained(mesh, bc, K, false, options, "laplace");
}

}  // namespace meshmorph

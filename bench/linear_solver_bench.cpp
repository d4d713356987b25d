// SPDX-License-Identifier: MIT
// Linear solves with the projected Hessian of the morphing energy (distortion η² against the
// input target) on structured tetrahedral P1 meshes, boundary nodes fixed, interior nodes
// moved at random by up to 10% of the spacing (a Newton step's matrix). One case and one
// backend per process, so that the peak RSS is the case's own:
//   bench_linear_solver CASE BACKEND THREADS [RTOL]
//     CASE = tet-50k | tet-200k | tet-650k, or smaller: tet-2k | tet-4k | tet-10k | tet-25k; BACKEND = cholmod | cg-amg
// Prints one Markdown table row: | case | unknowns | nnz | backend | setup s (first
// factorize / again, same pattern) | solve s | iterations | peak RSS MB |
#include <chrono>
#include <cstdio>
#include <algorithm>
#include <cstdlib>
#include <random>
#include <string>

#include <sys/resource.h>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/quality/metric_registry.h"
#include "meshmorph/solve/linear_solver.h"

#include "bench_clock.h"

namespace {

using namespace meshmorph;
using bench::Clock;
using bench::peak_rss_mb;
using bench::seconds_since;


}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s tet-2k|tet-4k|tet-10k|tet-25k|tet-50k|tet-200k|tet-650k cholmod|cg-amg THREADS [RTOL]\n", argv[0]);
    return 2;
  }
  const std::string name = argv[1], backend = argv[2];
  const int threads = std::atoi(argv[3]);
  const double rtol = argc > 4 ? std::atof(argv[4]) : 1e-6;
  int n = 0;  // interior unknowns 3·(n − 1)³
  if (name == "tet-2k") n = 10;
  if (name == "tet-4k") n = 12;
  if (name == "tet-10k") n = 16;
  if (name == "tet-25k") n = 21;
  if (name == "tet-50k") n = 27;
  if (name == "tet-200k") n = 41;
  if (name == "tet-650k") n = 61;
  if (n == 0 || threads < 1 || (backend != "cholmod" && backend != "cg-amg") || !(rtol > 0.0)) {
    std::fprintf(stderr, "bench_linear_solver: unknown case or backend, or bad thread count / tolerance\n");
    return 2;
  }

  const Mesh mesh = structured_mesh(ElementType::Tetrahedron, 1, n);
  const Topology topology = build_topology(mesh);
  const TargetField<3> targets = build_targets<3>(mesh, mesh.x, TargetKind::Input);
  const DofMap dofs = DofMap::fixing_boundary(mesh, topology);
  const EnergyAssembler<3> assembler(mesh, topology, targets, dofs);
  Eigen::MatrixXd x = mesh.x;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.1 / n, 0.1 / n);
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    if ((x.col(j).array() > 1e-12).all() && (x.col(j).array() < 1.0 - 1e-12).all())
      for (int k = 0; k < 3; ++k) x(k, j) += u(rng);
  AssemblyOptions assembly;
  assembly.threads = threads;
  Assembly out;
  assembler.assemble(*make_metric<3>("distortion2"), x, assembly, out);
  // A Newton right-hand side: the negative gradient.
  const Eigen::VectorXd b = -out.gradient;

  LinearSolverOptions options;
  options.kind = backend == "cholmod" ? LinearSolverKind::Cholesky : LinearSolverKind::Iterative;
  options.dim = 3;
  options.block_size = 3;
  options.threads = threads;
  const auto solver = make_linear_solver(options, dofs.n_free());
  auto t0 = Clock::now();
  if (!solver->factorize(out.hessian)) {
    std::fprintf(stderr, "bench_linear_solver: factorize failed\n");
    return 1;
  }
  const double setup_first = seconds_since(t0);
  t0 = Clock::now();
  solver->factorize(out.hessian);
  const double setup_again = seconds_since(t0);
  Eigen::VectorXd dx;
  t0 = Clock::now();
  const LinearSolveStats stats = solver->solve(b, dx, rtol);
  const double solve = seconds_since(t0);
  const double residual = (b - out.hessian * dx).norm() / b.norm();
  std::printf("| %s | %zu | %lld | %s (%d threads, rtol %.0e) | %.2f / %.2f | %.2f | %d | %.0f |\n", name.c_str(),
              dofs.n_free(), static_cast<long long>(out.hessian.nonZeros()), solver->name().c_str(), threads, rtol,
              setup_first, setup_again, solve, stats.iterations, peak_rss_mb());
  if (!stats.ok || !(residual <= std::max(rtol, 1e-10) * 1.01)) {
    std::fprintf(stderr, "bench_linear_solver: solve failed (%s), residual %g\n", stats.message.c_str(), residual);
    return 1;
  }
  return 0;
}

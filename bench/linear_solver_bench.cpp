// SPDX-License-Identifier: MIT
// Linear solves with the projected Hessian of the morphing energy (distortion η² against the
// input target), boundary nodes fixed, interior nodes moved at random (a Newton step's
// matrix), on structured tetrahedral P1 meshes or on a mesh file. One case and one backend
// per process, so that the peak RSS is the case's own:
//   bench_linear_solver CASE BACKEND THREADS [RTOL]
//     CASE = tet-50k | tet-200k | tet-650k, or smaller: tet-2k | tet-4k | tet-10k | tet-25k;
//            or MESH[:pORDER], a 3D mesh file (raised to ORDER when given), its nodes moved by
//            up to 5% of their shortest distance to a node of their cells
//     BACKEND = cholmod | cg-amg | petsc-gamg | petsc-hypre
// The solver is made as the Newton methods make it (detail::make_newton_solver: the vertex
// hats as CG-AMG's first coarse level on high-order meshes, the nodes' coordinates for GAMG).
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
#include "meshmorph/fem/elevate.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/quality/metric_registry.h"
#include "meshmorph/solve/linear_solver.h"
#include "methods/detail/newton_solver.h"

#include "bench_clock.h"

namespace {

using namespace meshmorph;
using bench::Clock;
using bench::peak_rss_mb;
using bench::seconds_since;

// Each node's shortest distance to another node of one of its cells.
Eigen::VectorXd node_spacing(const Mesh& mesh) {
  Eigen::VectorXd h = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(mesh.n_nodes()), HUGE_VAL);
  for (const CellBlock& block : mesh.cells)
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const std::int32_t* v = block.cell(c);
      const int m = block.n_nodes_per_cell();
      for (int a = 0; a < m; ++a)
        for (int b = a + 1; b < m; ++b) {
          const double d = (mesh.x.col(v[a]) - mesh.x.col(v[b])).norm();
          h[v[a]] = std::min(h[v[a]], d);
          h[v[b]] = std::min(h[v[b]], d);
        }
    }
  return h;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: %s tet-2k|tet-4k|tet-10k|tet-25k|tet-50k|tet-200k|tet-650k|MESH[:pORDER] "
                 "cholmod|cg-amg|petsc-gamg|petsc-hypre THREADS [RTOL]\n", argv[0]);
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
  const bool from_file = n == 0 && name.find('.') != std::string::npos;
  const LinearSolverKind kind = backend == "cholmod"       ? LinearSolverKind::Cholesky
                                : backend == "cg-amg"      ? LinearSolverKind::Iterative
                                : backend == "petsc-gamg"  ? LinearSolverKind::PetscGamg
                                : backend == "petsc-hypre" ? LinearSolverKind::PetscHypre
                                                           : LinearSolverKind::Auto;
  if ((n == 0 && !from_file) || threads < 1 || kind == LinearSolverKind::Auto || !(rtol > 0.0)) {
    std::fprintf(stderr, "bench_linear_solver: unknown case or backend, or bad thread count / tolerance\n");
    return 2;
  }

  Mesh mesh;
  double shift = 0.1 / n;  // of every node
  Eigen::VectorXd spacing;  // per node, for file meshes
  std::string label = name;
  if (from_file) {
    const std::size_t colon = name.rfind(":p");
    mesh = read_mesh(name.substr(0, colon));
    if (colon != std::string::npos) mesh = elevate_order(mesh, std::atoi(name.c_str() + colon + 2));
    label = name.substr(name.find_last_of('/') + 1);
    spacing = node_spacing(mesh);
    shift = 0.05;
  } else {
    mesh = structured_mesh(ElementType::Tetrahedron, 1, n);
  }
  if (mesh.dim != 3) {
    std::fprintf(stderr, "bench_linear_solver: a 3D mesh is needed\n");
    return 2;
  }
  const Topology topology = build_topology(mesh);
  const TargetField<3> targets = build_targets<3>(mesh, mesh.x, TargetKind::Input);
  const DofMap dofs = DofMap::fixing_boundary(mesh, topology);
  const EnergyAssembler<3> assembler(mesh, topology, targets, dofs);
  Eigen::MatrixXd x = mesh.x;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-shift, shift);
  for (Eigen::Index j = 0; j < x.cols(); ++j)
    if (dofs.first(static_cast<std::size_t>(j) + 1) > dofs.first(static_cast<std::size_t>(j)))
      for (int k = 0; k < 3; ++k) x(k, j) += u(rng) * (from_file ? spacing[j] : 1.0);
  AssemblyOptions assembly;
  assembly.threads = threads;
  Assembly out;
  assembler.assemble(*make_metric<3>("distortion2"), x, assembly, out);
  // A Newton right-hand side: the negative gradient.
  const Eigen::VectorXd b = -out.gradient;
  if (!b.allFinite()) {
    std::fprintf(stderr, "bench_linear_solver: the moved mesh has an inverted cell\n");
    return 1;
  }

  const auto solver = detail::make_newton_solver<3>(kind, threads, mesh, dofs);
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
  std::printf("| %s | %zu | %lld | %s (%d threads, rtol %.0e) | %.2f / %.2f | %.2f | %d | %.0f |\n", label.c_str(),
              dofs.n_free(), static_cast<long long>(out.hessian.nonZeros()), solver->name().c_str(), threads, rtol,
              setup_first, setup_again, solve, stats.iterations, peak_rss_mb());
  if (!stats.ok || !(residual <= std::max(rtol, 1e-10) * 1.01)) {
    std::fprintf(stderr, "bench_linear_solver: solve failed (%s), residual %g\n", stats.message.c_str(), residual);
    return 1;
  }
  return 0;
}

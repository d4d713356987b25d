// SPDX-License-Identifier: MIT
// Assembly of value + gradient + PSD-projected Hessian of the morphing energy (distortion η²
// against the input target) on structured tetrahedral meshes. One case per process, so that
// the peak RSS is the case's own:
//   bench_assembly CASE THREADS [REPEATS] [MODE]   MODE = projected (default) | exact | gradient
//                                              CASE = tet-p1 (~1M linear tets) | tet-p3 (~100k P3)
//                                                    | tet-p1-small | tet-p3-small (quick checks)
// Prints one Markdown table row (see bench/README.md for the columns).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/quality/metric_registry.h"

#include "bench_clock.h"

namespace {

using namespace meshmorph;
using bench::Clock;
using bench::cpu_seconds;
using bench::peak_rss_mb;
using bench::seconds_since;



// The interior nodes moved at random by up to 10% of the node spacing: a valid state where
// the metric Hessians are indefinite at some points, as in a Newton step of a morph.
Eigen::MatrixXd moved_state(const Mesh& mesh, double spacing) {
  Eigen::MatrixXd x = mesh.x;
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(-0.1 * spacing, 0.1 * spacing);
  for (Eigen::Index j = 0; j < x.cols(); ++j) {
    const bool inside = (x.col(j).array() > 1e-12).all() && (x.col(j).array() < 1.0 - 1e-12).all();
    if (inside)
      for (Eigen::Index k = 0; k < 3; ++k) x(k, j) += u(rng);
  }
  return x;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s tet-p1|tet-p3|tet-p1-small|tet-p3-small THREADS [REPEATS]\n", argv[0]);
    return 2;
  }
  const std::string name = argv[1];
  const int threads = std::atoi(argv[2]);
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 3;
  const std::string mode = argc > 4 ? argv[4] : "projected";
  int order = 1, n = 0;
  if (name == "tet-p1") n = 55;  // 6·55³ = 998,250 tetrahedra
  if (name == "tet-p3") order = 3, n = 26;  // 6·26³ = 105,456 tetrahedra
  if (name == "tet-p1-small") n = 20;
  if (name == "tet-p3-small") order = 3, n = 8;
  if (n == 0 || threads < 1 || repeats < 1 || (mode != "projected" && mode != "exact" && mode != "gradient")) {
    std::fprintf(stderr, "bench_assembly: unknown case '%s' or bad thread/repeat count\n", name.c_str());
    return 2;
  }

  const Mesh mesh = structured_mesh(ElementType::Tetrahedron, order, n);
  const auto t_setup = Clock::now();
  const Topology topology = build_topology(mesh);
  const double s_topology = seconds_since(t_setup);
  const auto t_targets = Clock::now();
  const TargetField<3> targets = build_targets<3>(mesh, mesh.x, TargetKind::Input);
  const double s_targets = seconds_since(t_targets);
  const DofMap dofs = DofMap::all_free(3, mesh.n_nodes());
  const auto t_plan = Clock::now();
  const EnergyAssembler<3> assembler(mesh, topology, targets, dofs);
  const double s_plan = seconds_since(t_plan);

  const auto metric = make_metric<3>("distortion2");
  const Eigen::MatrixXd x = moved_state(mesh, 1.0 / (n * order));
  AssemblyOptions options;
  options.want = mode == "gradient" ? Want::Gradient : Want::Hessian;
  options.hessian = mode == "exact" ? HessianMode::Exact : HessianMode::Projected;
  options.threads = threads;
  Assembly out;
  assembler.assemble(*metric, x, options, out);  // first call: allocates the output
  std::vector<double> times, cpu_times;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = Clock::now();
    const double c0 = cpu_seconds();
    assembler.assemble(*metric, x, options, out);
    times.push_back(seconds_since(t0));
    cpu_times.push_back(cpu_seconds() - c0);
  }
  std::sort(times.begin(), times.end());
  std::sort(cpu_times.begin(), cpu_times.end());
  const double best = times.front();
  const double cells = static_cast<double>(mesh.n_cells());
  // | case | elements | nodes | dofs | nnz | colours | threads | setup s (topology + targets + pattern/scatter/colouring) |
  // s per assembly (wall, best of R) | CPU s per assembly (all threads, best of R) |
  // elements/s per thread (wall) | peak RSS MB |
  const std::string label = mode == "projected" ? name : name + " (" + mode + ")";
  std::printf("| %s | %zu | %zu | %zu | %lld | %d | %d | %.2f + %.2f + %.2f | %.3f | %.3f | %.3g | %.0f |\n", label.c_str(),
              mesh.n_cells(), mesh.n_nodes(), dofs.n_free(), static_cast<long long>(assembler.nnz()),
              assembler.n_colors(0), threads, s_topology, s_targets, s_plan, best, cpu_times.front(), cells / best / threads, peak_rss_mb());
  if (!(out.value > 0.0)) {
    std::fprintf(stderr, "bench_assembly: unexpected energy %g\n", out.value);
    return 1;
  }
  return 0;
}

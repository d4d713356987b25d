// SPDX-License-Identifier: MIT
// The operations of one matrix-free Newton step of `meshmorph optimize` (μ303 in 3D, μ2 in 2D,
// ideal target, boundary fixed, Lobatto points as optimize takes them) on a mesh file: the
// gradient, the value, the per-point Hessian (prepare_hessian), its action and its diagonal.
//   bench_hessian_action MESH THREADS [REPEATS] [projected|exact]
// Prints one Markdown row (bench/README.md): best wall and CPU seconds of each operation over
// REPEATS runs. CPU seconds count every thread, so they hold on a loaded machine where the
// wall times do not.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/quality/metric_registry.h"

#include "bench_clock.h"

namespace {

using namespace meshmorph;
using bench::Clock;
using bench::cpu_seconds;
using bench::peak_rss_mb;
using bench::seconds_since;


struct Timing {
  double wall = 1e300, cpu = 1e300;
};

Timing best_of(int repeats, const std::function<void()>& f) {
  Timing t;
  for (int r = 0; r < repeats; ++r) {
    const auto w0 = Clock::now();
    const double c0 = cpu_seconds();
    f();
    t.wall = std::min(t.wall, seconds_since(w0));
    t.cpu = std::min(t.cpu, cpu_seconds() - c0);
  }
  return t;
}

template <int d>
int run(const Mesh& mesh, const std::string& name, int threads, int repeats, HessianMode mode) {
  const Topology topology = build_topology(mesh);
  int order = 1;
  for (const CellBlock& b : mesh.cells) order = std::max(order, b.order);
  // optimize's rule on tensor cells (OptimizeOptions::quadrature_degree): 2p + 1 in 3D, 4p + 5 in 2D.
  const int degree = d == 3 ? 0 : 4 * order + 5;
  const TargetField<d> targets = build_targets<d>(mesh, mesh.x, TargetKind::Ideal, degree, QuadratureFamily::Lobatto);
  const DofMap dofs = DofMap::fixing_boundary(mesh, topology);
  const EnergyAssembler<d> assembler(mesh, topology, targets, dofs, false);
  const auto metric = make_metric<d>(d == 3 ? "mu303" : "mu2");
  AssemblyOptions gradient;
  gradient.want = Want::Gradient;
  gradient.threads = threads;
  Assembly out;
  HessianAction<d> action;
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(static_cast<Eigen::Index>(dofs.n_free()), -1.0, 1.0), y;
  assembler.assemble(*metric, mesh.x, gradient, out);
  const Timing tg = best_of(repeats, [&] { assembler.assemble(*metric, mesh.x, gradient, out); });
  const Timing tv = best_of(repeats, [&] { assembler.value(*metric, mesh.x, {}, threads); });
  const Timing tp = best_of(repeats, [&] { assembler.prepare_hessian(*metric, mesh.x, mode, threads, action); });
  const Timing ta = best_of(repeats, [&] { assembler.apply_hessian(action, v, y, threads); });
  const Timing td = best_of(repeats, [&] { assembler.hessian_diagonal(action, threads); });
  // | mesh | cells | DOFs | threads | gradient | value | prepare | action | diagonal | peak MB |
  // (each: wall s / CPU s, best of REPEATS)
  std::printf("| %s | %zu | %zu | %d | %.3f / %.3f | %.3f / %.3f | %.3f / %.3f | %.4f / %.4f | %.4f / %.4f | %.0f |\n",
              name.c_str(), mesh.n_cells(), dofs.n_free(), threads, tg.wall, tg.cpu, tv.wall, tv.cpu, tp.wall, tp.cpu, ta.wall,
              ta.cpu, td.wall, td.cpu, peak_rss_mb());
  return y.allFinite() && y.norm() > 0.0 ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: %s MESH THREADS [REPEATS] [projected|exact]\n", argv[0]);
    return 2;
  }
  const std::string path = argv[1];
  const int threads = std::atoi(argv[2]);
  const int repeats = argc > 3 ? std::atoi(argv[3]) : 5;
  const std::string mode = argc > 4 ? argv[4] : "projected";
  if (threads < 1 || repeats < 1 || (mode != "projected" && mode != "exact")) {
    std::fprintf(stderr, "bench_hessian_action: bad thread or repeat count, or mode\n");
    return 2;
  }
  const HessianMode m = mode == "exact" ? HessianMode::Exact : HessianMode::Projected;
  const Mesh mesh = read_mesh(path);
  const std::string name = path.substr(path.find_last_of('/') + 1);
  return mesh.dim == 3 ? run<3>(mesh, name, threads, repeats, m) : run<2>(mesh, name, threads, repeats, m);
}

// SPDX-License-Identifier: MIT
#include "meshmorph/parallel/rank_optimize.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <petscsys.h>

#include "meshmorph/energy/assembler.h"
#include "meshmorph/energy/metric_summary.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/log.h"
#include "meshmorph/quality/metric_registry.h"
#include "parallel/detail/rank_system.h"

namespace meshmorph {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

double reduce(double v, MPI_Op op) {
  MPI_Allreduce(MPI_IN_PLACE, &v, 1, MPI_DOUBLE, op, PETSC_COMM_WORLD);
  return v;
}

// The rank's owned cells followed, block by block, by its ghost cells, and the weight of
// each (1 owned, 0 ghost) in the energy: the gradient and the Hessian rows of the owned DOFs
// are then complete on the rank (RankSystem), while F counts each cell once over the ranks.
// Owned cells come first in every block, so the targets of this mesh serve the owned cells'
// mesh (LocalMesh::mesh) too.
Mesh assembly_mesh(const LocalMesh& local, std::vector<double>& weights) {
  Mesh mesh = local.mesh;
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    CellBlock& block = mesh.cells[b];
    const CellBlock& ghosts = local.ghosts[b];
    weights.insert(weights.end(), block.n_cells(), 1.0);
    weights.insert(weights.end(), ghosts.n_cells(), 0.0);
    block.nodes.insert(block.nodes.end(), ghosts.nodes.begin(), ghosts.nodes.end());
    block.physical.insert(block.physical.end(), ghosts.physical.begin(), ghosts.physical.end());
    block.entity.insert(block.entity.end(), ghosts.entity.begin(), ghosts.entity.end());
  }
  return mesh;
}

// The figures of F on one rank's cells, summed or reduced over the ranks.
template <int d>
struct RankEnergy {
  const Mesh& mesh;  // the owned cells
  const EnergyAssembler<d>& assembler;  // on the owned and ghost cells
  const std::vector<double>& weights;
  const Metric<d>& metric;
  detail::RankSystem& system;
  int threads;

  // F at y; +∞ where a cell of any rank is inverted.
  double value(const Eigen::MatrixXd& y) const {
    const double v = assembler.value(metric, y, weights, threads);
    return reduce(std::isfinite(v) ? v : kInf, MPI_SUM);
  }
  // min det A over the validity samples of every cell of every rank.
  double min_det(const Eigen::MatrixXd& y) const {
    double m = kInf;
    for (const CellBlock& block : mesh.cells) {
      const int n = block.n_nodes_per_cell();
      Eigen::MatrixXd X(d, n);
      for (std::size_t c = 0; c < block.n_cells(); ++c) {
        for (int a = 0; a < n; ++a) X.col(a) = y.col(block.cell(c)[a]);
        const double det = min_jacobian_det(block.type, block.order, X);
        m = std::isnan(det) ? -kInf : std::min(m, det);
      }
    }
    return reduce(m, MPI_MIN);
  }
  // |∇F| at y, the gradient kept in the system's `slot`.
  double gradient_norm(const Eigen::MatrixXd& y, int slot) const {
    AssemblyOptions o;
    o.want = Want::Gradient;
    o.threads = threads;
    Assembly a;
    assembler.assemble(metric, y, o, a);
    return system.set_gradient(a.gradient, slot);
  }
};

template <int d>
OptimizeResult optimize_dim(const LocalMesh& local, const OptimizeOptions& options, Eigen::MatrixXd& x) {
  const Mesh& mesh = local.mesh;
  std::vector<double> weights;
  const Mesh cells = assembly_mesh(local, weights);
  const Topology topology = build_topology(cells);
  OptimizeResult result;
  result.quadrature_degree = options.quadrature_degree > 0 ? options.quadrature_degree : optimize_quadrature_degree(mesh);
  const TargetField<d> targets = build_targets<d>(cells, x, options.target, result.quadrature_degree, options.quadrature);
  const DofMap dofs = DofMap::from_mask(d, local.fixed);
  const EnergyAssembler<d> assembler(cells, topology, targets, dofs);
  const std::unique_ptr<Metric<d>> metric = make_metric<d>(options.metric.empty() ? default_shape_metric(d) : options.metric);
  detail::RankSystem system(local, dofs);
  const RankEnergy<d> F{mesh, assembler, weights, *metric, system, optimize_threads(options.threads, dofs.n_free())};
  result.solver = "petsc-gamg";

  double energy = result.energy0 = F.value(x);
  double min_det = result.min_det0 = F.min_det(x);
  MESHMORPH_CHECK(min_det > 0.0, "optimize: the input mesh must be valid");
  double g = F.gradient_norm(x, 0);
  const double g0 = g;
  result.history.push_back({0, 0.0, energy, g, min_det});
  double measure = 0.0;
  for (std::size_t b = 0; b < targets.blocks.size(); ++b)
    for (std::size_t c = 0; c < mesh.cells[b].n_cells(); ++c)
      for (int q = 0; q < targets.blocks[b].n_points(); ++q) measure += targets.blocks[b].cell(c)[q].weight;
  // Below this predicted decrease no step can be told from rounding (as optimize_mesh).
  const double rounding = 1e-15 * (std::abs(result.energy0) + reduce(measure, MPI_SUM));
  const double floor = std::max(0.0, options.det_floor * result.min_det0);

  bool converged = local.n_global_free == 0 || g0 == 0.0;
  bool exact = false;
  std::string why;
  Assembly hessian;
  AssemblyOptions ho;
  ho.threads = F.threads;
  Eigen::VectorXd p;
  Eigen::MatrixXd trial;
  while (!converged && result.newton < options.max_newton) {
    ho.hessian = exact ? HessianMode::Exact : HessianMode::Projected;
    assembler.assemble(*metric, x, ho, hessian);
    system.set_hessian(hessian.hessian);
    double slope = 0.0;
    bool indefinite = false;
    const bool solved = system.solve(1e-8, p, slope, indefinite, why);
    result.linear += system.iterations();
    if (!solved || !(slope < 0.0)) {
      if (exact) {  // the exact Hessian is not positive definite here: project it
        exact = false;
        continue;
      }
      why = "no descent direction: " + (solved ? std::string("the step goes uphill") : why);
      break;
    }
    const bool at_rounding = -0.5 * slope <= rounding;
    double alpha = 1.0, trial_energy = kInf, trial_det = 0.0, trial_g = kInf;
    bool found = false;
    for (; alpha >= 1e-12 && !found; alpha *= 0.5) {
      trial = x;
      dofs.add_step(p, alpha, trial);
      trial_energy = F.value(trial);
      if (!(trial_energy <= energy + 1e-4 * alpha * slope) && !(at_rounding && trial_energy <= energy + rounding)) continue;
      trial_det = F.min_det(trial);
      if (!(trial_det > floor)) continue;
      trial_g = F.gradient_norm(trial, 1);
      found = at_rounding || trial_g < options.growth * g;
      if (found) break;
    }
    if (!found) {
      if (exact) {
        exact = false;
        continue;
      }
      converged = at_rounding;
      if (!converged) why = "the line search found no acceptable step";
      break;
    }
    x.swap(trial);
    system.keep_trial_gradient();
    energy = trial_energy, min_det = trial_det, g = trial_g;
    ++result.newton;
    result.history.push_back({static_cast<int>(result.newton), alpha, energy, g, min_det});
    log_progress(format("optimize: Newton %lld: F %.10g, |grad F| %.3g, alpha %.3g", result.newton, energy, g, alpha));
    exact = exact || alpha == 1.0;
    converged = g <= options.rtol * g0 || at_rounding;
  }
  if (!converged && why.empty()) why = "Newton reached its iteration limit";

  result.energy = energy;
  result.min_det = min_det;
  const MetricSummary s = metric_summary(mesh, targets, *metric, x, F.threads);
  double count = static_cast<double>(s.count);
  result.mu_min = reduce(s.min, MPI_MIN);
  result.mu_max = reduce(s.max, MPI_MAX);
  count = reduce(count, MPI_SUM);
  result.mu_mean = count > 0.0 ? reduce(s.sum, MPI_SUM) / count : 0.0;
  result.converged = converged;
  result.message = converged ? format("optimized: F %.6g -> %.6g, |grad F| reduced by %.2g in %lld Newton steps", result.energy0,
                                      energy, g0 > 0.0 ? g / g0 : 0.0, result.newton)
                             : format("stopped after %lld Newton steps at |grad F| / |grad F0| = %.2g: ", result.newton, g / g0) + why;
  return result;
}

}  // namespace

OptimizeResult optimize_on_ranks(const LocalMesh& local, const OptimizeOptions& options, Eigen::MatrixXd& x) {
  MESHMORPH_CHECK(local.fixed.size() == static_cast<std::size_t>(local.mesh.dim) * local.mesh.n_nodes(),
                  "optimize_on_ranks: one fixed flag per local DOF");
  return local.mesh.dim == 2 ? optimize_dim<2>(local, options, x) : optimize_dim<3>(local, options, x);
}

OptimizeOptions broadcast_optimize_options(const OptimizeOptions* root) {
  OptimizeOptions o = root ? *root : OptimizeOptions{};
  int ints[7] = {static_cast<int>(o.target), static_cast<int>(o.quadrature), o.quadrature_degree, o.max_newton,
                 static_cast<int>(o.solver), o.threads, static_cast<int>(o.metric.size())};
  double reals[3] = {o.rtol, o.growth, o.det_floor};
  MPI_Bcast(ints, 7, MPI_INT, 0, PETSC_COMM_WORLD);
  MPI_Bcast(reals, 3, MPI_DOUBLE, 0, PETSC_COMM_WORLD);
  o.metric.resize(static_cast<std::size_t>(ints[6]));
  MPI_Bcast(o.metric.data(), ints[6], MPI_CHAR, 0, PETSC_COMM_WORLD);
  o.target = static_cast<TargetKind>(ints[0]);
  o.quadrature = static_cast<QuadratureFamily>(ints[1]);
  o.quadrature_degree = ints[2];
  o.max_newton = ints[3];
  o.solver = static_cast<OptimizeSolver>(ints[4]);
  o.threads = ints[5];
  o.rtol = reals[0], o.growth = reals[1], o.det_floor = reals[2];
  return o;
}

}  // namespace meshmorph

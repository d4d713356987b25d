// SPDX-License-Identifier: MIT
// What fit picks when the case leaves it open (docs/fit.md, Choices).
#include <cmath>

#include "meshmorph/energy/target.h"
#include "meshmorph/methods/fit.h"
#include "meshmorph/quality/metric_registry.h"

namespace meshmorph {
namespace {

template <int d>
double mean_shape_distortion(const Mesh& mesh) {
  const TargetField<d> targets = build_targets<d>(mesh, mesh.x, TargetKind::Ideal);
  const std::unique_ptr<Metric<d>> metric = make_metric<d>(default_shape_metric(d));
  double sum = 0.0, weight = 0.0;
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const CellBlock& block = mesh.cells[b];
    const BlockTargets<d>& bt = targets.blocks[b];
    const ShapeTable& table = *bt.table;
    const int n = block.n_nodes_per_cell();
    Eigen::Matrix<double, d, Eigen::Dynamic> X(d, n);
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      for (int a = 0; a < n; ++a) X.col(a) = mesh.x.col(block.nodes[c * static_cast<std::size_t>(n) + a]);
      const QuadratureTarget<d>* t = bt.cell(c);
      for (int q = 0; q < bt.n_points(); ++q) {
        const double mu = metric->eval(MatT<d>(X.lazyProduct(table.grad(q)) * t[q].W_inv), Want::Value).mu;
        sum += t[q].weight * (std::isfinite(mu) ? mu : 1.0);
        weight += t[q].weight;
      }
    }
  }
  return weight > 0.0 ? sum / weight : 0.0;
}

}  // namespace

double mean_shape_distortion(const Mesh& mesh) {
  return mesh.dim == 2 ? mean_shape_distortion<2>(mesh) : mean_shape_distortion<3>(mesh);
}

}  // namespace meshmorph

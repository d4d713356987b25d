// SPDX-License-Identifier: MIT
#include "meshmorph/energy/metric_summary.h"

#include <algorithm>
#include <limits>

#include "meshmorph/threads.h"

namespace meshmorph {

template <int d>
MetricSummary metric_summary(const Mesh& mesh, const TargetField<d>& targets, const Metric<d>& metric,
                             const Eigen::MatrixXd& x, int threads) {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
  std::size_t count = 0;
  for (std::size_t b = 0; b < mesh.cells.size(); ++b) {
    const CellBlock& block = mesh.cells[b];
    const BlockTargets<d>& block_targets = targets.blocks[b];
    const ShapeTable& table = *block_targets.table;
    const int n = block.n_nodes_per_cell(), nq = block_targets.n_points();
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
#pragma omp parallel for num_threads(resolve_threads(threads)) reduction(min : lo) reduction(max : hi) reduction(+ : sum) schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      Eigen::Matrix<double, d, Eigen::Dynamic> X(d, n);
      for (int a = 0; a < n; ++a) X.col(a) = x.col(block.nodes[static_cast<std::size_t>(c) * n + a]);
      const QuadratureTarget<d>* t = block_targets.cell(static_cast<std::size_t>(c));
      for (int q = 0; q < nq; ++q) {
        const MatT<d> T = X.lazyProduct(table.grad(q)) * t[q].W_inv;
        const double mu = metric.eval(T, Want::Value).mu;
        lo = std::min(lo, mu);
        hi = std::max(hi, mu);
        sum += mu;
      }
    }
    count += block.n_cells() * static_cast<std::size_t>(nq);
  }
  return {lo, hi, sum, count};
}

template MetricSummary metric_summary<2>(const Mesh&, const TargetField<2>&, const Metric<2>&, const Eigen::MatrixXd&, int);
template MetricSummary metric_summary<3>(const Mesh&, const TargetField<3>&, const Metric<3>&, const Eigen::MatrixXd&, int);

}  // namespace meshmorph

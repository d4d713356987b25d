// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>

#include <Eigen/Core>

#include "meshmorph/energy/target.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// μ(T) over the metric quadrature points of every cell: its least and greatest value
/// (+∞ where a point is inverted), its sum and the number of points. Sums of parts add up.
struct MetricSummary {
  double min = 0.0, max = 0.0, sum = 0.0;
  std::size_t count = 0;
  double mean() const { return count ? sum / static_cast<double>(count) : 0.0; }
};

/// The summary of `metric` over the cells of `mesh` at x (d × n_nodes) with the targets of
/// `targets` (of mesh), on `threads` OpenMP threads (0: the OpenMP default).
template <int d>
MetricSummary metric_summary(const Mesh& mesh, const TargetField<d>& targets, const Metric<d>& metric,
                             const Eigen::MatrixXd& x, int threads);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/quality/quality_report.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <limits>
#include <utility>
#include <vector>

#include "meshmorph/error.h"
#include "meshmorph/fem/jacobian.h"
#include "meshmorph/fem/orientation.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/geometry/boundary_crossings.h"
#include "meshmorph/quality/element_quality.h"
#include "meshmorph/quality/scaled_jacobian.h"
#include "meshmorph/timings.h"

namespace meshmorph {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_compatible(const Mesh& current, const Mesh& input) {
  MESHMORPH_CHECK(input.dim == current.dim && input.n_nodes() == current.n_nodes() &&
                      input.cells.size() == current.cells.size(),
                  "quality_report: the input mesh does not match the current mesh");
  for (std::size_t b = 0; b < current.cells.size(); ++b) {
    const CellBlock &c = current.cells[b], &i = input.cells[b];
    MESHMORPH_CHECK(c.type == i.type && c.order == i.order && c.nodes == i.nodes,
                    "quality_report: cell block " + std::to_string(b) + " differs between input and current mesh");
  }
}

// Summaries of a per-cell array: min and mean (NaN when empty) and the histogram.
void summarize(const std::vector<double>& q, double& min, double& mean, std::array<std::size_t, 10>& histogram) {
  if (q.empty()) {
    min = mean = kNaN;
    return;
  }
  double sum = 0.0;
  min = q.front();
  for (double v : q) {
    min = std::min(min, v);
    sum += v;
    ++histogram[quality_bin(v)];
  }
  mean = sum / static_cast<double>(q.size());
}

// The minimum of q over the cells [begin, end), ignoring non-finite values; NaN if none.
double finite_min(const std::vector<double>& q, std::size_t begin, std::size_t end, double min) {
  for (std::size_t g = begin; g < end; ++g)
    if (std::isfinite(q[g])) min = std::isnan(min) ? q[g] : std::min(min, q[g]);
  return min;
}

std::vector<CellTypeQuality> minima_by_type(const Mesh& mesh, const QualityReport& r) {
  std::vector<CellTypeQuality> by_type;
  std::size_t offset = 0;
  for (const CellBlock& block : mesh.cells) {
    auto it = std::find_if(by_type.begin(), by_type.end(), [&](const CellTypeQuality& t) { return t.type == block.type; });
    if (it == by_type.end()) {
      by_type.push_back({block.type, 0, kNaN, kNaN, kNaN});
      it = std::prev(by_type.end());
    }
    const std::size_t end = offset + block.n_cells();
    it->n_cells += block.n_cells();
    if (r.has_input) it->min_quality = finite_min(r.quality, offset, end, it->min_quality);
    it->min_shape_quality = finite_min(r.shape_quality, offset, end, it->min_shape_quality);
    it->min_scaled_jacobian = finite_min(r.scaled_jacobian, offset, end, it->min_scaled_jacobian);
    offset = end;
  }
  std::sort(by_type.begin(), by_type.end(), [](const CellTypeQuality& a, const CellTypeQuality& b) { return a.type < b.type; });
  return by_type;
}

}  // namespace

std::size_t quality_bin(double q) {
  if (!(q > 0.0)) return 0;
  return std::min<std::size_t>(9, static_cast<std::size_t>(10.0 * q));
}

namespace {

// Positive cells may still overlap: cells listed mirrored against their neighbours fold the
// mesh over itself, and then their volumes add up to more than the boundary encloses; cells
// listed alike overlap where the boundary passes through itself.
void injectivity(const Mesh& mesh, QualityReport& r) {
  if (mesh.n_cells() == 0) return;
  const Topology topology = build_topology(mesh, TopologyParts::Facets);
  const std::vector<double> volumes = signed_volumes(mesh);
  CellOrientation o = cell_orientation(mesh, topology, volumes);
  const VolumeBalance balance = volume_balance(mesh, topology, volumes, o);
  r.cell_volume = balance.cells;
  r.enclosed_volume = balance.enclosed;
  r.twisted = o.twisted_cell >= 0;
  r.flipped_cells = std::move(o.flipped);
  const bool finite = std::isfinite(balance.cells) && std::isfinite(balance.enclosed);
  const BoundaryCrossings crossings = boundary_crossings(mesh, topology);
  r.boundary_crossings = crossings.count;
  r.crossing_facets = crossings.first;
  r.overlapping = !r.flipped_cells.empty() || r.twisted || (finite && !balance.balanced()) || crossings.count > 0;
}

}  // namespace

QualityReport quality_report(const Mesh& current, const Mesh* input) {
  const PhaseTimer timer(Phase::Validity);
  if (input) check_compatible(current, *input);
  QualityReport r;
  r.n_cells = current.n_cells();
  r.has_input = input != nullptr;
  r.shape_quality.resize(r.n_cells);
  r.scaled_jacobian.resize(r.n_cells);
  if (input) r.quality.resize(r.n_cells);
  std::vector<std::uint8_t> inverted(r.n_cells, 0);

  std::size_t offset = 0;
  for (std::size_t b = 0; b < current.cells.size(); ++b) {
    const CellBlock& block = current.cells[b];
    const auto n = static_cast<std::int64_t>(block.n_cells());
    // Each cell writes its own slots only; the reductions below run serially in cell order.
#pragma omp parallel for schedule(static)
    for (std::int64_t c = 0; c < n; ++c) {
      const auto cell = static_cast<std::size_t>(c);
      const std::size_t g = offset + cell;
      const Eigen::MatrixXd X = cell_coordinates(current, block, cell);
      const bool finite = X.allFinite();
      inverted[g] = !finite || !(min_jacobian_det(block.type, block.order, X) > 0.0);
      // element_quality() without its validity check, already done above.
      const auto q_of = [&](const Eigen::MatrixXd* W) {
        const double eta = inverted[g] ? 0.0 : element_distortion(block.type, block.order, X, W);
        return std::isfinite(eta) && eta > 0.0 ? 1.0 / eta : 0.0;
      };
      r.shape_quality[g] = q_of(nullptr);
      r.scaled_jacobian[g] = scaled_jacobian(block.type, block.order, X);
      if (input) {
        const Eigen::MatrixXd X_input = cell_coordinates(*input, input->cells[b], cell);
        r.quality[g] = q_of(&X_input);
      }
    }
    offset += block.n_cells();
  }

  r.inverted_elements = static_cast<std::size_t>(std::count(inverted.begin(), inverted.end(), std::uint8_t{1}));
  summarize(r.shape_quality, r.min_shape_quality, r.mean_shape_quality, r.shape_histogram);
  if (input) {
    summarize(r.quality, r.min_quality, r.mean_quality, r.quality_histogram);
  } else {
    r.min_quality = r.mean_quality = kNaN;
  }
  r.min_scaled_jacobian = finite_min(r.scaled_jacobian, 0, r.n_cells, kNaN);
  r.by_type = minima_by_type(current, r);
  injectivity(current, r);
  return r;
}

}  // namespace meshmorph

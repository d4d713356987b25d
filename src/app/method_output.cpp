// SPDX-License-Identifier: MIT
#include "app/detail/method_output.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>


namespace meshmorph::detail {

std::pair<double, double> boundary_errors(const BoundaryTargets& bc, const Eigen::MatrixXd& x) {
  double max = 0.0, sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < bc.n_nodes(); ++i) {
    const auto col = static_cast<Eigen::Index>(i);
    double e = 0.0;
    if (bc.role[i] == NodeRole::Prescribed) e = (x.col(col) - bc.target.col(col)).norm();
    else if (bc.role[i] == NodeRole::Slide) e = std::abs(bc.normal.col(col).dot(x.col(col) - bc.target.col(col)));
    else continue;
    max = std::max(max, e);
    sum += e * e;
    ++count;
  }
  return {max, count ? std::sqrt(sum / static_cast<double>(count)) : 0.0};
}

BoundaryTargets with_targets(BoundaryTargets bc, const Eigen::MatrixXd& target) {
  for (std::size_t i = 0; i < bc.n_nodes(); ++i)
    if (bc.role[i] == NodeRole::Prescribed) bc.target.col(static_cast<Eigen::Index>(i)) = target.col(static_cast<Eigen::Index>(i));
  return bc;
}

void fill_measures(Report& report, const Mesh& mesh, const QualityReport& q) {
  report.dim = mesh.dim;
  report.order = mesh.order();
  report.nodes = mesh.n_nodes();
  report.elements = mesh.n_cells();
  report.inverted_elements = q.inverted_elements;
  report.flipped_elements = q.flipped_cells.size();
  report.boundary_crossings = q.boundary_crossings;
  if (q.n_cells > 0) {
    report.cell_volume = q.cell_volume;
    report.enclosed_volume = q.enclosed_volume;
  }
  report.valid = q.valid();
  if (q.has_input) {
    report.min_quality = q.min_quality;
    report.mean_quality = q.mean_quality;
  }
  report.min_shape_quality = q.min_shape_quality;
  report.min_scaled_jacobian = q.min_scaled_jacobian;
  report.cell_types.clear();
  for (const CellTypeQuality& t : q.by_type) {
    CellTypeMinima m{std::string(name_of(t.type)), t.n_cells, std::nullopt, t.min_shape_quality, t.min_scaled_jacobian};
    if (q.has_input) m.min_quality = t.min_quality;
    report.cell_types.push_back(std::move(m));
  }
}

QualityReport fill_result(Report& report, const Mesh& moved, const Mesh* input, const BoundaryTargets& bc) {
  QualityReport q = quality_report(moved, input);
  const auto [err_max, err_l2] = boundary_errors(bc, moved.x);
  fill_measures(report, moved, q);
  report.boundary_error_max = err_max;
  report.boundary_error_l2 = err_l2;
  if (!report.valid) {
    report.converged = false;
    report.message = invalid_message(q) + (report.message.empty() ? std::string() : "; " + report.message);
  }
  return q;
}

std::string invalid_message(const QualityReport& q) {
  std::string s;
  if (q.inverted_elements > 0) s = std::to_string(q.inverted_elements) + " inverted elements";
  if (q.overlapping) {
    char volumes[160];
    std::snprintf(volumes, sizeof volumes, "the cells add up to %.10g, the boundary encloses %.10g", q.cell_volume,
                  q.enclosed_volume);
    s += (s.empty() ? "" : "; ") + std::string("the mesh overlaps itself: ");
    if (!q.flipped_cells.empty())
      s += std::to_string(q.flipped_cells.size()) + " cell" + (q.flipped_cells.size() > 1 ? "s" : "") +
           " listed mirrored against " + (q.flipped_cells.size() > 1 ? "their" : "its") + " neighbours (cell " +
           std::to_string(q.flipped_cells.front()) + (q.flipped_cells.size() > 1 ? ", …" : "") + "); ";
    else if (q.twisted)
      s += "no orientation fits its cells; ";
    if (q.boundary_crossings > 0)
      s += "its boundary passes through itself (boundary facets " + std::to_string(q.crossing_facets[0]) + " and " +
           std::to_string(q.crossing_facets[1]) + " cross, " + std::to_string(q.boundary_crossings) + " crossing pieces in all); ";
    s += volumes;
  }
  return s;
}

std::string inverted_input(const CaseFile& c, std::size_t inverted) {
  return c.mesh.empty() ? c.file.string() + ": the mesh has " + std::to_string(inverted) + " inverted elements"
                        : c.mesh.string() + ": " + std::to_string(inverted) + " inverted elements";
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#include "cli/detail/mesh_picture.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include <Eigen/Geometry>

#include "meshmorph/error.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::detail {
namespace {

// The local nodes around a cell of `type` and `order` (2D): each edge's first corner, then
// the nodes inside the edge, so a curved cell is drawn through them.
std::vector<int> outline_loop(ElementType type, int order) {
  std::vector<int> loop;
  for (const std::vector<int>& edge : reference_element(type, order).facet_nodes) {
    loop.push_back(edge[0]);
    loop.insert(loop.end(), edge.begin() + 2, edge.end());
  }
  return loop;
}

// The cells of a 3D mesh on the low-y side of the middle of its y range, as a mesh, and the
// index in `mesh` of each of its cells.
std::pair<Mesh, std::vector<std::int32_t>> cut(const Mesh& mesh) {
  const double middle = 0.5 * (mesh.x.row(1).minCoeff() + mesh.x.row(1).maxCoeff());
  Mesh kept;
  kept.dim = mesh.dim;
  kept.x = mesh.x;
  std::vector<std::int32_t> index;
  std::int32_t cell = 0;
  for (const CellBlock& b : mesh.cells) {
    CellBlock part;
    part.type = b.type;
    part.order = b.order;
    const int n = b.n_nodes_per_cell();
    for (std::size_t c = 0; c < b.n_cells(); ++c, ++cell) {
      double y = 0.0;
      for (int k = 0; k < n; ++k) y += mesh.x(1, b.cell(c)[k]);
      if (y / n > middle) continue;
      part.push_back(b.cell(c), 0);
      index.push_back(cell);
    }
    if (part.n_cells() > 0) kept.cells.push_back(std::move(part));
  }
  return {std::move(kept), std::move(index)};
}

std::vector<Face> faces_2d(const Mesh& mesh) {
  std::vector<Face> faces;
  faces.reserve(mesh.n_cells());
  std::int32_t cell = 0;
  for (const CellBlock& b : mesh.cells) {
    const std::vector<int> loop = outline_loop(b.type, b.order);
    for (std::size_t c = 0; c < b.n_cells(); ++c) {
      Face& f = faces.emplace_back();
      f.cell = cell++;
      for (const int k : loop) f.outline.emplace_back(mesh.x.col(b.cell(c)[k]));
    }
  }
  return faces;
}

std::vector<Face> faces_3d(const Mesh& mesh) {
  const double elevation = 20.0 * std::numbers::pi / 180.0, azimuth = 60.0 * std::numbers::pi / 180.0;
  // Towards the eye, and the screen's right and up: an orthonormal frame.
  const Eigen::Vector3d eye(std::cos(elevation) * std::cos(azimuth), std::cos(elevation) * std::sin(azimuth),
                            std::sin(elevation));
  const Eigen::Vector3d right(-std::sin(azimuth), std::cos(azimuth), 0.0);
  const Eigen::Vector3d up = eye.cross(right);

  const auto [shown, index] = cut(mesh);
  const Topology topo = build_topology(shown, TopologyParts::Facets);
  std::map<std::pair<std::size_t, int>, std::vector<int>> loops;  // (block, local facet) → cell-local nodes
  std::vector<std::pair<double, Face>> faces;
  faces.reserve(topo.boundary_facets.size());
  for (const std::int32_t f : topo.boundary_facets) {
    const CellFacet& cf = topo.facets[static_cast<std::size_t>(f)][0];
    const auto [block, c] = topo.locate(cf.cell);
    const CellBlock& b = shown.cells[block];
    auto [at, added] = loops.try_emplace({block, cf.local});
    if (added) {
      const std::vector<int>& face_nodes = reference_element(b.type, b.order).facet_nodes[static_cast<std::size_t>(cf.local)];
      for (const int k : outline_loop(facet_type(b.type, cf.local), b.order)) at->second.push_back(face_nodes[static_cast<std::size_t>(k)]);
    }
    Face face;
    face.cell = index[static_cast<std::size_t>(cf.cell)];
    double depth = 0.0;
    for (const int k : at->second) {
      const Eigen::Vector3d p = shown.x.col(b.cell(c)[k]);
      face.outline.emplace_back(p.dot(right), p.dot(up));
      depth += p.dot(eye);
    }
    faces.emplace_back(depth / static_cast<double>(at->second.size()), std::move(face));
  }
  std::stable_sort(faces.begin(), faces.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Face> sorted;
  sorted.reserve(faces.size());
  for (auto& [depth, face] : faces) sorted.push_back(std::move(face));
  return sorted;
}

}  // namespace

CellField cell_field(const Mesh& mesh, std::string_view field, const Mesh* reference) {
  const bool against = field == "quality" || field == "displacement";
  if (std::find(kPlotFields.begin(), kPlotFields.end(), field) == kPlotFields.end())
    throw InputError("plot: unknown field \"" + std::string(field) +
                     "\" (expected quality, shape_quality, scaled_jacobian or displacement)");
  if (against && reference == nullptr)
    throw InputError("plot: the field \"" + std::string(field) + "\" is measured against a reference mesh (--reference MESH)");
  if (field == "displacement") {
    const Eigen::VectorXd moved = (mesh.x - reference->x).colwise().norm();
    CellField out{{}, "displacement (cell mean)"};
    out.values.reserve(mesh.n_cells());
    for (const CellBlock& b : mesh.cells)
      for (std::size_t c = 0; c < b.n_cells(); ++c) {
        double sum = 0.0;
        for (int k = 0; k < b.n_nodes_per_cell(); ++k) sum += moved(b.cell(c)[k]);
        out.values.push_back(sum / b.n_nodes_per_cell());
      }
    return out;
  }
  QualityReport q = quality_report(mesh, against ? reference : nullptr);
  if (field == "quality") return {std::move(q.quality), "quality 1/η against the input"};
  if (field == "shape_quality") return {std::move(q.shape_quality), "shape quality"};
  return {std::move(q.scaled_jacobian), "scaled Jacobian"};
}

std::vector<bool> worst_cells(const std::vector<double>& values, double fraction) {
  std::vector<double> finite;
  for (const double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  double below = -HUGE_VAL, top = -HUGE_VAL;
  if (fraction > 0.0 && !finite.empty()) {
    std::sort(finite.begin(), finite.end());
    // Cells at the best value (to rounding) are not the worst, though they are 5 % or more: a
    // field of one value outlines no cell.
    top = finite.back() - 1e-9 * std::abs(finite.back());
    const double at = fraction * static_cast<double>(finite.size() - 1);
    const auto low = static_cast<std::size_t>(std::floor(at));
    const std::size_t high = std::min(low + 1, finite.size() - 1);
    below = finite[low] + (finite[high] - finite[low]) * (at - static_cast<double>(low));
  }
  std::vector<bool> worst(values.size());
  for (std::size_t i = 0; i < values.size(); ++i)
    worst[i] = !std::isfinite(values[i]) || values[i] <= 0.0 || (values[i] <= below && values[i] < top);
  return worst;
}

std::vector<Face> mesh_faces(const Mesh& mesh) { return mesh.dim == 2 ? faces_2d(mesh) : faces_3d(mesh); }

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#include "meshmorph/energy/target.h"

#include <cmath>
#include <stdexcept>
#include <string>

#include <Eigen/LU>

#include "energy/detail/element_kernel.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/quadrature.h"
#include "meshmorph/fem/reference_element.h"
#include "meshmorph/quality/element_quality.h"

namespace meshmorph {
namespace {

std::string where(std::size_t block, std::size_t cell) {
  return "cell " + std::to_string(cell) + " of cell block " + std::to_string(block);
}

}  // namespace

template <int d>
MatT<d> ideal_jacobian(ElementType type, double volume) {
  MESHMORPH_CHECK(volume > 0.0, "ideal_jacobian: the volume must be positive");
  MESHMORPH_CHECK(topological_dim(type) == d, "ideal_jacobian: the family's dimension differs from d");
  // W = s·W₀ with W₀ the unit-edge regular simplex or [−1, 1]^d → cube map of quality/, and s
  // such that ∫_ref |det W| = s^d · det W₀ · |ref| = volume (|ref| = 1/d! or 2^d).
  const MatT<d> W0 = ideal_jacobian(type);
  const double ref_measure = reference_measure(type);
  return std::pow(volume / (ref_measure * W0.determinant()), 1.0 / d) * W0;
}

// Volume of the unit-size ideal cell: the regular simplex, prism or pyramid of unit edges (W₀
// of quality/ maps the reference cell onto it), the unit square or cube.
template <int d>
double unit_volume(ElementType type) {
  if (is_tensor(type)) return 1.0;
  return reference_measure(type) * ideal_jacobian(type).determinant();
}

template <int d>
TargetField<d> build_targets(const Mesh& mesh, const Eigen::MatrixXd& x_input, TargetKind kind,
                             int quadrature_degree, QuadratureFamily family) {
  MESHMORPH_CHECK(mesh.dim == d, "build_targets: the mesh dimension differs from d");
  MESHMORPH_CHECK(x_input.rows() == d && x_input.cols() == mesh.x.cols(),
                  "build_targets: x_input must be dim × n_nodes");
  TargetField<d> field;
  field.kind = kind;
  field.blocks.resize(mesh.cells.size());
  std::vector<std::vector<double>> volumes(mesh.cells.size());
  double volume_sum = 0.0;
  std::size_t volume_count = 0;
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    const CellBlock& block = mesh.cells[bi];
    MESHMORPH_CHECK(topological_dim(block.type) == d, "build_targets: a cell block is not of dimension d");
    const int degree = quadrature_degree > 0 ? quadrature_degree : metric_quadrature_degree(block.type, block.order);
    BlockTargets<d>& bt = field.blocks[bi];
    bt.table = &shape_table(block.type, block.order, degree, family);
    const ShapeTable& table = *bt.table;
    const int n = table.n_nodes();
    const int Q = table.n_points();
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
    bt.points.resize(block.n_cells() * static_cast<std::size_t>(Q));
    std::vector<double>& vol = volumes[bi];
    vol.assign(block.n_cells(), 0.0);
    std::ptrdiff_t bad_cell = -1;
    int bad_q = -1;
#pragma omp parallel for schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      detail::NodalMatrix<d> X(d, n);
      const std::int32_t* nodes = block.cell(static_cast<std::size_t>(c));
      for (int a = 0; a < n; ++a) X.col(a) = x_input.col(nodes[a]);
      QuadratureTarget<d>* out = bt.points.data() + c * Q;
      for (int q = 0; q < Q; ++q) {
        const MatT<d> A = X * table.dN.middleCols(q * d, d);
        const double det = A.determinant();
        vol[static_cast<std::size_t>(c)] += table.weights[q] * std::abs(det);
        if (kind == TargetKind::Input) {
          if (!(det > 0.0)) {
#pragma omp critical(meshmorph_build_targets)
            if (bad_cell < 0 || c < bad_cell) {
              bad_cell = c;
              bad_q = q;
            }
          }
          out[q].W_inv = A.inverse();
          out[q].weight = table.weights[q] * std::abs(det);
        }
      }
    }
    if (bad_cell >= 0)
      throw InputError("input target: " + where(bi, static_cast<std::size_t>(bad_cell)) +
                       " is inverted or degenerate at quadrature point " + std::to_string(bad_q) +
                       " (det A ≤ 0); morphing against the input needs a valid input mesh");
    for (double v : vol)
      if (v > 0.0) {
        volume_sum += v;
        ++volume_count;
      }
  }
  if (kind == TargetKind::Input) return field;
  if (volume_count == 0 && mesh.n_cells() > 0)
    throw InputError("ideal target: every cell of the mesh has zero volume");
  const double mean_volume = volume_count > 0 ? volume_sum / static_cast<double>(volume_count) : 1.0;
  for (std::size_t bi = 0; bi < mesh.cells.size(); ++bi) {
    BlockTargets<d>& bt = field.blocks[bi];
    const int Q = bt.n_points();
    const ShapeTable& table = *bt.table;
    for (std::size_t c = 0; c < volumes[bi].size(); ++c) {
      const double v = kind == TargetKind::IdealUnit ? unit_volume<d>(mesh.cells[bi].type)
                       : volumes[bi][c] > 0.0  ? volumes[bi][c]
                                               : mean_volume;
      const MatT<d> W = ideal_jacobian<d>(mesh.cells[bi].type, v);
      const MatT<d> W_inv = W.inverse();
      const double det = W.determinant();
      for (int q = 0; q < Q; ++q) {
        bt.points[c * static_cast<std::size_t>(Q) + static_cast<std::size_t>(q)] = {W_inv, table.weights[q] * det};
      }
    }
  }
  return field;
}

const char* target_name(TargetKind kind) {
  switch (kind) {
    case TargetKind::Input: return "input";
    case TargetKind::Ideal: return "ideal";
    case TargetKind::IdealUnit: return "ideal_unit";
  }
  return "?";
}

TargetKind target_kind(const std::string& name) {
  for (TargetKind k : {TargetKind::Input, TargetKind::Ideal, TargetKind::IdealUnit})
    if (name == target_name(k)) return k;
  throw std::invalid_argument("unknown target \"" + name + "\"");
}

template MatT<2> ideal_jacobian<2>(ElementType, double);
template MatT<3> ideal_jacobian<3>(ElementType, double);
template TargetField<2> build_targets<2>(const Mesh&, const Eigen::MatrixXd&, TargetKind, int, QuadratureFamily);
template TargetField<3> build_targets<3>(const Mesh&, const Eigen::MatrixXd&, TargetKind, int, QuadratureFamily);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/fem/shape_table.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/quality/metric.h"

namespace meshmorph {

/// Which target Jacobian W a metric measures T = A W⁻¹ against (DESIGN §2).
enum class TargetKind {
  /// W = the Jacobian of the input element at each quadrature point (paper 000: Dφ = A·A_input⁻¹):
  /// the identity map has distortion 1 and the input's sizing and anisotropy are kept.
  Input,
  /// W = the regular simplex / the cube, scaled to the element's own volume (volume-
  /// equivalent): elements are driven to ideal shape at their current size. W is constant
  /// over an element.
  Ideal,
  /// W = the regular simplex of unit edge / the unit square or cube, for every element
  /// (MFEM's -tid 1, "ideal shape, unit size"): each element weighs the same in the energy,
  /// whatever its size, as in MFEM's mesh-optimizer. Shape metrics see only the weights change.
  IdealUnit,
};

/// The case-file / CLI name of a target kind ("input", "ideal", "ideal_unit"), and back
/// (throws std::invalid_argument on other names).
const char* target_name(TargetKind kind);
TargetKind target_kind(const std::string& name);

/// The target data of one quadrature point: W⁻¹ and the integration weight w_q·|det W|.
template <int d>
struct QuadratureTarget {
  MatT<d> W_inv;
  double weight = 0.0;  ///< w_q · |det W_q|, so that E_e = Σ_q weight_q · μ(T_q)
};

/// Targets of the cells of one CellBlock at the points of its metric quadrature rule.
template <int d>
struct BlockTargets {
  const ShapeTable* table = nullptr;  ///< basis at the rule's points (shared, never null once built)
  std::vector<QuadratureTarget<d>> points;  ///< n_cells × table->n_points(), row per cell

  int n_points() const { return table->n_points(); }
  const QuadratureTarget<d>* cell(std::size_t c) const {
    return points.data() + c * static_cast<std::size_t>(n_points());
  }
};

/// Targets for every cell block of a mesh, built once per mesh (and target kind) and reused
/// by every energy evaluation. blocks[i] belongs to mesh.cells[i].
template <int d>
struct TargetField {
  TargetKind kind = TargetKind::Input;
  std::vector<BlockTargets<d>> blocks;
};

/// Ideal target Jacobian of a family with reference measure scaled to `volume`:
/// simplices map the unit reference simplex onto a regular simplex (corner 0 at the
/// origin, edge 1 before scaling), tensor cells map [−1,1]^d onto a cube; the scale s makes
/// ∫_ref |det W| = volume. `volume` must be > 0.
template <int d>
MatT<d> ideal_jacobian(ElementType type, double volume);

/// Builds the targets of `mesh` (dim must equal d) from the coordinates `x_input`
/// (d × n_nodes; usually mesh.x). Each block uses shape_table(type, order,
/// metric_quadrature_degree(type, order), family), or degree `quadrature_degree` when it is > 0.
///
/// Input: throws InputError naming the block and cell when det W ≤ 0 at a quadrature point
/// (an inverted input element has no meaningful input target).
/// Ideal: the volume of each cell is ∫|det A|; a cell of zero volume takes the mean volume of
/// the others (throws InputError if every cell is degenerate).
template <int d>
TargetField<d> build_targets(const Mesh& mesh, const Eigen::MatrixXd& x_input, TargetKind kind,
                             int quadrature_degree = 0, QuadratureFamily family = QuadratureFamily::Gauss);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/energy/level_set_penalty.h"
#include "meshmorph/energy/target.h"
#include "meshmorph/geometry/level_set_function.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph {

/// Material indicators of eq. 10: η_E = 0 where ∫_E σ ≥ 0, 1 otherwise (global cell order),
/// the integral by the metric quadrature of each cell.
std::vector<std::uint8_t> material_indicators(const Mesh& mesh, const LevelSetFunction& sigma);

/// The material interface of indicators η: for each cell (global order), the number of its
/// facets whose neighbour has the other indicator.
std::vector<int> interface_facet_counts(const Topology& topology, const std::vector<std::uint8_t>& eta);

/// Eq. 12, two passes (first the cells with η = 0, then those with η = 1, each seeing the
/// flips before it): a cell keeps η when at most one of its facets is on the interface,
/// flips when all but one are. Then (ours, with `reduce_crowding`) a cell still with two or
/// more interface facets flips when that lowers the count of such cells among it and its
/// neighbours, until no flip helps; with `vertex_stars` also every cell around a vertex of
/// such a cell takes one indicator when that lowers the count among them and their
/// neighbours (fit uses them on tetrahedra, where no split follows). The cells left with two or more
/// are listed in `to_split` (global cell indices). Returns the corrected indicators.
std::vector<std::uint8_t> correct_indicators(const Topology& topology, std::vector<std::uint8_t> eta,
                                             std::vector<std::int32_t>& to_split, bool reduce_crowding = true,
                                             bool vertex_stars = false);

/// Conforming splits of linear triangles and quadrilaterals with two or more interface
/// facets (paper 003 §3.2): a quadrilateral whose two interface facets meet at a corner is
/// cut along the diagonal from that corner (two triangles, one interface facet each); any
/// other listed triangle or quadrilateral is split from a new node at its centroid. The new
/// cells keep their cell's indicator; `eta` is extended accordingly. Facet blocks and groups
/// are kept; a new node's tag follows the largest, its nodal field values are the means over
/// its cell's corners. Throws std::invalid_argument for other cell types or orders.
Mesh split_cells(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& cells,
                 std::vector<std::uint8_t>& eta);

/// Trimming (paper 003 §4.2): removes the cells with η = 0 (global cell order) and the nodes
/// that no kept cell uses; facet elements whose nodes all remain are kept, node tags and
/// fields follow. `cut` receives, for each kept cell (new global order), one flag per local
/// facet: its neighbour was removed, so the facet is new boundary to fit.
Mesh trim_cells(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& eta,
                std::vector<std::vector<std::uint8_t>>& cut);

/// The facets flagged in `cut` (as trim_cells made it; the cells may have been elevated
/// since): the nodes of every order of each, in the facet element's ordering (trace.h).
std::vector<std::vector<std::int32_t>> cut_facets(const Mesh& mesh, const std::vector<std::vector<std::uint8_t>>& cut);

/// The facets between cells of different indicators, as cut_facets gives them.
std::vector<std::vector<std::int32_t>> interface_facets(const Mesh& mesh, const Topology& topology,
                                                        const std::vector<std::uint8_t>& eta);

/// The nodes of `facets` (cut_facets, interface_facets), sorted and unique.
std::vector<std::int32_t> facets_nodes(const std::vector<std::vector<std::int32_t>>& facets);

/// The validity samples that lie on a flat edge: in 3D an edge shared by two facets of one
/// cell whose nodes are all fitted, in 2D a corner shared by two such facets. Both facets
/// end on the level set's smooth surface, so the cell's angle there tends to 180° and det A
/// to 0 (every convex edge of a hexahedral staircase has one such cell: paper 003 §3.3,
/// §4.1). In 3D also a corner whose three edges have all their nodes fitted (det A there is
/// the triple product of three tangents of the surface).
struct FlatEdges {
  /// Per cell block, per cell: the index of its mask in `masks`, −1 for a cell without.
  std::vector<std::vector<std::int32_t>> mask_of_cell;
  /// One flag per validity sample of the cell's (type, order): 1 on a flat edge.
  std::vector<std::vector<std::uint8_t>> masks;
  std::size_t cells = 0;  ///< cells with a flat edge
};
FlatEdges flat_edges(const Mesh& mesh, const std::vector<std::uint8_t>& fitted);

/// The mean over the mesh (weighted by volume) of the shape metric μ2 (2D) / μ303 (3D)
/// against the ideal target: 0 on a mesh of squares or cubes, about 0.15 on right
/// triangles. Fit takes the input target when it is large (docs/fit.md, Choices).
double mean_shape_distortion(const Mesh& mesh);

/// Parameters of fitting (paper 003 Algorithm 1); defaults are the paper's.
struct FitOptions {
  std::string metric;            ///< "" = mu2 in 2D, mu303 in 3D (eq. 17)
  TargetKind target = TargetKind::Ideal;
  /// Points of the metric integral on tensor cells (degree metric_quadrature_degree).
  QuadratureFamily quadrature = QuadratureFamily::Gauss;
  int quadrature_degree = 0;  ///< 0 = metric_quadrature_degree of each block
  /// w_σ at the start; 0 = penalty0 · (mean diagonal of the metric Hessian at the fitted
  /// DOFs) / 2, the penalty as stiff as the mesh around it (F_σ's diagonal is 2w|∇σ|²).
  double weight0 = 0.0;
  double penalty0 = 1.0;
  bool adaptive = true;          ///< eq. 13; false keeps w_σ (paper Fig. 8)
  double alpha_sigma = 10.0;     ///< α_σ
  double eps_dsigma = 1e-3;      ///< ε_Δσ
  double eps_sigma = 1e-5;       ///< ε_σ: stop when max |σ| at S is below
  int n_sigma = 10;              ///< N_σ: stop after this many consecutive weight increases
  int max_newton = 200;          ///< N_opt
  double growth = 1.2;           ///< line search: |∇F| and max |σ| grow by less than this (eq. 14)
  double det_floor = 1e-3;       ///< eq. 15: min det A stays above det_floor · its initial value
  /// Validity (line search and result) skips the samples on flat edges (FlatEdges): det A
  /// may reach 0 there, as MFEM's TMOP allows by checking its quadrature points only.
  bool flat_edges = false;
  LinearSolverKind solver = LinearSolverKind::Auto;
  int threads = 0;
};

/// One Newton step of the report's history.
struct FitIteration {
  int newton = 0;
  double weight = 0.0;      ///< w_σ of the step
  double alpha = 0.0;       ///< step length
  double fit_error = 0.0;   ///< max |σ| at S after the step
  double min_det = 0.0;     ///< min det A over the validity samples after the step
};

struct FitResult {
  bool converged = false;
  std::string message;
  long long newton = 0, linear = 0, weight_updates = 0;
  double fit_error0 = 0.0, fit_error = 0.0;  ///< max |σ| at S, before and after
  double min_det0 = 0.0, min_det = 0.0;      ///< min det A, before and after
  /// Cells with min det A ≤ 0 over their validity samples, except the flat-edge samples
  /// when options.flat_edges; and the cells whose det A ≤ 0 only there.
  std::size_t inverted = 0, flat = 0;
  std::vector<FitIteration> history;
};

/// Paper 003 Algorithm 1: minimises F = ∫ μ(A W⁻¹) + w_σ Σ_terms Σ_{s∈S} σ(x_s)² over the
/// nodes not fixed by `fixed` (one flag per DOF, dim·node + k), from `x` (d × n, a valid
/// mesh), with the adaptive weight of eq. 13 and the line-search rules of §2.2 and eq.
/// 14–15. `x` is the last accepted iterate on return (always valid).
FitResult fit_to_level_sets(const Mesh& mesh, const Topology& topology, const std::vector<FitTerm>& terms,
                            const std::vector<std::uint8_t>& fixed, const FitOptions& options, Eigen::MatrixXd& x);

}  // namespace meshmorph

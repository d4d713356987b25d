// SPDX-License-Identifier: MIT
#pragma once
#include <string>

#include <Eigen/Core>

#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/methods/eikonal.h"
#include "meshmorph/methods/surface_cvt.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/solve/linear_solver.h"

namespace meshmorph {

/// How the design motion is carried into the volume.
enum class DeformMethod {
  Eikonal,  ///< convection–diffusion along the Eikonal rays (paper 004, eq. 3.8)
  Laplace,  ///< component-wise Laplacian extension, the baseline of paper 004 §3.3
};

/// Which Eikonal distance scales the diffusion of eq. 3.8.
enum class DiffusionDistance {
  FarField,  ///< α ε₁², ε₁ = distance to the far field: eq. 3.8 as printed
  Design,    ///< α ε₂², ε₂ = distance to the design: the paper's text ("diffusivity scaled down with the
             ///< square of the distance to the obstacle, making the convective term dominant in close vicinity")
};

/// Parameters of `deform` (paper 004, Alg. 1: CVT repair, then Eikonal convection).
struct DeformOptions {
  DeformMethod method = DeformMethod::Eikonal;
  bool cvt = true;            ///< the tangential CVT repair of the design surface (eq. 3.5)
  CvtOptions cvt_options;
  EikonalOptions eikonal;     ///< both Eikonal solves (eq. 3.7)
  /// α of eq. 3.8 (diffusion α ε̂², ε̂ = ε / max ε). The paper leaves α and β "to be chosen
  /// based on the actual geometry"; only β/α matters (the equation is homogeneous), and it
  /// sets where diffusion takes over from convection: at ε̂ ≈ β/α. 1 and 1 keep the 2D and 3D
  /// obstacle benchmarks valid (docs/deform.md).
  double alpha = 1.0;
  double beta = 1.0;          ///< β of eq. 3.8: the convection speed along ∇ε̂₂
  DiffusionDistance diffusion = DiffusionDistance::Design;
  /// true: the convection as printed, div(β v ∇ε₂) (eq. 3.8); false (default): β ∇ε₂·∇v, which
  /// carries v along the rays without the thinning by their spread (v Δε₂) that compresses
  /// the cells in front of a convex bump (docs/deform.md has the measurements).
  bool conservative = false;
  LinearSolverKind solver = LinearSolverKind::Auto;  ///< the Laplace baseline's linear solver
  int threads = 0;            ///< OpenMP threads; 0 = the OpenMP default
};

/// The Eikonal distances of an update on its input mesh: Newton starts from them in the next
/// update of a sequence, whose mesh differs only by the deformation.
struct EikonalDistances {
  Eigen::VectorXd far_field;  ///< ε₁
  Eigen::VectorXd design;     ///< ε₂
};

struct DeformResult {
  Eigen::MatrixXd x;          ///< dim × n_nodes: the deformed mesh
  EikonalDistances distances; ///< empty for the Laplace method
  CvtResult cvt;              ///< the CVT step (iterations 0 when it was off)
  int newton = 0;             ///< Newton steps of the two Eikonal solves
  int linear_solves = 0;      ///< linear solves of the volume extension
  /// Curved cells that the extension inverted and whose inner nodes were put back between
  /// their corners (straight-sided); 0 on linear meshes.
  std::size_t straightened_cells = 0;
  bool converged = false;
  std::string message;
};

/// One deformation update (paper 004, Alg. 1) of the mesh at its current positions `mesh.x`.
/// The design is the Prescribed nodes of `bc`, whose targets describe the moved design surface
/// (typically x + g n); Fixed nodes are the far field (v = 0); Slide nodes move on their plane
/// (natural condition per component, then the normal part of the displacement is removed).
///
/// 1. CVT (options.cvt): the design nodes are redistributed tangentially on the moved surface
///    (surface_cvt: onto `projection` where it applies, else onto the facets at the targets).
///    Design nodes on a non-design boundary facet and at features stay at their targets.
/// 2. The volume displacement v with v = (design position − x) on the design:
///    Eikonal: ε₁, ε₂ from eikonal_distance (zero on the Fixed nodes, on the design), then
///    −div(α ε̂² ∇v) + div(β v ∇ε̂₂) = 0 per component (eq. 3.8, ε̂ = ε / max ε, the diffusion
///    distance per options.diffusion), SUPG-stabilized, one sparse LU for all components.
///    Laplace: laplace_morph with the design nodes prescribed.
/// `density_reference` (d × n_nodes) gives CvtDensity::Input its facet sizes (the input mesh).
/// `previous`: the distances of the previous update of a sequence (start of both Newton solves).
/// Throws InputError when no node is Prescribed, when Eikonal has no Fixed far field, or when
/// a cell has det J ≤ 0. Does not check the validity of the result (the caller does).
DeformResult deform(const Mesh& mesh, const Topology& topology, const BoundaryTargets& bc,
                    const Eigen::MatrixXd& density_reference, const DeformOptions& options = {},
                    const SurfaceProjection& projection = {}, const EikonalDistances& previous = {});

}  // namespace meshmorph

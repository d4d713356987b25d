// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// A design surface as linear simplices on the mesh's nodes: segments in 2D, triangles in
/// 3D. Facets of order 2 are split into their linear sub-facets (a P2 segment into 2, a P2
/// triangle into 4) and quadrilaterals into triangles, so every surface node is a generator.
struct DesignSurface {
  int dim = 0;                        ///< spatial dimension; dim nodes per facet
  std::vector<std::int32_t> facets;   ///< n_facets × dim node indices, oriented out of the volume
  std::size_t n_facets() const { return dim ? facets.size() / static_cast<std::size_t>(dim) : 0; }
};

/// The boundary facets of `mesh` whose nodes are all in `on_design`, split into linear
/// sub-facets. Throws InputError for facet kinds it cannot split (order ≥ 3 triangles,
/// quadrilaterals above order 1).
DesignSurface design_surface(const Mesh& mesh, const Topology& topology, const std::vector<std::uint8_t>& on_design);

/// How the density ρ of eq. 3.3 is chosen.
enum class CvtDensity {
  Uniform,  ///< ρ = 1: equal spacing (paper 004)
  Input,    ///< ρ per facet from its size on a reference surface, so that the reference spacing is kept
};

/// Parameters of the tangential CVT reparameterization (paper 004, eq. 3.5).
struct CvtOptions {
  CvtDensity density = CvtDensity::Uniform;
  double tolerance = 1e-4;    ///< stop when max |τ| ≤ tolerance · mean edge length (Alg. 1, ‖τ‖ ≤ ε)
  int max_iterations = 5000;  ///< iterations of eq. 3.5
  /// Nodes where the surface turns by more than this (degrees) stay put: corners and sharp
  /// edges, whose position is part of the shape.
  double feature_angle = 30.0;
};

/// Exact projection onto the target surface for one node, when one is known (an analytic
/// level set): returns the closest point of x on it, or nothing to use the discrete surface.
using SurfaceProjection = std::function<std::optional<Eigen::VectorXd>(std::int32_t node, const Eigen::VectorXd& x)>;

struct CvtResult {
  Eigen::MatrixXd x;             ///< d × n_nodes: the surface nodes redistributed, others unchanged
  int iterations = 0;
  double last_update = 0.0;      ///< max |τ| of the last iteration, relative to the mean edge length
  bool converged = false;
  double spacing_ratio_before = 0.0;  ///< max / min edge length of the surface before
  double spacing_ratio_after = 0.0;   ///< and after
  std::size_t pinned = 0;        ///< surface nodes held at corners, sharp edges and the surface's rim
};

/// Tangential CVT reparameterization of the surface `surface` whose nodes sit at `x`
/// (paper 004, eq. 3.3–3.5): every free surface node moves to the ρ-weighted centroid of its
/// patch (the facets holding it) projected into its tangent plane, x_i ← x_i + P_i Σ ρ_e |e|
/// (c_e − x_i) / Σ ρ_e |e| with P_i = I − n_i n_iᵀ (n_i the area-weighted node normal), and
/// is projected back onto the target surface: by `projection` where it gives a point, else
/// onto the input surface (the facets at `x`, which do not move during the iteration: the
/// shape is kept to its discretization). Jacobi sweeps until the tangential update is below
/// the tolerance. Pinned: nodes on the rim of the surface (an edge of one facet, or a node of
/// a non-design boundary facet, `pinned_nodes`) and at features (CvtOptions::feature_angle).
/// `reference` (d × n_nodes) gives the facet sizes of CvtDensity::Input: ρ_e = |e_ref|^{−(k+1)/k}
/// for k-dimensional facets, so that the reference spacing balances the patch centroids.
CvtResult surface_cvt(const DesignSurface& surface, const Eigen::MatrixXd& x, const Eigen::MatrixXd& reference,
                      const std::vector<std::uint8_t>& pinned_nodes, const CvtOptions& options = {},
                      const SurfaceProjection& projection = {});

/// max / min edge length of the surface's facets at positions x.
double spacing_ratio(const DesignSurface& surface, const Eigen::MatrixXd& x);

/// Distance of point p from the surface's facets at positions `surface_x` (every facet is
/// tried: for reports, not for inner loops).
double distance_to_surface(const DesignSurface& surface, const Eigen::MatrixXd& surface_x, const Eigen::VectorXd& p);

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <vector>

#include "meshmorph/geometry/level_set_function.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

/// The unit outward normal of a boundary facet with tangents T = ∂φ/∂u (d × (d − 1)) at a
/// point, its nodes in the trace's ordering (fem/trace.h): by the right-hand rule of
/// mesh/topology.h, the normal points out of a cell of positive Jacobian.
Eigen::VectorXd outward_normal(const Eigen::MatrixXd& T);

/// The level set of a discrete surface: the union S of the boundary facets `facets` (indices
/// into topology.facets, each with one cell) of `mesh`, the polynomial maps φ_f of their
/// Lagrange nodes frozen at mesh.x (lines in 2D, triangles and quadrilaterals in 3D).
///
/// With p the closest point of S to x (over every facet, each by Newton on |φ_f(u) − x|² in
/// its reference facet, edges and corners included; a box tree over the facets, and
/// each facet skipped when a polytope around its Bézier control points is farther than the
/// nearest facet so far) and n_f(p) the outward unit normal there (outward_normal):
/// - x on S (|x − p| ≤ 1e-12 of S's size): σ = (x − p)·n̄, ∇σ = n̄, the mean of the normals of
///   the facets through p (one normal where p is inside a facet, and a mean across the normal
///   jumps of a C⁰ surface);
/// - p on the rim of S (an edge or corner of S's facets with no neighbour in S: a feature
///   curve when S is a smooth patch of a boundary): σ = (x − p)·n_f(p), ∇σ = n_f(p), the
///   continuation of S by its tangent plane, whose zero set meets a neighbouring patch's
///   along the rim only;
/// - otherwise the signed distance: σ = ±|x − p| (+ on the side of n_f), ∇σ = (x − p)/σ.
/// ∇²σ = −T G⁻¹ B (G − σB)⁻¹ Tᵀ from the facet at p (T = ∂φ/∂u, G = TᵀT, B = n·∂²φ/∂u²,
/// n = ∇σ): exact where p is inside a facet; on S at a facet's edge, the mean over the facets
/// through p; at points of the rim and of the wedges around facet edges, that of the facet
/// (the Hessian of the distance to a curve or point is not used). closest_point(x) is p, on S
/// to rounding, so a Gauss–Newton projection x − σ∇σ lands on S in one step off the rim.
/// Creases (S is C⁰ across facet edges; x within 1e-8 of S's size from one, 1e-8 of the
/// reference facet): stationarity(x, g) is the largest descent over the tangent cones of the
/// facets through x, and step_normals(x, g) all their normals when no cone descends more than
/// the crease itself (the step follows the crease), else the normal of the steepest facet.
/// φ_f is evaluated in monomials, a change of basis of its Lagrange form (equal to rounding).
/// Cost: one closest-point search per call; LevelSetFunction::at(x) makes one search for the
/// value, gradient, Hessian, stationarity and step normals at x together.
LevelSetFunction facet_surface(const Mesh& mesh, const Topology& topology, const std::vector<std::int32_t>& facets);

}  // namespace meshmorph

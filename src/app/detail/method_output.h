// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/app/case_file.h"
#include "meshmorph/app/report.h"
#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/quality/quality_report.h"

namespace meshmorph::detail {

/// Max and root-mean-square distance of the Prescribed nodes from their targets, and of the
/// Slide nodes from their planes.
std::pair<double, double> boundary_errors(const BoundaryTargets& bc, const Eigen::MatrixXd& x);

/// `bc` with the targets of its Prescribed nodes taken from `target` (d × n).
BoundaryTargets with_targets(BoundaryTargets bc, const Eigen::MatrixXd& target);

/// The mesh and quality fields of a report (DESIGN §3.3) from `q`, the measures of `mesh`:
/// min_quality and mean_quality only where q was taken against an input.
void fill_measures(Report& report, const Mesh& mesh, const QualityReport& q);

/// Measures `moved` and fills the mesh, quality and boundary fields of a method's report
/// (DESIGN §3.3): quality against `input` unless it is null. An invalid result is not
/// converged, whatever the method said, and the message says why (invalid_message).
QualityReport fill_result(Report& report, const Mesh& moved, const Mesh* input, const BoundaryTargets& bc);

/// Why a mesh measured by `q` is invalid: "3 inverted elements", "the mesh overlaps itself: 1
/// cell listed mirrored against its neighbours (cell 4); the cells add up to …, the boundary
/// encloses …". Empty for a valid mesh.
std::string invalid_message(const QualityReport& q);

/// "mesh.msh: 3 inverted elements" for a case read from a file, "Morpher: the mesh has 3
/// inverted elements" for one whose mesh is in memory (CaseFile::mesh empty).
std::string inverted_input(const CaseFile& c, std::size_t inverted);

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#pragma once
#include <algorithm>
#include <string>

#include "meshmorph/fem/jacobian.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/methods/boundary_targets.h"
#include "meshmorph/mesh/mesh.h"
#include "meshmorph/mesh/topology.h"
#include "meshmorph/quality/element_quality.h"

namespace meshmorph::test {

/// Min quality of the mesh at x against the input (1/η per cell).
inline double min_quality(const Mesh& input, const Eigen::MatrixXd& x) {
  Mesh moved = input;
  moved.x = x;
  double q = 1.0;
  for (const CellBlock& block : input.cells)
    for (std::size_t c = 0; c < block.n_cells(); ++c) {
      const Eigen::MatrixXd X0 = cell_coordinates(input, block, c), X = cell_coordinates(moved, block, c);
      q = std::min(q, element_quality(block.type, block.order, X, &X0));
    }
  return q;
}

/// The nodes of group `fixed` fixed, those of group `moved` translated by dx along x.
inline BoundaryTargets translated_group(const Mesh& mesh, const std::string& fixed, const std::string& moved, double dx) {
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(mesh.dim, static_cast<Eigen::Index>(mesh.n_nodes()));
  for (std::int32_t node : mesh.group_nodes(*mesh.find_group(fixed))) bc.role[node] = NodeRole::Fixed;
  for (std::int32_t node : mesh.group_nodes(*mesh.find_group(moved))) {
    bc.role[node] = NodeRole::Prescribed;
    bc.target(0, node) += dx;
  }
  return bc;
}

/// Paper 000 §5.2's shell (bench/geo/shell.geo at lc 0.8: 444 nodes, 42 across), its inner
/// sphere translated by 8 along x, the outer one fixed.
struct CoarseShell {
  Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/shell_coarse.msh");
  Topology topology = build_topology(mesh);
  BoundaryTargets bc = translated_group(mesh, "outer", "inner", 8.0);
};

}  // namespace meshmorph::test

// SPDX-License-Identifier: MIT
#pragma once
#include "meshmorph/mesh/mesh.h"

namespace meshmorph {

/// Straight-sided order elevation: every cell and facet block is raised to `order`, new
/// nodes are placed by the current element map (so a curved input keeps its shape) and
/// shared between neighbours. Existing nodes keep their indices; new nodes get tags after
/// the largest one. Node fields are interpolated to the new nodes with the old cell's basis
/// (exact for fields of the old order). Lowering the order is an error (std::invalid_argument).
Mesh elevate_order(const Mesh& mesh, int order);

/// Whether elevate_order(mesh, order) raises the mesh: a cell block below `order` and none
/// above (a mesh of several orders is raised where its highest is `order` already).
bool below_order(const Mesh& mesh, int order);

}  // namespace meshmorph

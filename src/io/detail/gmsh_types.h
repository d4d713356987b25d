// SPDX-License-Identifier: MIT
#pragma once
#include <optional>
#include <string>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph::detail {

struct FamilyOrder {
  ElementType type;
  int order;
  /// Nodes an element of the type lists: fewer than the cell's for the incomplete
  /// (serendipity) types read as complete cells (promote.h), else 0 (all of them).
  int n_listed = 0;
};

/// Nodes an element of `fo` lists in a file.
inline int n_listed(const FamilyOrder& fo) { return fo.n_listed > 0 ? fo.n_listed : n_nodes_of(fo.type, fo.order); }

/// Family and order of a Gmsh element type number (ecosystem.md §A.3), or nothing for the
/// types meshmorph does not read (the serendipity types other than 16 QUA_8, 17 HEX_20,
/// 18 PRI_15 and 19 PYR_13, which are read as the complete cells; order ≥ 5, unknown).
std::optional<FamilyOrder> from_gmsh_type(int code);
/// Why `code` is rejected, e.g. "serendipity/incomplete element type 16 (QUA_8)".
std::string describe_unsupported_gmsh_type(int code);
/// Gmsh type number of a family and order; throws InputError if MSH has none.
int gmsh_type_of(ElementType type, int order);

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#pragma once
#include <optional>
#include <string>

#include "meshmorph/mesh/element_type.h"

namespace meshmorph::detail {

struct FamilyOrder {
  ElementType type;
  int order;
};

/// Family and order of a Gmsh element type number (ecosystem.md §A.3), or nothing for the
/// types meshmorph does not hold (serendipity, prisms, pyramids, order ≥ 5, unknown).
std::optional<FamilyOrder> from_gmsh_type(int code);
/// Why `code` is rejected, e.g. "serendipity/incomplete element type 16 (QUA_8)".
std::string describe_unsupported_gmsh_type(int code);
/// Gmsh type number of a family and order; throws InputError if MSH has none.
int gmsh_type_of(ElementType type, int order);

}  // namespace meshmorph::detail

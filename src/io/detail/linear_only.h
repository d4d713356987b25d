// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <string_view>

#include "meshmorph/error.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

/// Throws InputError "<format> holds linear cells only; the mesh has <family>s of order N"
/// where a block of `mesh` (points aside) is of order > 1: for the writers of linear formats,
/// before they write anything.
inline void require_linear(const Mesh& mesh, std::string_view format) {
  for (const auto* list : {&mesh.facets, &mesh.cells})
    for (const CellBlock& b : *list)
      if (b.type != ElementType::Point && b.order != 1)
        throw InputError(std::string(format) + " holds linear cells only; the mesh has " +
                         std::string(name_of(b.type)) + "s of order " + std::to_string(b.order));
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#pragma once
#include <cgnslib.h>

#include <string>
#include <vector>

#include "io/detail/cgns_file.h"
#include "io/detail/mesh_builder.h"

namespace meshmorph::detail {

/// An element of a CGNS section as read into a MeshBuilder: its block and position there.
struct CgnsElement {
  ElementType type;
  int order;
  std::size_t cell;
};

/// What the CGNS reader keeps of a zone for its groups.
struct CgnsZone {
  std::string path;  ///< "/Base/Zone", for messages
  int base = 0, zone = 0;
  std::vector<std::int32_t> node;  ///< zone node (0-based) → mesh node
  struct Section {
    std::string name;
    cgsize_t start = 0, end = 0;
    std::vector<CgnsElement> elements;  ///< end − start + 1
  };
  std::vector<Section> sections;
  /// The element of number `n`, or null when no section holds it.
  const CgnsElement* find(cgsize_t n) const;
};

/// Reads the BC_t, ZoneSubRegion_t and Family_t nodes of the zones into groups of `b`
/// (read_cgns's rules, meshmorph/io/cgns.h).
void read_cgns_groups(const CgnsFile& f, MeshBuilder& b, const std::vector<CgnsZone>& zones, int cell_dim);

}  // namespace meshmorph::detail

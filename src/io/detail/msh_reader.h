// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <map>
#include <utility>

#include "io/detail/cursor.h"
#include "io/detail/gmsh_types.h"
#include "io/detail/mesh_builder.h"

namespace meshmorph::detail {

/// State shared by the MSH 2.2 and 4.1 section readers.
struct MshState {
  Cursor cur;
  MeshBuilder builder;
  TagIndex index;
  bool binary = false;
  bool have_nodes = false;
  /// (entity dim, entity tag) → first physical tag of the entity (MSH 4.1 $Entities).
  std::map<std::pair<int, int>, std::int32_t> entity_physical;

  /// Fails unless `count` items of at least `min_bytes` each fit in the rest of the file.
  void check_count(std::uint64_t count, std::size_t min_bytes, std::size_t at) const {
    if (count > cur.remaining() / min_bytes + 1)
      cur.fail_at(at, "count " + std::to_string(count) + " is larger than the rest of the file can hold");
  }
  /// Records a node read at `at` (coordinates checked finite by the caller).
  void add_node(std::int64_t tag, double x, double y, double z, std::size_t at) {
    builder.tags.push_back(tag);
    builder.xyz.insert(builder.xyz.end(), {x, y, z});
    if (z != 0.0 && builder.first_nonzero_z.empty()) builder.first_nonzero_z = cur.where(at);
  }
  /// Builds the tag index after $Nodes; fails on a duplicate tag.
  void index_nodes(std::size_t section_start);
  /// Resolves the node tags of one element and appends it to `block`.
  void add_element(CellBlock& block, const std::int64_t* node_tags, std::int32_t physical,
                   std::int32_t entity, std::size_t at);
  /// Family/order of a type number, or a failure naming it.
  FamilyOrder element_type(int code, std::size_t at) const;
};

double finite_or_fail(const Cursor& cur, double v, std::size_t at, const char* what);

void read_msh41_entities(MshState& s);
void read_msh41_nodes(MshState& s);
void read_msh41_elements(MshState& s);
void read_msh22_nodes(MshState& s);
void read_msh22_elements(MshState& s);

}  // namespace meshmorph::detail

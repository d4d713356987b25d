// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

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
  /// (entity dim, entity tag) → the physical tags of the entity (MSH 4.1 $Entities).
  std::map<std::pair<int, int>, std::vector<std::int32_t>> entity_physical;
  /// Entities of $PartitionedEntities that lie inside a parent of higher dimension: the
  /// interfaces between partitions, whose elements are not facets of the model.
  std::set<std::pair<int, int>> partition_interfaces;
  /// A scalar $NodeData field: the time step held, a value per node, which nodes have one,
  /// and where its last section starts (for the "node without a value" error).
  struct NodeField {
    std::int64_t step = 0;
    std::vector<double> values;
    std::vector<std::uint8_t> given;
    std::size_t at = 0;
  };
  std::map<std::string, NodeField, std::less<>> node_fields;

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
  /// Resolves the node tags of one element of type `fo` and appends it to `block`; an
  /// incomplete element's missing nodes are −1 until MeshBuilder::finish.
  void add_element(CellBlock& block, const FamilyOrder& fo, const std::int64_t* node_tags, std::int32_t physical,
                   std::int32_t entity, std::size_t at);
  /// Family/order of a type number, or a failure naming it.
  FamilyOrder element_type(int code, std::size_t at) const;
};

double finite_or_fail(const Cursor& cur, double v, std::size_t at, const char* what);

void read_msh41_entities(MshState& s);
void read_msh41_partitioned_entities(MshState& s);
void read_msh41_nodes(MshState& s);
void read_msh41_elements(MshState& s);
void read_msh22_nodes(MshState& s, bool parametric = false);
void read_msh22_elements(MshState& s);
/// One $NodeData section (2.2 and 4.1; its "$NodeData" token starts at `at`). Scalar fields go to
/// s.node_fields (a new time step of a name replaces the previous one, sections of the
/// same step are merged); fields of several components are read and dropped.
void read_node_data(MshState& s, std::size_t at);
/// Moves the scalar fields into the builder; fails when a field misses a node.
void finish_node_data(MshState& s);

}  // namespace meshmorph::detail

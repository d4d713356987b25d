// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <unordered_map>
#include <vector>

#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

/// Maps file node tags to 0-based node indices: a dense table when the tags are compact,
/// a hash map otherwise (tags may be sparse and unordered; never index by tag − 1 blindly).
class TagIndex {
 public:
  /// Builds the map; returns the position of the first duplicate tag, or -1.
  std::ptrdiff_t build(const std::vector<std::int64_t>& tags);
  /// Node index of `tag`, or -1.
  std::int32_t find(std::int64_t tag) const {
    if (dense_) {
      if (tag < min_ || tag - min_ >= static_cast<std::int64_t>(table_.size())) return -1;
      return table_[static_cast<std::size_t>(tag - min_)];
    }
    const auto it = map_.find(tag);
    return it == map_.end() ? -1 : it->second;
  }

 private:
  bool dense_ = true;
  std::int64_t min_ = 0;
  std::vector<std::int32_t> table_;
  std::unordered_map<std::int64_t, std::int32_t> map_;
};

/// Position in `nodes` (n entries) of the first node that an element lists twice, or −1. A
/// cell with a repeated node has no volume; reported at its line it is found where it is
/// wrong, not later as a facet "shared by three cells" or an inverted cell.
int repeated_node(const std::int32_t* nodes, int n);

/// Collects what a reader finds (nodes in 3D, elements of every dimension, groups) and
/// turns it into a Mesh: dimension 3 if there is a 3D cell, else 2 (z must then be 0);
/// elements of that dimension become cells, the others facets. A facet in several physical
/// groups is held once per group (as Gmsh writes it in MSH 2.2); a cell keeps its first.
class MeshBuilder {
 public:
  std::vector<std::int64_t> tags;
  std::vector<double> xyz;                 ///< 3 per node
  std::vector<PhysicalGroup> named_groups; ///< from the file's names, in file order
  /// Where the first node with z ≠ 0 was read (a full error prefix), empty if none.
  std::string first_nonzero_z;
  /// Scalar nodal fields by name, one value per node of `tags` (the readers check that
  /// every node has one before finish()).
  std::map<std::string, std::vector<double>, std::less<>> node_fields;
  /// An element's physical tags after its first (an MSH 4.1 entity in several groups).
  struct ExtraPhysical {
    ElementType type;
    int order;
    std::size_t cell;  ///< in the block of (type, order)
    std::int32_t tag;
  };
  std::vector<ExtraPhysical> extra_physical;

  /// The block of (type, order), created on first use (blocks keep first-use order).
  CellBlock& block(ElementType type, int order);

  /// Builds the mesh. `where` is an error prefix ("file: line N") for whole-file problems.
  /// Cells read as incomplete ones (−1 for the nodes they lack) are completed first
  /// (promote_incomplete), and a note saying how many is logged once, naming `file`.
  Mesh finish(const std::string& where, const std::filesystem::path& file = {});

 private:
  std::vector<CellBlock> blocks_;
};

}  // namespace meshmorph::detail

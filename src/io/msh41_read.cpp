// SPDX-License-Identifier: MIT
// MSH 4.1 sections ($Entities, $PartitionedEntities, $Nodes, $Elements), ASCII and binary
// (size_t = 8 bytes).
#include <string>
#include <vector>

#include "io/detail/msh_reader.h"

namespace meshmorph::detail {
namespace {

// A section header number: size_t in binary files, a token in ASCII files.
std::uint64_t count(MshState& s, const char* what) {
  return s.binary ? s.cur.raw<std::uint64_t>(what) : s.cur.integer<std::uint64_t>(what);
}
int small_int(MshState& s, const char* what) {
  return s.binary ? s.cur.raw<std::int32_t>(what) : s.cur.integer<int>(what);
}
double real(MshState& s, const char* what) {
  if (!s.binary) return s.cur.real(what);
  const std::size_t at = s.cur.pos();
  return finite_or_fail(s.cur, s.cur.raw<double>(what), at, what);
}
// Where the field just read starts (its first byte in binary content).
std::size_t here(MshState& s) { return s.cur.token_start(); }

void begin_binary(MshState& s) {
  if (!s.binary) return;
  s.cur.skip_line();  // the rest of the "$Section" line
  s.cur.binary = true;
}

}  // namespace

namespace {

// The four counts and the records of $Entities, or of $PartitionedEntities, whose records
// hold their parent entity and partitions after the tag.
void read_entity_records(MshState& s, bool partitioned) {
  std::uint64_t n[4];
  for (auto& v : n) {
    v = count(s, "number of entities");
    s.check_count(v, s.binary ? (partitioned ? 28 : 4) : (partitioned ? 8 : 2), here(s));
  }
  for (int dim = 0; dim < 4; ++dim) {
    for (std::uint64_t e = 0; e < n[dim]; ++e) {
      const int tag = small_int(s, "entity tag");
      if (partitioned) {
        if (small_int(s, "parent entity dimension") != dim) s.partition_interfaces.insert({dim, tag});
        small_int(s, "parent entity tag");
        const std::uint64_t n_parts = count(s, "number of partitions of the entity");
        s.check_count(n_parts, s.binary ? 4 : 2, here(s));
        for (std::uint64_t k = 0; k < n_parts; ++k) small_int(s, "partition tag");
      }
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) real(s, "entity bounding box");
      const std::uint64_t n_phys = count(s, "number of physical tags");
      s.check_count(n_phys, s.binary ? 4 : 2, here(s));
      std::vector<std::int32_t>& physical = s.entity_physical[{dim, tag}];
      physical.clear();
      for (std::uint64_t k = 0; k < n_phys; ++k) physical.push_back(small_int(s, "physical tag"));
      if (dim > 0) {
        const std::uint64_t n_bound = count(s, "number of bounding entities");
        s.check_count(n_bound, s.binary ? 4 : 2, here(s));
        for (std::uint64_t k = 0; k < n_bound; ++k) small_int(s, "bounding entity tag");
      }
    }
  }
}

}  // namespace

void read_msh41_entities(MshState& s) {
  begin_binary(s);
  read_entity_records(s, false);
}

// A partitioned file (gmsh -part N) puts its elements on the entities of this section, each a
// piece of a model entity in one or more partitions, and gives them the physical tags there;
// its $Entities holds the model's entities, which no element names. Ghost entities and
// partition numbers are read past: the mesh is read whole. Entities inside a parent of higher
// dimension are the interfaces between partitions: they carry the parent's physical tags,
// and their elements are left out.
void read_msh41_partitioned_entities(MshState& s) {
  begin_binary(s);
  count(s, "number of partitions");
  const std::uint64_t n_ghosts = count(s, "number of ghost entities");
  s.check_count(n_ghosts, s.binary ? 8 : 4, here(s));
  for (std::uint64_t g = 0; g < n_ghosts; ++g) {
    small_int(s, "ghost entity tag");
    small_int(s, "ghost entity partition");
  }
  read_entity_records(s, true);
}

// The header shared by $Nodes and $Elements: numBlocks numItems minTag maxTag, the counts
// checked against the bytes left (at least `block_bytes` per block, `item_bytes` per item).
struct SectionHeader {
  std::uint64_t n_blocks = 0, n_items = 0;
  std::size_t n_items_at = 0;  // offset of numItems, for the final count check
};

SectionHeader read_section_header(MshState& s, const std::string& item, int item_bytes_binary, int item_bytes_text) {
  begin_binary(s);
  SectionHeader h;
  h.n_blocks = count(s, ("number of " + item + " blocks").c_str());
  s.check_count(h.n_blocks, s.binary ? 20 : 8, here(s));
  h.n_items = count(s, ("number of " + item + "s").c_str());
  h.n_items_at = here(s);
  s.check_count(h.n_items, s.binary ? item_bytes_binary : item_bytes_text, h.n_items_at);
  count(s, ("minimum " + item + " tag").c_str());
  count(s, ("maximum " + item + " tag").c_str());
  return h;
}

void read_msh41_nodes(MshState& s) {
  const auto [n_blocks, n_nodes, n_nodes_at] = read_section_header(s, "node", 32, 8);
  Cursor& c = s.cur;
  s.builder.tags.reserve(n_nodes);
  s.builder.xyz.reserve(3 * n_nodes);
  std::uint64_t seen = 0;
  std::vector<std::int64_t> block_tags;
  for (std::uint64_t b = 0; b < n_blocks; ++b) {
    const int dim = small_int(s, "entity dimension");
    if (dim < 0 || dim > 3) c.fail_at(here(s), "entity dimension must be 0..3");
    small_int(s, "entity tag");
    const int parametric = small_int(s, "parametric flag");
    if (parametric != 0 && parametric != 1) c.fail_at(here(s), "parametric flag must be 0 or 1");
    const std::uint64_t n = count(s, "number of nodes in block");
    s.check_count(n, s.binary ? 32 : 8, here(s));
    seen += n;
    if (seen > n_nodes) c.fail_at(here(s), "node blocks hold more nodes than the " + std::to_string(n_nodes) + " announced");
    block_tags.resize(n);
    for (auto& t : block_tags) {
      t = s.binary ? static_cast<std::int64_t>(c.raw<std::uint64_t>("node tag")) : c.integer<std::int64_t>("node tag");
      if (t <= 0) c.fail_at(here(s), "node tag must be positive");
    }
    const int n_param = parametric ? dim : 0;
    for (std::uint64_t i = 0; i < n; ++i) {
      const std::size_t at = s.binary ? c.pos() : (c.skip_space(), c.pos());
      const double x = real(s, "x coordinate");
      const double y = real(s, "y coordinate");
      const double z = real(s, "z coordinate");
      for (int k = 0; k < n_param; ++k) real(s, "parametric coordinate");
      s.add_node(block_tags[i], x, y, z, at);
    }
  }
  if (seen != n_nodes)
    c.fail_at(n_nodes_at, "announced " + std::to_string(n_nodes) + " nodes but the blocks hold " + std::to_string(seen));
}

void read_msh41_elements(MshState& s) {
  const auto [n_blocks, n_elements, n_elements_at] = read_section_header(s, "element", 16, 4);
  Cursor& c = s.cur;
  std::uint64_t seen = 0;
  std::vector<std::int64_t> tags;
  for (std::uint64_t b = 0; b < n_blocks; ++b) {
    const int dim = small_int(s, "entity dimension");
    const std::size_t dim_at = here(s);
    const int entity = small_int(s, "entity tag");
    const int code = small_int(s, "element type");
    const FamilyOrder fo = s.element_type(code, here(s));
    if (topological_dim(fo.type) != dim)
      c.fail_at(dim_at, "entity dimension " + std::to_string(dim) + " does not match element type " + std::to_string(code));
    const std::uint64_t n = count(s, "number of elements in block");
    const int k = n_listed(fo);
    s.check_count(n, s.binary ? 8 * static_cast<std::size_t>(k + 1) : 2 * static_cast<std::size_t>(k + 1), here(s));
    seen += n;
    if (seen > n_elements)
      c.fail_at(here(s), "element blocks hold more elements than the " + std::to_string(n_elements) + " announced");
    const bool interface = s.partition_interfaces.contains({dim, entity});
    const auto it = s.entity_physical.find({dim, entity});
    const std::vector<std::int32_t> none;
    const std::vector<std::int32_t>& physical = it == s.entity_physical.end() ? none : it->second;
    CellBlock& block = s.builder.block(fo.type, fo.order);
    block.nodes.reserve(block.nodes.size() + n * static_cast<std::size_t>(n_nodes_of(fo.type, fo.order)));
    tags.resize(static_cast<std::size_t>(k));
    for (std::uint64_t e = 0; e < n; ++e) {
      const std::size_t at = s.binary ? c.pos() : (c.skip_space(), c.pos());
      count(s, "element tag");
      for (auto& t : tags)
        t = s.binary ? static_cast<std::int64_t>(c.raw<std::uint64_t>("node tag")) : c.integer<std::int64_t>("node tag");
      if (interface) continue;
      s.add_element(block, fo, tags.data(), physical.empty() ? 0 : physical.front(), entity, at);
      for (std::size_t p = 1; p < physical.size(); ++p)
        s.builder.extra_physical.push_back({fo.type, fo.order, block.n_cells() - 1, physical[p]});
    }
  }
  if (seen != n_elements)
    c.fail_at(n_elements_at, "announced " + std::to_string(n_elements) + " elements but the blocks hold " + std::to_string(seen));
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
// MSH 2.2 sections ($Nodes, $Elements), ASCII and binary (32-bit ints, 64-bit doubles).
#include <string>
#include <vector>

#include "io/detail/msh_reader.h"

namespace meshmorph::detail {

void read_msh22_nodes(MshState& s, bool parametric) {
  Cursor& c = s.cur;
  const auto n = c.integer<std::uint64_t>("number of nodes");
  s.check_count(n, s.binary ? 28 : 8, c.token_start());
  s.builder.tags.reserve(n);
  s.builder.xyz.reserve(3 * n);
  if (s.binary) {
    c.skip_line();
    c.binary = true;
  }
  for (std::uint64_t i = 0; i < n; ++i) {
    std::int64_t tag = 0;
    double x[3];
    std::size_t at = 0;
    if (s.binary) {
      at = c.pos();
      tag = c.raw<std::int32_t>("node tag");
      for (double& v : x) v = finite_or_fail(c, c.raw<double>("coordinate"), at, "coordinate");
    } else {
      tag = c.integer<std::int64_t>("node tag");
      at = c.token_start();
      x[0] = c.real("x coordinate");
      x[1] = c.real("y coordinate");
      x[2] = c.real("z coordinate");
      if (parametric) {  // Mesh.SaveParametric: the entity's dimension and tag, then u (curves) or u v (surfaces)
        const int dim = c.integer<int>("entity dimension");
        if (dim < 0 || dim > 3) c.fail_at(c.token_start(), "entity dimension must be 0..3");
        c.integer<std::int64_t>("entity tag");
        for (int k = 0; k < (dim == 1 || dim == 2 ? dim : 0); ++k) c.real("parametric coordinate");
      }
    }
    if (tag <= 0) c.fail_at(at, "node tag must be positive");
    s.add_node(tag, x[0], x[1], x[2], at);
  }
}

void read_msh22_elements(MshState& s) {
  Cursor& c = s.cur;
  const auto n = c.integer<std::uint64_t>("number of elements");
  s.check_count(n, s.binary ? 12 : 8, c.token_start());
  std::vector<std::int64_t> tags;
  CellBlock* block = nullptr;
  FamilyOrder fo{};
  int block_code = 0;  // the type of *block, once set (no sentinel: a file may hold any int)
  auto use_type = [&](int code, std::size_t at) {
    if (block != nullptr && code == block_code) return;
    fo = s.element_type(code, at);
    block = &s.builder.block(fo.type, fo.order);
    block_code = code;
    tags.resize(static_cast<std::size_t>(n_listed(fo)));
  };
  if (!s.binary) {
    for (std::uint64_t e = 0; e < n; ++e) {
      c.integer<std::int64_t>("element tag");
      const std::size_t at = c.token_start();
      const int code = c.integer<int>("element type");
      use_type(code, c.token_start());
      const int n_tags = c.integer<int>("number of tags");
      if (n_tags < 0 || n_tags > 1000) c.fail_at(c.token_start(), "number of tags must be 0..1000");
      std::int32_t physical = 0;
      std::int32_t entity = 0;
      for (int k = 0; k < n_tags; ++k) {
        const auto t = c.integer<std::int32_t>("element tag value");
        if (k == 0) physical = t;
        if (k == 1) entity = t;
      }
      for (auto& t : tags) t = c.integer<std::int64_t>("node tag");
      s.add_element(*block, fo, tags.data(), physical, entity, at);
    }
    return;
  }
  c.skip_line();
  c.binary = true;
  std::uint64_t seen = 0;
  std::vector<std::int32_t> record;
  while (seen < n) {
    const std::size_t header_at = c.pos();
    const int code = c.raw<std::int32_t>("element type");
    const auto count = c.raw<std::int32_t>("number of elements");
    const auto n_tags = c.raw<std::int32_t>("number of tags");
    if (count <= 0 || static_cast<std::uint64_t>(count) > n - seen)
      c.fail_at(header_at, "element group count " + std::to_string(count) + " does not fit the announced total");
    if (n_tags < 0 || n_tags > 1000) c.fail_at(header_at, "number of tags must be 0..1000");
    use_type(code, header_at);
    record.resize(1 + static_cast<std::size_t>(n_tags) + tags.size());
    for (std::int32_t e = 0; e < count; ++e) {
      const std::size_t at = c.pos();
      for (auto& v : record) v = c.raw<std::int32_t>("element data");
      for (std::size_t k = 0; k < tags.size(); ++k) tags[k] = record[1 + static_cast<std::size_t>(n_tags) + k];
      s.add_element(*block, fo, tags.data(), n_tags > 0 ? record[1] : 0, n_tags > 1 ? record[2] : 0, at);
    }
    seen += static_cast<std::uint64_t>(count);
  }
}

}  // namespace meshmorph::detail

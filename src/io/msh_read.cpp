// SPDX-License-Identifier: MIT
#include "meshmorph/io/msh.h"

#include <cmath>
#include <string>

#include "io/detail/msh_reader.h"
#include "meshmorph/error.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace detail {

double finite_or_fail(const Cursor& cur, double v, std::size_t at, const char* what) {
  if (!std::isfinite(v)) cur.fail_at(at, std::string(what) + " is not finite");
  return v;
}

void MshState::index_nodes(std::size_t section_start) {
  const std::ptrdiff_t dup = index.build(builder.tags);
  if (dup >= 0)
    cur.fail_at(section_start, "duplicate node tag " + std::to_string(builder.tags[static_cast<std::size_t>(dup)]));
  have_nodes = true;
}

void MshState::add_element(CellBlock& block, const FamilyOrder& fo, const std::int64_t* node_tags, std::int32_t physical,
                           std::int32_t entity, std::size_t at) {
  const int n = n_listed(fo);
  for (int k = 0; k < n; ++k) {
    const std::int32_t i = index.find(node_tags[k]);
    if (i < 0) cur.fail_at(at, "element references undefined node tag " + std::to_string(node_tags[k]));
    block.nodes.push_back(i);
  }
  if (const int k = repeated_node(block.nodes.data() + block.nodes.size() - n, n); k >= 0)
    cur.fail_at(at, "element lists node tag " + std::to_string(node_tags[k]) + " twice (a degenerate element)");
  block.nodes.resize(block.nodes.size() + static_cast<std::size_t>(n_nodes_of(fo.type, fo.order) - n), -1);
  block.physical.push_back(physical);
  block.entity.push_back(entity);
}

FamilyOrder MshState::element_type(int code, std::size_t at) const {
  const auto fo = from_gmsh_type(code);
  if (!fo) cur.fail_at(at, describe_unsupported_gmsh_type(code));
  return *fo;
}

namespace {

void read_physical_names(MshState& s) {
  Cursor& c = s.cur;
  const auto n = c.integer<std::uint64_t>("number of physical names");
  s.check_count(n, 6, c.token_start());
  for (std::uint64_t i = 0; i < n; ++i) {
    const int dim = c.integer<int>("physical group dimension");
    if (dim < 0 || dim > 3) c.fail_at(c.token_start(), "physical group dimension must be 0..3");
    const auto tag = c.integer<std::int32_t>("physical tag");
    c.skip_blank();
    const std::string_view t = c.text();
    if (c.pos() >= t.size() || t[c.pos()] != '"') c.fail("expected a quoted physical name");
    const std::size_t open = c.pos();
    std::size_t close = open + 1;
    while (close < t.size() && t[close] != '"' && t[close] != '\n') ++close;
    if (close >= t.size() || t[close] != '"') c.fail_at(open, "missing closing quote in physical name");
    const std::string_view name = t.substr(open + 1, close - open - 1);
    if (const auto bad = group_name_problem(name)) c.fail_at(open, "physical name " + *bad);
    s.builder.named_groups.push_back(PhysicalGroup{dim, tag, std::string(name)});
    c.seek(close + 1);
  }
}

void read_mesh_format(MshState& s, int& version) {
  Cursor& c = s.cur;
  const std::string_view v = c.token("MSH version");
  const std::size_t at = c.token_start();
  if (v == "4.1") {
    version = 41;
  } else if (v == "2.2" || v == "2.1" || v == "2.0" || v == "2") {
    version = 22;
  } else if (v == "4" || v == "4.0") {
    c.fail_at(at, "MSH 4.0 is not supported; save the mesh as MSH 4.1 or 2.2 (gmsh -format msh41)");
  } else {
    c.fail_at(at, "unsupported MSH version '" + Cursor::shorten(v) + "' (4.1 and 2.2 are read)");
  }
  const int file_type = c.integer<int>("file type");
  if (file_type != 0 && file_type != 1) c.fail_at(c.token_start(), "file type must be 0 (ASCII) or 1 (binary)");
  const int data_size = c.integer<int>("data size");
  if (data_size != 8) c.fail_at(c.token_start(), "data size must be 8");
  s.binary = file_type == 1;
  if (s.binary) {
    c.skip_line();
    c.binary = true;
    if (c.raw<std::int32_t>("endianness marker") != 1)
      c.fail_at(c.pos() - 4, "binary MSH with a foreign byte order is not supported");
    c.binary = false;
  }
}

void skip_section(Cursor& c, std::string_view name, std::size_t at) {
  const std::string end = "$End" + std::string(name);
  const std::size_t found = c.text().find(end, c.pos());
  if (found == std::string_view::npos) c.fail_at(at, "section $" + std::string(name) + " has no " + end);
  c.seek(found);
}

}  // namespace
}  // namespace detail

Mesh read_msh(const std::filesystem::path& path) { return parse_msh(detail::read_file(path), path); }

Mesh parse_msh(std::string_view data, const std::filesystem::path& path) {
  detail::MshState s{detail::Cursor(path, data), {}, {}, false, false, {}, {}, {}};
  detail::Cursor& c = s.cur;
  if (!c.skip_space()) c.fail_at(0, "empty file");
  c.expect("$MeshFormat");
  int version = 0;
  detail::read_mesh_format(s, version);
  c.expect("$EndMeshFormat");
  while (c.skip_space()) {
    const std::string_view tok = c.token("a section");
    const std::size_t at = c.token_start();
    if (tok.size() < 2 || tok[0] != '$' || tok.starts_with("$End"))
      c.fail_at(at, "expected a section start ($Name), got '" + detail::Cursor::shorten(tok) + "'");
    const std::string_view name = tok.substr(1);
    if (name == "MeshFormat") c.fail_at(at, "second $MeshFormat section");
    if (name == "PhysicalNames") {
      detail::read_physical_names(s);
    } else if (name == "Entities" && version == 41) {
      detail::read_msh41_entities(s);
    } else if (name == "PartitionedEntities" && version == 41) {
      detail::read_msh41_partitioned_entities(s);
    } else if (name == "Nodes") {
      if (s.have_nodes) c.fail_at(at, "second $Nodes section");
      version == 41 ? detail::read_msh41_nodes(s) : detail::read_msh22_nodes(s);
      s.index_nodes(at);
    } else if (name == "ParametricNodes" && version == 22) {  // $Nodes with each node's entity and parameters
      if (s.have_nodes) c.fail_at(at, "second $Nodes section");
      if (s.binary) c.fail_at(at, "binary $ParametricNodes is not supported (save without Mesh.SaveParametric)");
      detail::read_msh22_nodes(s, true);
      s.index_nodes(at);
    } else if (name == "NodeData") {
      if (!s.have_nodes) c.fail_at(at, "$NodeData before $Nodes");
      detail::read_node_data(s, at);
    } else if (name == "Elements") {
      if (!s.have_nodes) c.fail_at(at, "$Elements before $Nodes");
      version == 41 ? detail::read_msh41_elements(s) : detail::read_msh22_elements(s);
    } else {
      detail::skip_section(c, name, at);
    }
    // After binary data, the end marker is located by byte offset.
    c.binary = s.binary && (name == "Nodes" || name == "Elements" || name == "Entities" || name == "PartitionedEntities" ||
                            name == "NodeData");
    c.expect("$End" + std::string(name));
    c.binary = false;
  }
  detail::finish_node_data(s);
  return s.builder.finish(c.where(data.size()), path);
}

}  // namespace meshmorph

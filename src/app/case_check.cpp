// SPDX-License-Identifier: MIT
#include <algorithm>
#include <cstdint>
#include <string>
#include <type_traits>
#include <vector>

#include "app/detail/json_reader.h"
#include "meshmorph/app/case_file.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/orientation.h"
#include "meshmorph/io/foam.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph {

using detail::JsonWhere;

namespace {

class MeshChecker {
 public:
  MeshChecker(const CaseFile& c, const Mesh& mesh) : c_(c), mesh_(mesh) {}

  void vector(const CaseVector& v, const JsonWhere& w) const {
    if (v.size() != mesh_.dim)
      w.fail("expected " + std::to_string(mesh_.dim) + " numbers for a " + std::to_string(mesh_.dim) +
             "D mesh, found " + std::to_string(v.size()));
  }

  void only_3d(const JsonWhere& w, const char* what) const {
    if (mesh_.dim != 3) w.fail(std::string(what) + " exists only in 3D; the mesh is 2D");
  }

  void level_set(const LevelSet& ls) const {
    const JsonWhere base{c_.file.string(), ls.key_path};
    std::visit(
        [&](const auto& s) {
          using S = std::decay_t<decltype(s)>;
          if constexpr (std::is_same_v<S, SphereLevelSet>) {
            vector(s.center, base.key("sphere").key("center"));
          } else if constexpr (std::is_same_v<S, CylinderLevelSet>) {
            only_3d(base.key("cylinder"), "an infinite cylinder");
            vector(s.center, base.key("cylinder").key("center"));
            vector(s.axis, base.key("cylinder").key("axis"));
          } else if constexpr (std::is_same_v<S, PlaneLevelSet>) {
            vector(s.point, base.key("plane").key("point"));
            vector(s.normal, base.key("plane").key("normal"));
          } else if constexpr (std::is_same_v<S, BoxLevelSet>) {
            vector(s.center, base.key("box").key("center"));
            vector(s.size, base.key("box").key("size"));
          } else if constexpr (std::is_same_v<S, TorusLevelSet>) {
            only_3d(base.key("torus"), "a torus");
            vector(s.center, base.key("torus").key("center"));
            vector(s.axis, base.key("torus").key("axis"));
          } else if constexpr (std::is_same_v<S, UnionLevelSet> || std::is_same_v<S, IntersectionLevelSet> ||
                               std::is_same_v<S, DifferenceLevelSet>) {
            for (const auto& operand : s.operands) level_set(operand);
          } else if constexpr (std::is_same_v<S, DistanceLevelSet>) {
            vector(s.lower, base.key("distance").key("lower"));
            vector(s.upper, base.key("distance").key("upper"));
            for (const auto& operand : s.operands) level_set(operand);
          }
        },
        ls.shape);
  }

  // Every row is a node of the entry's group: a row elsewhere (a node of a fixed group, an
  // interior node) is a mistake in the table, not something to apply or to ignore.
  void displacement(const DisplacementTable& t, const BoundaryCondition& bc, const JsonWhere& w) const {
    if (t.displacement.rows() != mesh_.dim)
      w.fail(t.file.string() + ": expected " + std::to_string(mesh_.dim) + " displacement components per row for a " +
             std::to_string(mesh_.dim) + "D mesh, found " + std::to_string(t.displacement.rows()));
    const auto index = mesh_.node_index_of_tag();
    std::vector<std::uint8_t> in_group(mesh_.n_nodes(), 0);
    for (std::int32_t v : mesh_.group_nodes(*mesh_.find_group(bc.group))) in_group[static_cast<std::size_t>(v)] = 1;
    for (std::size_t i = 0; i < t.node_tags.size(); ++i) {
      const std::int64_t tag = t.node_tags[i];
      const auto node = index.find(tag);
      const std::string where = t.file.string() + ":" + std::to_string(t.line[i]) + ": node " + std::to_string(tag);
      const std::string key = " (" + c_.file.string() + ": " + w.path + ")";
      if (node == index.end()) throw InputError(where + " is not in " + mesh_name() + key);
      if (!in_group[static_cast<std::size_t>(node->second)])
        throw InputError(where + " is not in group \"" + bc.group + "\"" + key);
    }
  }

  // A case read without its mesh (the Python module's Morpher) names it by role.
  std::string mesh_name() const { return c_.mesh.empty() ? std::string("the mesh") : c_.mesh.filename().string(); }

  void boundary(const BoundaryCondition& bc) const {
    const JsonWhere w{c_.file.string(), bc.key_path};
    if (!mesh_.find_group(bc.group)) {
      std::string known;
      for (const auto& g : mesh_.groups) {
        if (!known.empty()) known += ", ";
        known += g.name.empty() ? std::to_string(g.tag) : g.name + " (" + std::to_string(g.tag) + ")";
      }
      w.key("group").fail("no physical group \"" + bc.group + "\" in " + mesh_name() +
                          (known.empty() ? std::string(" (it has no groups)") : " (it has: " + known + ")"));
    }
    // A name in $PhysicalNames that no element carries (an MSH 4.1 file without $Entities,
    // where elements get their groups): a motion of it would move nothing.
    if (mesh_.group_nodes(*mesh_.find_group(bc.group)).empty())
      w.key("group").fail("physical group \"" + bc.group + "\" of " + mesh_name() +
                          " has no elements: no element of the mesh carries its tag");
    std::visit(
        [&](const auto& m) {
          using M = std::decay_t<decltype(m)>;
          if constexpr (std::is_same_v<M, TranslateMotion>) {
            vector(m.displacement, w.key("translate"));
          } else if constexpr (std::is_same_v<M, RotateMotion>) {
            vector(m.center, w.key("rotate").key("center"));
            if (mesh_.dim == 3 && !m.axis) w.key("rotate").fail("missing key \"axis\" (needed in 3D)");
            if (mesh_.dim == 2 && m.axis) w.key("rotate").key("axis").fail("a 2D rotation takes no axis");
          } else if constexpr (std::is_same_v<M, ScaleMotion>) {
            vector(m.center, w.key("scale").key("center"));
          } else if constexpr (std::is_same_v<M, ProjectMotion>) {
            level_set(m.target);
          } else if constexpr (std::is_same_v<M, DisplaceMotion>) {
            displacement(m.table, bc, w.key("displace").key("file"));
          }
        },
        bc.motion);
  }

 private:
  const CaseFile& c_;
  const Mesh& mesh_;
};

}  // namespace

void check_case_against_mesh(const CaseFile& c, const Mesh& mesh) {
  const MeshChecker check(c, mesh);
  if (c.order) {
    const JsonWhere w{c.file.string(), "order"};
    if (*c.order < mesh.order())
      w.fail("the mesh is of order " + std::to_string(mesh.order()) + "; order cannot be lowered to " +
             std::to_string(*c.order));
    for (const auto& block : mesh.cells)
      if (*c.order > max_order_of(block.type))
        w.fail("order " + std::to_string(*c.order) + " is above the highest for " + std::string(name_of(block.type)) +
               " cells (" + std::to_string(max_order_of(block.type)) + ")");
  }
  for (const auto& bc : c.boundary) check.boundary(bc);
  if (c.interface) check.level_set(*c.interface);
  if (c.trim) check.level_set(*c.trim);
  // Found before the run rather than by the writer after it.
  const int order = std::max(mesh.order(), c.order.value_or(1));
  if (c.output && c.output_each_step && is_foam_time_folder(*c.output))
    JsonWhere{c.file.string(), "output_each_step"}.fail("an OpenFOAM time folder holds one time: morph into one "
                                                        "time folder a run, or write the steps as .vtu or .msh");
  if (c.output && (c.output->extension() == ".mesh" || c.output->extension() == ".su2") && order > 1)
    JsonWhere{c.file.string(), "output"}.fail((c.output->extension() == ".su2" ? "SU2 .su2" : "Medit .mesh") +
                                              std::string(" holds linear cells only; the result is of order ") +
                                              std::to_string(order) + " (write .msh or .vtu)");
  const std::string ext = c.output ? c.output->extension().string() : "";
  if ((ext == ".exo" || ext == ".e" || ext == ".ex2") && order > 2)
    JsonWhere{c.file.string(), "output"}.fail("Exodus II holds cells of orders 1 and 2; the result is of order " +
                                              std::to_string(order) + " (write .cgns, .msh or .vtu)");
}

std::size_t orient_cells(const CaseFile& c, Mesh& mesh) {
  if (mesh.n_cells() == 0) return 0;
  return orient_cells(c, mesh, build_topology(mesh, TopologyParts::Facets));
}

std::size_t orient_cells(const CaseFile& c, Mesh& mesh, const Topology& topology) {
  if (mesh.n_cells() == 0) return 0;
  const CellOrientation o = cell_orientation(mesh, topology, signed_volumes(mesh));
  const std::string where = c.mesh.empty() ? c.file.string() + ": the mesh" : c.mesh.string();
  if (o.twisted_cell >= 0)
    throw InputError(where + ": no orientation fits the cells around cell " + std::to_string(o.twisted_cell) +
                     " (a non-orientable mesh cannot be placed without overlapping itself)");
  if (o.flipped.empty()) return 0;
  if (!c.reorient) {
    const std::size_t n = o.flipped.size();
    const std::size_t b = topology.locate(o.flipped.front()).first;
    throw InputError(where + ": " + std::to_string(n) + (n > 1 ? " cells are" : " cell is") +
                     " listed mirrored against " + (n > 1 ? "their" : "its") + " neighbours, first cell " +
                     std::to_string(o.flipped.front()) + " (a " + std::string(name_of(mesh.cells[b].type)) +
                     "; cells counted from 0 as `quality -o` writes them): the mesh folds over itself there; fix its "
                     "node order or pass --reorient (case key \"reorient\")");
  }
  mirror_cells(mesh, topology, o.flipped);
  return o.flipped.size();
}

}  // namespace meshmorph

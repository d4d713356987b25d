// SPDX-License-Identifier: MIT
#include <exodusII.h>

#include <algorithm>
#include <string>
#include <vector>

#include "io/detail/exodus_writer.h"
#include "io/detail/library_file.h"
#include "meshmorph/error.h"
#include "meshmorph/io/exodus.h"

namespace meshmorph {
namespace {

// The nodal variables' names, each vector's components in a row: displacement_x, ….
struct Nodal {
  std::vector<std::string> vectors;  // the point vectors written, in order
  std::vector<std::string> names;    // their components
};

Nodal nodal_names(const Mesh& mesh, const MeshStep& s, bool motion) {
  static const char* const axes[] = {"_x", "_y", "_z"};
  Nodal n;
  if (motion) n.vectors.push_back("displacement");
  for (const auto& [name, v] : s.point_vectors)
    if (!motion || name != "displacement") n.vectors.push_back(name);
  for (const std::string& v : n.vectors)
    for (int k = 0; k < mesh.dim; ++k) {
      n.names.push_back(v + axes[k]);
      if (n.names.back().size() > MAX_STR_LENGTH)
        throw InputError("field name '" + v + "' is too long for an Exodus II variable (" + n.names.back() + ": over 32 characters)");
    }
  return n;
}

void put_variable_names(const detail::ExodusFile& f, ex_entity_type type, const std::vector<std::string>& names,
                        const std::string& where) {
  if (names.empty()) return;
  f.check(ex_put_variable_param(f.id(), type, static_cast<int>(names.size())), where);
  detail::ExodusNames c(names);
  f.check(ex_put_variable_names(f.id(), type, static_cast<int>(names.size()), c.ptrs.data()), where);
}

}  // namespace

void detail::write_exodus_steps(const ExodusFile& f, const Mesh& mesh, const std::vector<ExodusBlock>& blocks, int n_steps,
                                const std::function<MeshStep(int)>& step, bool motion) {
  if (n_steps < 1) return;
  MeshStep s = step(0);
  const Nodal nodal = nodal_names(mesh, s, motion);
  std::vector<std::string> element;
  for (const auto& [name, values] : s.cell_data) {
    if (name.size() > MAX_STR_LENGTH) throw InputError("field name '" + name + "' is over the 32 characters of an Exodus II variable");
    element.push_back(name);
  }
  put_variable_names(f, EX_NODAL, nodal.names, "nodal variable names");
  put_variable_names(f, EX_ELEM_BLOCK, element, "element variable names");
  if (!element.empty()) {  // no cell data on the blocks of facets
    std::vector<int> table;
    for (const ExodusBlock& b : blocks) table.insert(table.end(), element.size(), b.offset >= 0 ? 1 : 0);
    f.check(ex_put_truth_table(f.id(), EX_ELEM_BLOCK, static_cast<int>(blocks.size()), static_cast<int>(element.size()), table.data()),
            "element variable truth table");
  }
  const auto n_nodes = static_cast<int64_t>(mesh.n_nodes());
  for (int k = 0; k < n_steps; ++k) {
    if (k > 0) s = step(k);
    const std::string where = "time step " + std::to_string(k + 1);
    if (nodal_names(mesh, s, motion).names != nodal.names || s.cell_data.size() != element.size() ||
        !std::equal(element.begin(), element.end(), s.cell_data.begin(), [](const std::string& a, const auto& b) { return a == b.first; }))
      throw InputError("step " + std::to_string(k + 1) + " of the series holds other fields than step 1");
    f.check(ex_put_time(f.id(), k + 1, &s.time), where);
    int index = 1;
    for (const std::string& name : nodal.vectors) {
      const Eigen::MatrixXd v = name == "displacement" && motion ? Eigen::MatrixXd(s.x - mesh.x) : s.point_vectors.at(name);
      MESHMORPH_CHECK(v.rows() == mesh.dim && v.cols() == static_cast<Eigen::Index>(n_nodes),
                      "write_exodus: point vectors '" + name + "' are not dim × n_nodes");
      for (int d = 0; d < mesh.dim; ++d) {
        const Eigen::VectorXd c = v.row(d).transpose();
        f.check(ex_put_var(f.id(), k + 1, EX_NODAL, index++, 1, n_nodes, c.data()), where + ": nodal variables");
      }
    }
    index = 1;
    for (const auto& [name, values] : s.cell_data) {
      MESHMORPH_CHECK(values.size() == mesh.n_cells(), "write_exodus: cell_data '" + name + "' has " + std::to_string(values.size()) +
                                                           " values for " + std::to_string(mesh.n_cells()) + " cells");
      for (std::size_t i = 0; i < blocks.size(); ++i) {
        const ExodusBlock& b = blocks[i];
        if (b.offset < 0) continue;
        std::vector<double> block_values;
        for (std::size_t c = 0; c < b.cells->n_cells(); ++c)
          if (b.cells->physical[c] == b.tag) block_values.push_back(values[static_cast<std::size_t>(b.offset) + c]);
        f.check(ex_put_var(f.id(), k + 1, EX_ELEM_BLOCK, index, static_cast<int>(i) + 1, static_cast<int64_t>(block_values.size()),
                           block_values.data()),
                where + ": element variable " + name);
      }
      ++index;
    }
  }
}

void write_exodus_series(const std::filesystem::path& file, const Mesh& mesh, int n_steps,
                         const std::function<MeshStep(int)>& step, const std::filesystem::path& shown) {
  const std::lock_guard lock(detail::library_mutex());
  const detail::ExodusFile f(file, true, shown.string());
  const std::vector<detail::ExodusBlock> blocks = detail::write_exodus_mesh(f, mesh);
  detail::write_exodus_steps(f, mesh, blocks, n_steps, step, true);
}

}  // namespace meshmorph

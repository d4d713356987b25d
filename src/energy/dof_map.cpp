// SPDX-License-Identifier: MIT
#include "meshmorph/energy/dof_map.h"

#include <limits>
#include <string>

#include "meshmorph/error.h"
#include "meshmorph/fem/trace.h"

namespace meshmorph {

DofMap DofMap::from_mask(int dim, std::span<const std::uint8_t> fixed) {
  MESHMORPH_CHECK(dim == 2 || dim == 3, "DofMap: dim must be 2 or 3");
  MESHMORPH_CHECK(fixed.size() % static_cast<std::size_t>(dim) == 0, "DofMap: the mask size must be dim · n_nodes");
  MESHMORPH_CHECK(fixed.size() < static_cast<std::size_t>(std::numeric_limits<std::int32_t>::max()),
                  "DofMap: too many DOFs for 32-bit indices");
  DofMap map;
  map.dim_ = dim;
  const std::size_t n_nodes = fixed.size() / static_cast<std::size_t>(dim);
  map.reduced_.resize(fixed.size());
  map.first_.resize(n_nodes + 1);
  std::int32_t next = 0;
  for (std::size_t i = 0; i < n_nodes; ++i) {
    map.first_[i] = next;
    for (int k = 0; k < dim; ++k) {
      const std::size_t dof = i * static_cast<std::size_t>(dim) + static_cast<std::size_t>(k);
      if (fixed[dof]) {
        map.reduced_[dof] = -1;
      } else {
        map.reduced_[dof] = next++;
        map.free_.push_back(static_cast<std::int32_t>(dof));
      }
    }
  }
  map.first_[n_nodes] = next;
  return map;
}

DofMap DofMap::all_free(int dim, std::size_t n_nodes) {
  const std::vector<std::uint8_t> mask(n_nodes * static_cast<std::size_t>(dim), 0);
  return from_mask(dim, mask);
}

DofMap DofMap::fixing_nodes(int dim, std::size_t n_nodes, std::span<const std::int32_t> fixed_nodes) {
  std::vector<std::uint8_t> mask(n_nodes * static_cast<std::size_t>(dim), 0);
  for (std::int32_t v : fixed_nodes) {
    MESHMORPH_CHECK(v >= 0 && static_cast<std::size_t>(v) < n_nodes,
                    "DofMap: fixed node " + std::to_string(v) + " is out of range");
    for (int k = 0; k < dim; ++k) mask[static_cast<std::size_t>(v) * static_cast<std::size_t>(dim) + static_cast<std::size_t>(k)] = 1;
  }
  return from_mask(dim, mask);
}

DofMap DofMap::fixing_boundary(const Mesh& mesh, const Topology& topology) {
  const std::vector<std::int32_t> boundary = boundary_nodes(mesh, topology);
  return fixing_nodes(mesh.dim, mesh.n_nodes(), boundary);
}

Eigen::VectorXd DofMap::restrict(const Eigen::Ref<const Eigen::VectorXd>& full) const {
  MESHMORPH_CHECK(static_cast<std::size_t>(full.size()) == n_dofs(), "DofMap::restrict: size must be n_dofs()");
  Eigen::VectorXd out(static_cast<Eigen::Index>(free_.size()));
  for (std::size_t r = 0; r < free_.size(); ++r) out[static_cast<Eigen::Index>(r)] = full[free_[r]];
  return out;
}

void DofMap::add_step(const Eigen::Ref<const Eigen::VectorXd>& step, double alpha, Eigen::MatrixXd& x) const {
  MESHMORPH_CHECK(static_cast<std::size_t>(step.size()) == n_free(), "DofMap::add_step: size must be n_free()");
  MESHMORPH_CHECK(x.rows() == dim_ && static_cast<std::size_t>(x.cols()) == n_nodes(),
                  "DofMap::add_step: x must be dim × n_nodes");
  double* data = x.data();  // column-major dim × n: entry dof = dim·node + k
  for (std::size_t r = 0; r < free_.size(); ++r) data[free_[r]] += alpha * step[static_cast<Eigen::Index>(r)];
}

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#pragma once
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "io/detail/exodus_file.h"
#include "meshmorph/io/mesh_series.h"
#include "meshmorph/mesh/mesh.h"

namespace meshmorph::detail {

/// An element block of an Exodus file: the cells of `cells` in group `tag`.
struct ExodusBlock {
  const CellBlock* cells;
  std::int32_t tag;
  int first = 0;            ///< global number of its first element (1-based)
  std::ptrdiff_t offset = 0;  ///< of `cells`' first cell in Mesh::cells (blocks concatenated); −1: facets
};

/// `names` as the array of C strings the Exodus calls take, valid while this lives.
struct ExodusNames {
  explicit ExodusNames(const std::vector<std::string>& names);
  std::vector<std::vector<char>> buffers;
  std::vector<char*> ptrs;
};

/// Writes `mesh` into the open file `f` as write_exodus lays it out (coordinates = mesh.x);
/// returns its element blocks, ids 1, 2, … in order.
std::vector<ExodusBlock> write_exodus_mesh(const ExodusFile& f, const Mesh& mesh);

/// Writes `n_steps` time steps (ex_put_time) of the fields of `step(k)`, k = 0 … n_steps − 1:
/// with `motion`, first the nodal variables displacement_x/_y(/_z) = step.x − mesh.x (a point
/// vector named displacement is that motion and not written again); each point vector as the
/// nodal variables <name>_x/_y(/_z), each cell data array as an element variable of the cell
/// blocks (none on the blocks of facets: the truth table). Throws InputError for a variable
/// name over 32 characters or a step whose fields differ from the first's.
void write_exodus_steps(const ExodusFile& f, const Mesh& mesh, const std::vector<ExodusBlock>& blocks, int n_steps,
                        const std::function<MeshStep(int)>& step, bool motion);

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#pragma once
#include <string>
#include <vector>

#include <Eigen/Core>

#include "meshmorph/mesh/topology.h"
#include "meshmorph/parallel/local_mesh.h"

namespace meshmorph {

/// The rank of each cell (global order) for mpi_size() ranks, from PETSc's MatPartitioning of
/// the cells' graph, cells joined across shared facets (`topology`'s cell_neighbors), on rank
/// 0 alone: rank 0 passes the whole mesh's topology and gets the assignment, the same for the
/// same mesh and number of ranks; the other ranks pass nullptr and get an empty vector. One
/// rank: every cell on it, without PETSc. `partitioner` gets the MatPartitioning type used on
/// rank 0: "ptscotch" unless PETSC_OPTIONS names another (-mat_partitioning_type), "none" on
/// one rank and on the other ranks. Throws std::runtime_error when PETSc fails.
std::vector<int> partition_cells(const Topology* topology, std::string& partitioner);

/// Collective: rank 0 passes one LocalMesh per rank (split_mesh), the others an empty
/// vector; every rank gets its own.
LocalMesh scatter_local_meshes(std::vector<LocalMesh> parts);

/// Collective: the coordinates of every rank's owned nodes (`x`: d × local nodes) into
/// `global` on rank 0 (d × global nodes; columns that no rank owns keep their values).
/// `global` is ignored on the other ranks.
void gather_owned_nodes(const LocalMesh& local, const Eigen::MatrixXd& x, Eigen::MatrixXd* global);

}  // namespace meshmorph

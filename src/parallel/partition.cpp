// SPDX-License-Identifier: MIT
#include "meshmorph/parallel/partition.h"

#include <cstdint>
#include <cstdlib>
#include <string>

#include <petscmat.h>
#include <scotch/scotch.h>

#include "meshmorph/parallel/ranks.h"
#include "meshmorph/solve/petsc_runtime.h"

namespace meshmorph {
namespace {

// A LocalMesh as two flat arrays, integers and coordinates, for one message each.
struct Packed {
  std::vector<std::int64_t> ints;
  std::vector<double> reals;
};

template <class T>
void put(std::vector<std::int64_t>& out, const std::vector<T>& v) {
  out.push_back(static_cast<std::int64_t>(v.size()));
  out.insert(out.end(), v.begin(), v.end());
}

Packed pack(const LocalMesh& m) {
  Packed p;
  std::vector<std::int64_t>& o = p.ints;
  o = {m.rank, m.mesh.dim, static_cast<std::int64_t>(m.mesh.cells.size())};
  for (std::size_t b = 0; b < m.mesh.cells.size(); ++b)
    for (const CellBlock* block : {&m.mesh.cells[b], &m.ghosts[b]}) {
      o.push_back(static_cast<std::int64_t>(block->type));
      o.push_back(block->order);
      put(o, block->nodes);
      put(o, block->physical);
    }
  put(o, m.global_node);
  o.push_back(static_cast<std::int64_t>(m.n_owned_nodes));
  put(o, m.fixed);
  put(o, m.global_free);
  o.insert(o.end(), {m.n_owned_free, m.first_owned_free, m.n_global_free});
  p.reals.assign(m.mesh.x.data(), m.mesh.x.data() + m.mesh.x.size());
  return p;
}

struct Reader {
  const std::vector<std::int64_t>& in;
  std::size_t at = 0;
  std::int64_t next() { return in.at(at++); }
  template <class T>
  void get(std::vector<T>& v) {
    v.resize(static_cast<std::size_t>(next()));
    for (T& e : v) e = static_cast<T>(next());
  }
};

LocalMesh unpack(const Packed& p) {
  LocalMesh m;
  Reader r{p.ints};
  m.rank = static_cast<int>(r.next());
  m.mesh.dim = static_cast<int>(r.next());
  const auto n_blocks = static_cast<std::size_t>(r.next());
  m.mesh.cells.resize(n_blocks);
  m.ghosts.resize(n_blocks);
  for (std::size_t b = 0; b < n_blocks; ++b)
    for (CellBlock* block : {&m.mesh.cells[b], &m.ghosts[b]}) {
      block->type = static_cast<ElementType>(r.next());
      block->order = static_cast<int>(r.next());
      r.get(block->nodes);
      r.get(block->physical);
      block->entity.assign(block->physical.size(), 0);
    }
  r.get(m.global_node);
  m.n_owned_nodes = static_cast<std::size_t>(r.next());
  r.get(m.fixed);
  r.get(m.global_free);
  m.n_owned_free = static_cast<std::int32_t>(r.next());
  m.first_owned_free = static_cast<std::int32_t>(r.next());
  m.n_global_free = static_cast<std::int32_t>(r.next());
  m.mesh.x = Eigen::Map<const Eigen::MatrixXd>(p.reals.data(), m.mesh.dim, static_cast<Eigen::Index>(m.global_node.size()));
  return m;
}

}  // namespace

std::vector<int> partition_cells(const Topology* topology, std::string& partitioner) {
  partitioner = "none";
  if (mpi_rank() != 0) return {};
  const auto n_cells = static_cast<PetscInt>(topology->block_offset.back());
  if (mpi_size() == 1) return std::vector<int>(static_cast<std::size_t>(n_cells), 0);
  // Rank 0 holds the whole graph and partitions it alone: PT-Scotch spread over ranks with
  // all the vertices on one gave another partition from run to run.
  PetscInt* ia = nullptr;
  PetscInt* ja = nullptr;
  std::size_t n_edges = 0;
  for (const std::int32_t c : topology->cell_neighbors) n_edges += c >= 0 ? 1 : 0;
  check_petsc(PetscMalloc1(n_cells + 1, &ia), "allocation");
  check_petsc(PetscMalloc1(n_edges + 1, &ja), "allocation");
  ia[0] = 0;
  for (PetscInt c = 0; c < n_cells; ++c) {
    ia[c + 1] = ia[c];
    for (auto k = topology->cell_neighbor_offset[c]; k < topology->cell_neighbor_offset[c + 1]; ++k)
      if (topology->cell_neighbors[k] >= 0) ja[ia[c + 1]++] = topology->cell_neighbors[k];
  }
  Mat adjacency = nullptr;  // takes ia and ja over
  check_petsc(MatCreateMPIAdj(PETSC_COMM_SELF, n_cells, n_cells, ia, ja, nullptr, &adjacency), "cell graph set-up");
  // The same partition for the same graph: Scotch 7's threads share out its work differently
  // from run to run (unless the user chose their number), and it seeds its random generator
  // with a fixed value only where told to.
  setenv("SCOTCH_PTHREAD_NUMBER", "1", 0);
  SCOTCH_randomSeed(1);
  SCOTCH_randomReset();
  MatPartitioning part = nullptr;
  IS assignment = nullptr;
  PetscErrorCode e = MatPartitioningCreate(PETSC_COMM_SELF, &part);
  if (e == 0) e = MatPartitioningSetAdjacency(part, adjacency);
  if (e == 0) e = MatPartitioningSetNParts(part, mpi_size());
  if (e == 0) e = MatPartitioningSetType(part, MATPARTITIONINGPTSCOTCH);
  if (e == 0) e = MatPartitioningSetFromOptions(part);
  if (e == 0) e = MatPartitioningApply(part, &assignment);
  MatPartitioningType type = nullptr;
  if (e == 0) e = MatPartitioningGetType(part, &type);
  if (e == 0) partitioner = type;
  std::vector<int> ranks;
  const PetscInt* to = nullptr;
  if (e == 0) e = ISGetIndices(assignment, &to);
  if (e == 0) {
    ranks.assign(to, to + n_cells);
    ISRestoreIndices(assignment, &to);
  }
  ISDestroy(&assignment);
  MatPartitioningDestroy(&part);
  MatDestroy(&adjacency);
  check_petsc(e, "partitioning");
  return ranks;
}

LocalMesh scatter_local_meshes(std::vector<LocalMesh> parts) {
  const int size = mpi_size();
  if (!on_ranks() || size == 1) return std::move(parts.at(0));
  if (mpi_rank() == 0) {
    for (int r = 1; r < size; ++r) {
      const Packed p = pack(parts.at(static_cast<std::size_t>(r)));
      const std::int64_t sizes[2] = {static_cast<std::int64_t>(p.ints.size()), static_cast<std::int64_t>(p.reals.size())};
      MPI_Send(sizes, 2, MPI_INT64_T, r, 0, PETSC_COMM_WORLD);
      MPI_Send(p.ints.data(), static_cast<int>(p.ints.size()), MPI_INT64_T, r, 1, PETSC_COMM_WORLD);
      MPI_Send(p.reals.data(), static_cast<int>(p.reals.size()), MPI_DOUBLE, r, 2, PETSC_COMM_WORLD);
    }
    return std::move(parts.at(0));
  }
  std::int64_t sizes[2] = {0, 0};
  MPI_Recv(sizes, 2, MPI_INT64_T, 0, 0, PETSC_COMM_WORLD, MPI_STATUS_IGNORE);
  Packed p;
  p.ints.resize(static_cast<std::size_t>(sizes[0]));
  p.reals.resize(static_cast<std::size_t>(sizes[1]));
  MPI_Recv(p.ints.data(), static_cast<int>(sizes[0]), MPI_INT64_T, 0, 1, PETSC_COMM_WORLD, MPI_STATUS_IGNORE);
  MPI_Recv(p.reals.data(), static_cast<int>(sizes[1]), MPI_DOUBLE, 0, 2, PETSC_COMM_WORLD, MPI_STATUS_IGNORE);
  return unpack(p);
}

void gather_owned_nodes(const LocalMesh& local, const Eigen::MatrixXd& x, Eigen::MatrixXd* global) {
  const int d = local.mesh.dim;
  const int n = static_cast<int>(local.n_owned_nodes);
  const int size = mpi_size();
  const bool root = mpi_rank() == 0;
  std::vector<int> counts(static_cast<std::size_t>(size), n), offsets(static_cast<std::size_t>(size) + 1, 0);
  if (on_ranks()) MPI_Gather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, PETSC_COMM_WORLD);
  for (int r = 0; r < size; ++r) offsets[r + 1] = offsets[r] + counts[r];
  std::vector<std::int64_t> nodes(root ? static_cast<std::size_t>(offsets[size]) : 0);
  Eigen::MatrixXd coordinates(d, root ? offsets[size] : 0);
  const Eigen::MatrixXd owned = x.leftCols(n);
  if (on_ranks()) {
    MPI_Gatherv(local.global_node.data(), n, MPI_INT64_T, nodes.data(), counts.data(), offsets.data(), MPI_INT64_T, 0,
                PETSC_COMM_WORLD);
    for (int r = 0; r < size; ++r) counts[r] *= d, offsets[r] *= d;
    MPI_Gatherv(owned.data(), d * n, MPI_DOUBLE, coordinates.data(), counts.data(), offsets.data(), MPI_DOUBLE, 0,
                PETSC_COMM_WORLD);
  } else {
    nodes.assign(local.global_node.begin(), local.global_node.begin() + n);
    coordinates = owned;
  }
  if (root)
    for (std::size_t j = 0; j < nodes.size(); ++j) global->col(nodes[j]) = coordinates.col(static_cast<Eigen::Index>(j));
}

}  // namespace meshmorph

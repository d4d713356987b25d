// SPDX-License-Identifier: MIT
#pragma once
#include <cstdint>
#include <functional>
#include <string_view>
#include <vector>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "meshmorph/fem/shape_table.h"
#include "meshmorph/mesh/topology.h"

namespace meshmorph::detail {

/// What an element kernel of a scalar problem sees of one cell of the (fixed) mesh.
struct ScalarCell {
  const std::int32_t* nodes = nullptr;  ///< n global node indices
  const ShapeTable* table = nullptr;    ///< basis values N (n × points) at the quadrature points
  std::vector<Eigen::MatrixXd> G;       ///< per point: physical gradients, n × d
  Eigen::VectorXd w;                    ///< per point: quadrature weight · det A
  double size = 0.0;                    ///< h_K / order: the cell's node spacing (SUPG, default h)
  int order = 1;
};

/// Fills the element matrix Ke (n × n, row = test function) and vector Fe (n) of one cell;
/// both arrive zeroed. Called concurrently for cells that share no node.
using ScalarKernel = std::function<void(const ScalarCell&, Eigen::MatrixXd& Ke, Eigen::VectorXd& Fe)>;

/// Assembly of scalar (one unknown per node) finite-element systems on every cell block of
/// a mesh, with the Lagrange basis of each block's type and order. The CSC pattern is
/// Topology::node_nodes and the scatter map is built once; gradients and weights are
/// precomputed per cell, so each assembly is one pass of the kernel. Parallel over a cell
/// colouring: the same bits for any thread count.
class ScalarAssembler {
 public:
  /// Throws InputError naming `method` if a cell has det A ≤ 0 at a quadrature point.
  ScalarAssembler(const Mesh& mesh, const Topology& topology, int threads, std::string_view method);
  /// A (n_nodes × n_nodes, not necessarily symmetric) and F from `kernel`.
  void assemble(const ScalarKernel& kernel, Eigen::SparseMatrix<double>& A, Eigen::VectorXd& F) const;
  /// Mean of ScalarCell::size over the cells.
  double mean_size() const { return mean_size_; }
  std::size_t n_nodes() const { return n_nodes_; }

 private:
  struct Block {
    std::vector<ScalarCell> cells;
    std::vector<std::int32_t> color_offset, order;
    std::vector<std::int32_t> scatter;  // per cell, n × n: position of (a, b) in column b
  };
  std::size_t n_nodes_ = 0;
  int threads_ = 0;
  double mean_size_ = 0.0;
  std::vector<int> outer_, inner_;
  std::vector<Block> blocks_;
};

/// Solves A u = b for the free nodes with u given (Dirichlet) on the nodes where `fixed` is
/// set: A_ff u_f = b_f − A_fd u_d. The sparse LU's ordering is analysed once and reused while
/// the matrices keep their pattern (Newton steps, components).
class DirichletSolver {
 public:
  explicit DirichletSolver(std::vector<std::uint8_t> fixed);
  /// Factorizes the free block of A; false when it is singular.
  bool factorize(const Eigen::SparseMatrix<double>& A);
  /// u: the Dirichlet values on input (free entries ignored), the solution on return.
  void solve(const Eigen::VectorXd& b, Eigen::VectorXd& u) const;
  /// The free entries of a full vector.
  Eigen::VectorXd free_part(const Eigen::VectorXd& full) const;

 private:
  std::vector<std::uint8_t> fixed_;
  std::vector<int> free_index_;  // per node: index among the free nodes, or −1
  std::vector<int> free_nodes_;
  Eigen::SparseMatrix<double> A_fd_;
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu_;
  bool analyzed_ = false;
};

}  // namespace meshmorph::detail

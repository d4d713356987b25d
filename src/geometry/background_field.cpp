// SPDX-License-Identifier: MIT
// A nodal field on a background mesh (paper 003 §3.1). Points are located through a
// uniform bucket grid over the cells' bounding boxes (about one cell per bucket). Inside a
// candidate cell the reference coordinates ξ come from the inverse of its affine map where
// the cell is affine (straight simplices, parallelepipeds: every cell of a distance field),
// else from Newton on x(ξ) = x. A point in no cell takes the cell with the nearest centroid
// (a linear scan) and its polynomial extended beyond the cell. The Hessian is that of the
// polynomial of the cell that holds x: exact on affine cells, A⁻ᵀ (Σ φ_a ∇²N_a) A⁻¹;
// elsewhere central differences of its gradient, evaluated beyond the cell where the
// stencil leaves it, so that it never straddles the kinks between cells.
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>

#include <Eigen/Dense>

#include "geometry/detail/level_set_node.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/lagrange_basis.h"

namespace meshmorph::detail {

namespace {

constexpr double kInsideTolerance = 1e-10;

struct CellRef {
  const CellBlock* block;
  std::size_t index;
  const LagrangeBasis* basis;
  std::int32_t affine;  // index into BackgroundField::affine_, -1 for a curved cell
};

// x = A ξ + b over a whole cell; `inverse` = A⁻¹.
struct AffineMap {
  Eigen::MatrixXd inverse;
  Vec origin;
};

class BackgroundField final : public LevelSetNode {
 public:
  BackgroundField(Mesh mesh, Eigen::VectorXd values) : mesh_(std::move(mesh)), values_(std::move(values)) {
    for (const auto& b : mesh_.cells)
      if (topological_dim(b.type) == mesh_.dim) {
        const LagrangeBasis* basis = &lagrange_basis(b.type, b.order);
        for (std::size_t c = 0; c < b.n_cells(); ++c) {
          CellRef cell{&b, c, basis, -1};
          if (auto map = affine_map(cell)) {
            cell.affine = static_cast<std::int32_t>(affine_.size());
            affine_.push_back(std::move(*map));
          }
          cells_.push_back(cell);
        }
      }
    build_grid();
    // The difference step's length scale ℓ: the diagonal of the mesh's bounding box.
    length_scale_ = (hi_.rowwise().maxCoeff() - lo_.rowwise().minCoeff()).norm();
    if (!(length_scale_ > 0)) length_scale_ = 1;
  }

  double value(const Vec& x) const override {
    Vec g;
    return evaluate(x, g, false);
  }
  double value_gradient(const Vec& x, Vec& g) const override { return evaluate(x, g, true); }
  Eigen::MatrixXd hessian(const Vec& x) const override {
    Vec xi;
    const CellRef c = locate(x, xi);
    if (c.affine >= 0) {
      const Eigen::MatrixXd& Ainv = affine_[static_cast<std::size_t>(c.affine)].inverse;
      const Eigen::Index d = mesh_.dim;
      const Eigen::VectorXd h = c.basis->hessians(xi).transpose() * cell_values(c);  // ∂²σ/∂ξ_k∂ξ_l at k·d + l
      const Eigen::MatrixXd H = Ainv.transpose() * h.reshaped(d, d) * Ainv;
      return (H + H.transpose()) / 2;  // exactly symmetric
    }
    const auto gradient = [&](const Vec& y) {
      Vec eta;
      invert(c, y, eta);
      return cell_gradient(c, eta);
    };
    return hessian_by_differences(gradient, x, difference_step(x, length_scale_));
  }

 private:
  Eigen::MatrixXd coordinates(const CellRef& c) const {
    const int n = c.block->n_nodes_per_cell();
    Eigen::MatrixXd X(mesh_.dim, n);
    const std::int32_t* nodes = c.block->cell(c.index);
    for (int a = 0; a < n; ++a) X.col(a) = mesh_.x.col(nodes[a]);
    return X;
  }

  // The cell's map x(ξ) when it is affine: the least-squares affine fit through its nodes,
  // kept where every node lies on it to 1e-12 of the cell's size.
  std::optional<AffineMap> affine_map(const CellRef& c) const {
    const Eigen::MatrixXd X = coordinates(c);
    const Eigen::MatrixXd& ref = c.basis->reference().nodes;
    const Eigen::Index d = mesh_.dim, n = X.cols();
    Eigen::MatrixXd R(n, d + 1);  // rows (ξ_bᵀ, 1)
    R.leftCols(d) = ref.transpose();
    R.col(d).setOnes();
    const Eigen::MatrixXd Ab = R.colPivHouseholderQr().solve(X.transpose()).transpose();  // d × (d + 1): [A b]
    const Eigen::MatrixXd A = Ab.leftCols(d);
    const double size = (X.rowwise().maxCoeff() - X.rowwise().minCoeff()).norm();
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(A);
    if (!(size > 0) || !(std::abs(lu.determinant()) > 1e-12 * std::pow(size, static_cast<double>(d))) ||
        (Ab * R.transpose() - X).cwiseAbs().maxCoeff() > 1e-12 * size)
      return std::nullopt;
    return AffineMap{lu.inverse(), Ab.col(d)};
  }

  // ξ with x(ξ) = x (the inverse affine map, or Newton from the reference centroid), and how
  // far ξ lies outside the reference element (0 inside).
  double invert(const CellRef& c, const Vec& x, Vec& xi) const {
    if (c.affine >= 0) {
      const AffineMap& map = affine_[static_cast<std::size_t>(c.affine)];
      xi.noalias() = map.inverse * (x - map.origin);
    } else {
      const Eigen::MatrixXd X = coordinates(c);
      const auto& corners = reference_element(c.block->type, 1).nodes;
      xi = corners.rowwise().mean();
      for (int it = 0; it < 30; ++it) {
        const Vec r = X * c.basis->values(xi) - x;
        const Eigen::MatrixXd J = X * c.basis->gradients(xi);
        const Vec d = J.partialPivLu().solve(r);
        if (!d.allFinite()) return std::numeric_limits<double>::infinity();
        xi -= d;
        if (d.norm() <= 1e-14 * (1 + xi.norm())) break;
      }
    }
    if (is_simplex(c.block->type)) return std::max({0.0, -xi.minCoeff(), xi.sum() - 1});
    return std::max(0.0, xi.cwiseAbs().maxCoeff() - 1);
  }

  Vec cell_values(const CellRef& c) const {
    const int n = c.block->n_nodes_per_cell();
    Vec phi(n);
    const std::int32_t* nodes = c.block->cell(c.index);
    for (int a = 0; a < n; ++a) phi(a) = values_(nodes[a]);
    return phi;
  }

  // ∇σ = J⁻ᵀ Σ φ_a ∇_ξ N_a at reference point ξ of cell c.
  Vec cell_gradient(const CellRef& c, const Vec& xi) const {
    const Eigen::MatrixXd G = c.basis->gradients(xi);
    if (c.affine >= 0) return affine_[static_cast<std::size_t>(c.affine)].inverse.transpose() * (G.transpose() * cell_values(c));
    const Eigen::MatrixXd J = coordinates(c) * G;
    return J.transpose().partialPivLu().solve(G.transpose() * cell_values(c));
  }

  double evaluate(const Vec& x, Vec& g, bool want_gradient) const {
    Vec xi;
    const CellRef c = locate(x, xi);
    if (want_gradient) g = cell_gradient(c, xi);
    return c.basis->values(xi).dot(cell_values(c));
  }

  CellRef locate(const Vec& x, Vec& xi) const {
    double best = std::numeric_limits<double>::infinity();
    CellRef found = cells_.front();
    if (const auto b = bucket_of(x)) {
      for (std::int32_t k = bucket_start_[*b]; k < bucket_start_[*b + 1]; ++k) {
        const std::size_t i = static_cast<std::size_t>(bucket_cells_[static_cast<std::size_t>(k)]);
        if ((x.array() < lo_.col(i).array()).any() || (x.array() > hi_.col(i).array()).any()) continue;
        Vec xi_c;
        const double outside = invert(cells_[i], x, xi_c);
        if (outside < best) best = outside, found = cells_[i], xi = xi_c;
        if (outside <= kInsideTolerance) return found;
      }
    }
    // Outside every cell: extrapolate from the cell with the nearest centroid.
    Eigen::Index nearest = 0;
    (centroid_.colwise() - x).colwise().squaredNorm().minCoeff(&nearest);
    found = cells_[static_cast<std::size_t>(nearest)];
    invert(found, x, xi);
    return found;
  }

  std::optional<std::size_t> bucket_of(const Vec& x) const {
    std::size_t index = 0, stride = 1;
    for (int k = 0; k < mesh_.dim; ++k) {
      const double u = (x(k) - origin_(k)) / cell_size_(k);
      if (!(u >= 0) || u >= static_cast<double>(resolution_[k])) return std::nullopt;
      index += static_cast<std::size_t>(u) * stride;
      stride *= resolution_[k];
    }
    return index;
  }

  void build_grid() {
    const int d = mesh_.dim;
    const auto n = static_cast<Eigen::Index>(cells_.size());
    lo_.resize(d, n);
    hi_.resize(d, n);
    centroid_.resize(d, n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const Eigen::MatrixXd X = coordinates(cells_[static_cast<std::size_t>(i)]);
      // Widen by 10%: the nodes' box may miss the bulge of a curved high-order cell.
      const Vec pad = 0.1 * (X.rowwise().maxCoeff() - X.rowwise().minCoeff());
      lo_.col(i) = X.rowwise().minCoeff() - pad;
      hi_.col(i) = X.rowwise().maxCoeff() + pad;
      centroid_.col(i) = X.rowwise().mean();
    }
    origin_ = lo_.rowwise().minCoeff();
    const Vec extent = (hi_.rowwise().maxCoeff() - origin_).cwiseMax(std::numeric_limits<double>::min());
    const double per_axis = std::pow(static_cast<double>(n), 1.0 / d);
    const double mean_extent = std::pow(extent.prod(), 1.0 / d);
    resolution_.assign(static_cast<std::size_t>(d), 1);
    cell_size_.resize(d);
    for (int k = 0; k < d; ++k) {
      resolution_[k] = static_cast<std::size_t>(std::clamp(std::round(per_axis * extent(k) / mean_extent), 1.0, 1024.0));
      cell_size_(k) = extent(k) / static_cast<double>(resolution_[k]) * (1 + 1e-12);
    }
    // Counting sort of (bucket, cell) pairs into CSR.
    std::size_t n_buckets = 1;
    for (auto r : resolution_) n_buckets *= r;
    std::vector<std::vector<std::int32_t>> lists(n_buckets);
    for (Eigen::Index i = 0; i < n; ++i) {
      std::vector<std::size_t> a(static_cast<std::size_t>(d)), b(static_cast<std::size_t>(d));
      for (int k = 0; k < d; ++k) {
        const double r = static_cast<double>(resolution_[k] - 1);
        a[k] = static_cast<std::size_t>(std::clamp(std::floor((lo_(k, i) - origin_(k)) / cell_size_(k)), 0.0, r));
        b[k] = static_cast<std::size_t>(std::clamp(std::floor((hi_(k, i) - origin_(k)) / cell_size_(k)), 0.0, r));
      }
      for (std::size_t u = a[0]; u <= b[0]; ++u)
        for (std::size_t v = a[1]; v <= b[1]; ++v)
          for (std::size_t w = d > 2 ? a[2] : 0; w <= (d > 2 ? b[2] : 0); ++w)
            lists[u + resolution_[0] * (v + resolution_[1] * w)].push_back(static_cast<std::int32_t>(i));
    }
    bucket_start_.assign(n_buckets + 1, 0);
    for (std::size_t b = 0; b < n_buckets; ++b)
      bucket_start_[b + 1] = bucket_start_[b] + static_cast<std::int32_t>(lists[b].size());
    bucket_cells_.reserve(static_cast<std::size_t>(bucket_start_.back()));
    for (const auto& l : lists) bucket_cells_.insert(bucket_cells_.end(), l.begin(), l.end());
  }

  Mesh mesh_;
  Eigen::VectorXd values_;
  std::vector<CellRef> cells_;  // point into mesh_.cells
  std::vector<AffineMap> affine_;
  Eigen::MatrixXd lo_, hi_, centroid_;  // d × n_cells
  Vec origin_, cell_size_;
  std::vector<std::size_t> resolution_;
  std::vector<std::int32_t> bucket_start_, bucket_cells_;
  double length_scale_ = 1;
};

}  // namespace

NodePtr make_background_field(Mesh mesh, Eigen::VectorXd values, const std::string& where) {
  if (static_cast<std::size_t>(values.size()) != mesh.n_nodes())
    throw InputError(where + ": expected one field value per node (" + std::to_string(mesh.n_nodes()) +
                     "), found " + std::to_string(values.size()));
  for (Eigen::Index i = 0; i < values.size(); ++i)
    if (!std::isfinite(values(i))) {
      const auto node = static_cast<std::size_t>(i);
      throw InputError(where + ": the value at node " +
                       (mesh.node_tags.size() == mesh.n_nodes() ? std::to_string(mesh.node_tags[node])
                                                                : "index " + std::to_string(node)) +
                       " is not finite (" + std::to_string(values(i)) + ")");
    }
  bool has_cells = false;
  for (const auto& b : mesh.cells) has_cells |= topological_dim(b.type) == mesh.dim && b.n_cells() > 0;
  if (!has_cells) throw InputError(where + ": the background mesh has no cells");
  return std::make_shared<BackgroundField>(std::move(mesh), std::move(values));
}

}  // namespace meshmorph::detail

// SPDX-License-Identifier: MIT
#include "meshmorph/energy/slide_constraints.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>

#include "meshmorph/energy/block_offsets.h"
#include "meshmorph/error.h"
#include "meshmorph/quality/spd_projection.h"
#include "meshmorph/threads.h"

namespace meshmorph {
namespace {

// Modified Gram–Schmidt; two normals are never parallel at a node the caller let slide on a curve.
template <int d>
Eigen::Matrix<double, d, Eigen::Dynamic> orthonormal(Eigen::Matrix<double, d, Eigen::Dynamic> N) {
  for (Eigen::Index i = 0; i < N.cols(); ++i) {
    for (Eigen::Index j = 0; j < i; ++j) N.col(i) -= N.col(j).dot(N.col(i)) * N.col(j);
    N.col(i).normalize();
  }
  return N;
}

}  // namespace

Eigen::MatrixXd tangent_basis(const Eigen::VectorXd& n) {
  if (n.size() == 2) return Eigen::Vector2d(-n[1], n[0]);
  Eigen::Index axis = 0;  // the coordinate axis least aligned with n
  n.cwiseAbs().minCoeff(&axis);
  const Eigen::Vector3d nn = n;
  const Eigen::Vector3d t1 = nn.cross(Eigen::Vector3d::Unit(axis)).normalized();
  Eigen::MatrixXd T(3, 2);
  T.col(0) = t1;
  T.col(1) = nn.cross(t1);
  return T;
}

template <int d>
SlideConstraints<d>::SlideConstraints(const std::vector<FitTerm>& slides, const DofMap& dofs) : dofs_(&dofs) {
  std::vector<int> slot(dofs.n_nodes(), -1);
  for (const FitTerm& t : slides) {
    const auto i = static_cast<std::int32_t>(sigma_.size());
    sigma_.push_back(t.sigma);
    for (std::int32_t node : t.nodes) {
      int& k = slot[static_cast<std::size_t>(node)];
      if (k < 0) {
        k = static_cast<int>(nodes_.size());
        nodes_.push_back({node, dofs.first(static_cast<std::size_t>(node)), 0, {}});
      }
      Node& sn = nodes_[static_cast<std::size_t>(k)];
      MESHMORPH_CHECK(sn.m < d - 1, "SlideConstraints: a slide node lies on d constraints (fix it instead)");
      MESHMORPH_CHECK(dofs.first(static_cast<std::size_t>(node) + 1) - sn.first == d, "SlideConstraints: a slide node has a fixed DOF");
      sn.sigma[static_cast<std::size_t>(sn.m++)] = i;
    }
  }
  slot_of_row_.assign(dofs.n_free(), -1);
  for (std::size_t k = 0; k < nodes_.size(); ++k) slot_of_row_[static_cast<std::size_t>(nodes_[k].first)] = static_cast<std::int32_t>(k);
}

template <int d>
std::vector<std::int32_t> SlideConstraints<d>::nodes() const {
  std::vector<std::int32_t> out;
  out.reserve(nodes_.size());
  for (const Node& s : nodes_) out.push_back(s.node);
  return out;
}

template <int d>
Eigen::Matrix<double, d, Eigen::Dynamic> SlideConstraints<d>::normals(const Node& s, const Eigen::MatrixXd& x) const {
  Eigen::Matrix<double, d, Eigen::Dynamic> N(d, s.m);
  for (int i = 0; i < s.m; ++i) N.col(i) = sigma_[static_cast<std::size_t>(s.sigma[static_cast<std::size_t>(i)])].gradient(x.col(s.node));
  return orthonormal<d>(std::move(N));
}

template <int d>
bool SlideConstraints<d>::project(Eigen::MatrixXd& x, int threads) const {
  bool ok = true;
  const auto n = static_cast<std::ptrdiff_t>(nodes_.size());
#pragma omp parallel for num_threads(resolve_threads(threads)) reduction(&& : ok) schedule(static)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const Node& s = nodes_[static_cast<std::size_t>(k)];
    Eigen::Matrix<double, d, 1> p = x.col(s.node);
    // Gauss–Newton on σ_i(p) = 0 with minimal-norm corrections −Jᵀ(JJᵀ)⁻¹σ: one step for planes,
    // and a sphere's exact closest point in one step too (σ is the distance, ∇σ radial).
    bool done = false;
    for (int it = 0; it < 50 && !done; ++it) {
      Eigen::Matrix<double, Eigen::Dynamic, d> J(s.m, d);
      Eigen::VectorXd r(s.m);
      for (int i = 0; i < s.m; ++i) {
        const LevelSetPoint at = sigma_[static_cast<std::size_t>(s.sigma[static_cast<std::size_t>(i)])].at(p);
        r[i] = at.value();
        J.row(i) = at.gradient().transpose();
      }
      const Eigen::Matrix<double, d, 1> dx = -J.transpose() * (J * J.transpose()).ldlt().solve(r);
      if (!dx.allFinite()) break;
      p += dx;
      done = dx.norm() <= 1e-15 * std::max(1.0, p.norm());
    }
    ok = ok && done;
    x.col(s.node) = p;
  }
  return ok;
}

template <int d>
typename SlideConstraints<d>::Frame SlideConstraints<d>::frame(const Node& s, const Eigen::MatrixXd& x,
                                                               const Eigen::Matrix<double, d, d>& B,
                                                               const Eigen::Matrix<double, d, 1>& g, HessianMode mode) const {
  Frame f;
  const Eigen::Matrix<double, d, 1> p = x.col(s.node);
  // Each level set's questions in a row: a facet surface answers them from one search.
  Eigen::Matrix<double, d, Eigen::Dynamic> J(d, s.m);  // the ∇σ_i
  std::array<Eigen::Matrix<double, d, d>, 2> curvature;  // the ∇²σ_i
  std::optional<LevelSetPoint> first;
  for (std::size_t i = 0; i < static_cast<std::size_t>(s.m); ++i) {
    const LevelSetPoint at = sigma_[static_cast<std::size_t>(s.sigma[i])].at(p);
    J.col(static_cast<Eigen::Index>(i)) = at.gradient();
    curvature[i] = at.hessian();
    if (i == 0) first = at;
  }
  // One surface: its level set says which normals bind the step (more at a crease it keeps to).
  if (s.m == 1) f.N = first->step_normals(g);
  else f.N = orthonormal<d>(J);
  f.P = Eigen::Matrix<double, d, d>::Identity() - f.N * f.N.transpose();
  const Eigen::VectorXd lambda = (J.transpose() * J).ldlt().solve(J.transpose() * g);
  Eigen::Matrix<double, d, d> K = Eigen::Matrix<double, d, d>::Zero();
  for (int i = 0; i < s.m && f.N.cols() == s.m; ++i) {  // kept to a crease: its curvature is left out
    const Eigen::Matrix<double, d, d>& hs = curvature[static_cast<std::size_t>(i)];
    if (hs.allFinite()) K -= lambda[i] * f.P * hs * f.P;
  }
  if (mode == HessianMode::Projected) {
    K = (0.5 * (K + K.transpose())).eval();
    project_spd(K);
  }
  // A node held at a corner of a crease (no tangent left) keeps the mean diagonal of B.
  const double tangential = (f.P * B * f.P).trace();
  const double c = f.N.cols() == d ? B.trace() / d : tangential > 0.0 ? tangential / static_cast<double>(d - f.N.cols()) : 1.0;
  f.add = K + c * f.N * f.N.transpose();
  return f;
}

template <int d>
void SlideConstraints<d>::constrain(const Eigen::MatrixXd& x, HessianMode mode, Assembly& out, int threads) {
  Eigen::SparseMatrix<double>& H = out.hessian;
  if (block_offsets_.empty()) block_offsets_ = diagonal_block_offsets(*dofs_, H, nodes());
  const int* outer = H.outerIndexPtr();
  const int* inner = H.innerIndexPtr();
  double* values = H.valuePtr();
  frames_.resize(nodes_.size());
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const std::int64_t* o = block_offsets_.data() + k * d * d;
    Eigen::Matrix<double, d, d> B;
    for (int l = 0; l < d; ++l)
      for (int i = 0; i < d; ++i) B(i, l) = values[o[l * d + i]];
    frames_[k] = frame(nodes_[k], x, B, out.gradient.segment<d>(nodes_[k].first), mode);
  }
  // Rows: the d rows of a slide node are consecutive in every column that holds them.
  const auto n_cols = static_cast<std::ptrdiff_t>(H.outerSize());
#pragma omp parallel for num_threads(resolve_threads(threads)) schedule(static)
  for (std::ptrdiff_t col = 0; col < n_cols; ++col)
    for (int t = outer[col]; t < outer[col + 1]; ++t)
      if (const std::int32_t k = slot_of_row_[static_cast<std::size_t>(inner[t])]; k >= 0) {
        Eigen::Map<Eigen::Matrix<double, d, 1>> v(values + t);
        v = frames_[static_cast<std::size_t>(k)].P * v;
        t += d - 1;
      }
  // Columns: the d columns of a node share their row pattern.
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const int c0 = nodes_[k].first, len = outer[c0 + 1] - outer[c0];
    for (int t = 0; t < len; ++t) {
      Eigen::Matrix<double, d, 1> v;
      for (int l = 0; l < d; ++l) v[l] = values[outer[c0 + l] + t];
      v = frames_[k].P * v;
      for (int l = 0; l < d; ++l) values[outer[c0 + l] + t] = v[l];
    }
  }
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const std::int64_t* o = block_offsets_.data() + k * d * d;
    for (int l = 0; l < d; ++l)
      for (int i = 0; i < d; ++i) values[o[l * d + i]] += frames_[k].add(i, l);
    auto g = out.gradient.segment<d>(nodes_[k].first);
    g -= frames_[k].N * (frames_[k].N.transpose() * g);
  }
}

template <int d>
void SlideConstraints<d>::constrain(const Eigen::MatrixXd& x, const std::vector<double>& node_blocks, HessianMode mode,
                                    Eigen::VectorXd& gradient) {
  frames_.resize(nodes_.size());
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    const Node& s = nodes_[k];
    const Eigen::Map<const Eigen::Matrix<double, d, d>> B(node_blocks.data() + static_cast<std::size_t>(s.node) * d * d);
    frames_[k] = frame(s, x, B, gradient.segment<d>(s.first), mode);
    auto g = gradient.segment<d>(s.first);
    g -= frames_[k].N * (frames_[k].N.transpose() * g);
  }
}

template <int d>
void SlideConstraints<d>::tangential(const Eigen::VectorXd& v, Eigen::VectorXd& out) const {
  out = v;
  for (std::size_t k = 0; k < nodes_.size(); ++k) out.segment<d>(nodes_[k].first) = frames_[k].P * v.segment<d>(nodes_[k].first);
}

template <int d>
void SlideConstraints<d>::finish_action(const Eigen::VectorXd& v, Eigen::VectorXd& y) const {
  for (std::size_t k = 0; k < nodes_.size(); ++k) {
    auto yk = y.segment<d>(nodes_[k].first);
    yk = frames_[k].P * yk + frames_[k].add * v.segment<d>(nodes_[k].first);
  }
}

template <int d>
const typename SlideConstraints<d>::Frame* SlideConstraints<d>::frame_of_row(std::int32_t row) const {
  const std::int32_t k = slot_of_row_[static_cast<std::size_t>(row)];
  return k >= 0 ? &frames_[static_cast<std::size_t>(k)] : nullptr;
}

template <int d>
double SlideConstraints<d>::tangential_gradient(const Eigen::MatrixXd& x, Eigen::VectorXd& gradient) const {
  // A node sliding on one surface counts the descent that surface allows: at a crease of a
  // discrete surface, that of the facets' tangent cones (0 at a minimum on the crease, where
  // the projection on the mean tangent plane is not). A node on several, P g.
  double on_one = 0.0;
  for (const Node& s : nodes_) {
    auto g = gradient.segment<d>(s.first);
    if (s.m == 1) {
      on_one += std::pow(sigma_[static_cast<std::size_t>(s.sigma[0])].stationarity(x.col(s.node), g), 2);
      g.setZero();
    } else {
      const Eigen::Matrix<double, d, Eigen::Dynamic> N = normals(s, x);
      g -= N * (N.transpose() * g);
    }
  }
  return on_one;
}

template class SlideConstraints<2>;
template class SlideConstraints<3>;

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "methods/detail/fit_problem.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Eigenvalues>
#include <omp.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/quality/metric_registry.h"

namespace meshmorph {

template <int d>
FitProblem<d>::FitProblem(const Mesh& mesh, const Topology& topology, const std::vector<FitTerm>& terms,
                          const std::vector<std::uint8_t>& fixed, const FitOptions& options, const Eigen::MatrixXd& x,
                          const std::vector<FitTerm>& slides, bool matrix_free)
    : mesh_(&mesh), terms_(&terms), options_(options), x_(x) {
  targets_ = build_targets<d>(mesh, x, options.target, options.quadrature_degree, options.quadrature);
  dofs_ = DofMap::from_mask(d, fixed);
  slide_sigma_.reserve(slides.size());  // no reallocation: SlideNode points into it
  std::vector<int> slot(mesh.n_nodes(), -1);
  for (const FitTerm& t : slides) {
    slide_sigma_.push_back(t.sigma);
    for (std::int32_t node : t.nodes) {
      int& k = slot[static_cast<std::size_t>(node)];
      if (k < 0) {
        k = static_cast<int>(slides_.size());
        slides_.push_back({node, dofs_.first(static_cast<std::size_t>(node)), 0, {}});
      }
      SlideNode& sn = slides_[static_cast<std::size_t>(k)];
      MESHMORPH_CHECK(sn.m < d - 1, "FitProblem: a slide node lies on d constraints (fix it instead)");
      MESHMORPH_CHECK(dofs_.first(static_cast<std::size_t>(node) + 1) - sn.first == d, "FitProblem: a slide node has a fixed DOF");
      sn.sigma[static_cast<std::size_t>(sn.m++)] = &slide_sigma_.back();
    }
  }
  slide_of_row_.assign(dofs_.n_free(), -1);
  for (std::size_t k = 0; k < slides_.size(); ++k) slide_of_row_[static_cast<std::size_t>(slides_[k].first)] = static_cast<std::int32_t>(k);
  MESHMORPH_CHECK(project_slides(x_), "FitProblem: a slide node cannot be projected onto its surface");
  assembler_ = std::make_unique<EnergyAssembler<d>>(mesh, topology, targets_, dofs_, !matrix_free);
  // Not with sliding nodes: with the coarse level the P2 sphere sliding on its own facets
  // (OptimizeSlide) stalled at |∇F| = 1.2e-8 |∇F₀|, its line search finding no step, where
  // block Jacobi alone converges.
  if (matrix_free && slides_.empty()) {
    coarse_ = std::make_unique<CoarseSpace<d>>(mesh, dofs_, targets_);
    if (coarse_->size() == 0) coarse_.reset();
  }
  metric_ = make_metric<d>(options.metric.empty() ? (d == 2 ? "mu2" : "mu303") : options.metric);
  if (options.flat_edges) {
    std::vector<std::uint8_t> fitted(mesh.n_nodes(), 0);
    for (const FitTerm& t : terms)
      for (std::int32_t s : t.nodes) fitted[static_cast<std::size_t>(s)] = 1;
    flat_ = flat_edges(mesh, fitted);
  }
  min_det0_ = min_det(x);
}

template <int d>
double FitProblem<d>::fit_error(const Eigen::MatrixXd& x) const {
  double e = 0.0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) e = std::max(e, std::abs(t.sigma.value(x.col(s))));
  return e;
}

template <int d>
double FitProblem<d>::cell_min_det(std::size_t b, std::size_t c, const Eigen::MatrixXd& x, bool all) const {
  const CellBlock& block = mesh_->cells[b];
  const int n = block.n_nodes_per_cell();
  Eigen::MatrixXd X(d, n);
  for (int a = 0; a < n; ++a) X.col(a) = x.col(block.nodes[c * n + a]);
  const std::int32_t k = flat_.mask_of_cell.empty() || all ? -1 : flat_.mask_of_cell[b][c];
  return k < 0 ? min_jacobian_det(block.type, block.order, X)
               : min_jacobian_det(block.type, block.order, X, flat_.masks[static_cast<std::size_t>(k)]);
}

template <int d>
double FitProblem<d>::min_det(const Eigen::MatrixXd& x) const {
  double m = std::numeric_limits<double>::infinity();
  for (std::size_t b = 0; b < mesh_->cells.size(); ++b) {
    const auto n_cells = static_cast<std::ptrdiff_t>(mesh_->cells[b].n_cells());
#pragma omp parallel for num_threads(options_.threads > 0 ? options_.threads : omp_get_max_threads()) reduction(min : m) schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) m = std::min(m, cell_min_det(b, static_cast<std::size_t>(c), x, false));
  }
  return m;
}

template <int d>
std::array<std::size_t, 2> FitProblem<d>::invalid_cells(const Eigen::MatrixXd& x) const {
  std::size_t inverted = 0, flat = 0;
  for (std::size_t b = 0; b < mesh_->cells.size(); ++b)
    for (std::size_t c = 0; c < mesh_->cells[b].n_cells(); ++c) {
      if (!(cell_min_det(b, c, x, false) > 0.0)) ++inverted;
      else if (!(cell_min_det(b, c, x, true) > 0.0)) ++flat;
    }
  return {inverted, flat};
}

template <int d>
double FitProblem<d>::target_measure() const {
  double v = 0.0;
  for (const BlockTargets<d>& b : targets_.blocks)
    for (const QuadratureTarget<d>& t : b.points) v += t.weight;
  return v;
}

template <int d>
std::array<double, 3> FitProblem<d>::metric_range() const {
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0.0;
  std::size_t count = 0;
  for (std::size_t b = 0; b < mesh_->cells.size(); ++b) {
    const CellBlock& block = mesh_->cells[b];
    const BlockTargets<d>& targets = targets_.blocks[b];
    const ShapeTable& table = *targets.table;
    const int n = block.n_nodes_per_cell(), nq = targets.n_points();
    const auto n_cells = static_cast<std::ptrdiff_t>(block.n_cells());
#pragma omp parallel for num_threads(options_.threads > 0 ? options_.threads : omp_get_max_threads()) reduction(min : lo) reduction(max : hi) reduction(+ : sum) schedule(static)
    for (std::ptrdiff_t c = 0; c < n_cells; ++c) {
      Eigen::Matrix<double, d, Eigen::Dynamic> X(d, n);
      for (int a = 0; a < n; ++a) X.col(a) = x_.col(block.nodes[static_cast<std::size_t>(c) * n + a]);
      const QuadratureTarget<d>* t = targets.cell(static_cast<std::size_t>(c));
      for (int q = 0; q < nq; ++q) {
        const MatT<d> T = X.lazyProduct(table.grad(q)) * t[q].W_inv;
        const double mu = metric_->eval(T, Want::Value).mu;
        lo = std::min(lo, mu);
        hi = std::max(hi, mu);
        sum += mu;
      }
    }
    count += block.n_cells() * static_cast<std::size_t>(nq);
  }
  return {lo, count ? sum / static_cast<double>(count) : 0.0, hi};
}

template <int d>
std::vector<std::int64_t> FitProblem<d>::node_blocks(const Eigen::SparseMatrix<double>& H,
                                                     const std::vector<std::int32_t>& nodes) const {
  std::vector<std::int64_t> offsets;
  offsets.reserve(nodes.size() * d * d);
  for (std::int32_t s : nodes)
    for (int l = 0; l < d; ++l)
      for (int k = 0; k < d; ++k) {
        const std::int32_t row = dofs_.reduced(static_cast<std::size_t>(d) * s + k);
        const std::int32_t col = dofs_.reduced(static_cast<std::size_t>(d) * s + l);
        std::int64_t offset = -1;
        if (row >= 0 && col >= 0) {
          const int* begin = H.innerIndexPtr() + H.outerIndexPtr()[col];
          const int* end = H.innerIndexPtr() + H.outerIndexPtr()[col + 1];
          const int* it = std::lower_bound(begin, end, row);
          MESHMORPH_CHECK(it != end && *it == row, "FitProblem: a node block is missing from the Hessian pattern");
          offset = it - H.innerIndexPtr();
        }
        offsets.push_back(offset);
      }
  return offsets;
}

template <int d>
void FitProblem<d>::bind_blocks(const Eigen::SparseMatrix<double>& H) {
  block_offsets_.clear();
  for (const FitTerm& t : *terms_) {
    const std::vector<std::int64_t> o = node_blocks(H, t.nodes);
    block_offsets_.insert(block_offsets_.end(), o.begin(), o.end());
  }
}

template <int d>
double FitProblem<d>::penalty_value(const Eigen::MatrixXd& x) const {
  double v = 0.0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) {
      const double sigma = t.sigma.value(x.col(s));
      v += sigma * sigma;
    }
  return weight * v;
}

template <int d>
void FitProblem<d>::add_penalty(const Eigen::MatrixXd& x, Want want, HessianMode mode, Assembly& out) {
  out.value += penalty_value(x);
  if (want == Want::Value) return;
  if (want == Want::Hessian && block_offsets_.empty()) bind_blocks(out.hessian);
  double* values = want == Want::Hessian ? out.hessian.valuePtr() : nullptr;
  std::size_t e = 0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes) {
      const Eigen::Matrix<double, d, 1> p = x.col(s);
      const double sigma = t.sigma.value(p);
      const Eigen::Matrix<double, d, 1> g = t.sigma.gradient(p);
      for (int k = 0; k < d; ++k) {
        const std::int32_t i = dofs_.reduced(static_cast<std::size_t>(d) * s + k);
        if (i >= 0) out.gradient[i] += 2.0 * weight * sigma * g(k);
      }
      if (!values) continue;
      Eigen::Matrix<double, d, d> H = 2.0 * weight * (g * g.transpose() + sigma * Eigen::Matrix<double, d, d>(t.sigma.hessian(p)));
      if (mode == HessianMode::Projected) {
        const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, d, d>> eig(H);
        H = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
      }
      for (int l = 0; l < d; ++l)
        for (int k = 0; k < d; ++k, ++e)
          if (block_offsets_[e] >= 0) values[block_offsets_[e]] += H(k, l);
    }
}

template <int d>
Eigen::Matrix<double, d, Eigen::Dynamic> FitProblem<d>::orthonormal(Eigen::Matrix<double, d, Eigen::Dynamic> N) {
  // Modified Gram–Schmidt; two normals are never parallel at a node the caller let slide on a curve.
  for (Eigen::Index i = 0; i < N.cols(); ++i) {
    for (Eigen::Index j = 0; j < i; ++j) N.col(i) -= N.col(j).dot(N.col(i)) * N.col(j);
    N.col(i).normalize();
  }
  return N;
}

template <int d>
Eigen::Matrix<double, d, Eigen::Dynamic> FitProblem<d>::normals(const SlideNode& s, const Eigen::MatrixXd& x) const {
  Eigen::Matrix<double, d, Eigen::Dynamic> N(d, s.m);
  for (int i = 0; i < s.m; ++i) N.col(i) = s.sigma[static_cast<std::size_t>(i)]->gradient(x.col(s.node));
  return orthonormal(std::move(N));
}

template <int d>
bool FitProblem<d>::project_slides(Eigen::MatrixXd& x) const {
  bool ok = true;
  const auto n = static_cast<std::ptrdiff_t>(slides_.size());
#pragma omp parallel for num_threads(options_.threads > 0 ? options_.threads : omp_get_max_threads()) reduction(&& : ok) schedule(static)
  for (std::ptrdiff_t k = 0; k < n; ++k) {
    const SlideNode& s = slides_[static_cast<std::size_t>(k)];
    Eigen::Matrix<double, d, 1> p = x.col(s.node);
    // Gauss–Newton on σ_i(p) = 0 with minimal-norm corrections −Jᵀ(JJᵀ)⁻¹σ: one step for planes,
    // and a sphere's exact closest point in one step too (σ is the distance, ∇σ radial).
    bool done = false;
    for (int it = 0; it < 50 && !done; ++it) {
      Eigen::Matrix<double, Eigen::Dynamic, d> J(s.m, d);
      Eigen::VectorXd r(s.m);
      for (int i = 0; i < s.m; ++i) {
        r[i] = s.sigma[static_cast<std::size_t>(i)]->value(p);
        J.row(i) = s.sigma[static_cast<std::size_t>(i)]->gradient(p).transpose();
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
typename FitProblem<d>::SlideFrame FitProblem<d>::slide_frame(const SlideNode& s, const Eigen::Matrix<double, d, d>& B,
                                                             const Eigen::Matrix<double, d, 1>& g, HessianMode mode) const {
  SlideFrame f;
  const Eigen::Matrix<double, d, 1> p = x_.col(s.node);
  // Each level set's questions in a row: a facet surface answers them from one search.
  Eigen::Matrix<double, d, Eigen::Dynamic> J(d, s.m);  // the ∇σ_i
  std::array<Eigen::Matrix<double, d, d>, 2> curvature;  // the ∇²σ_i
  for (std::size_t i = 0; i < static_cast<std::size_t>(s.m); ++i) {
    J.col(static_cast<Eigen::Index>(i)) = s.sigma[i]->gradient(p);
    curvature[i] = s.sigma[i]->hessian(p);
  }
  // One surface: its level set says which normals bind the step (more at a crease it keeps to).
  if (s.m == 1) f.N = s.sigma[0]->step_normals(p, g);
  else f.N = orthonormal(J);
  f.P = Eigen::Matrix<double, d, d>::Identity() - f.N * f.N.transpose();
  const Eigen::VectorXd lambda = (J.transpose() * J).ldlt().solve(J.transpose() * g);
  Eigen::Matrix<double, d, d> K = Eigen::Matrix<double, d, d>::Zero();
  for (int i = 0; i < s.m && f.N.cols() == s.m; ++i) {  // kept to a crease: its curvature is left out
    const Eigen::Matrix<double, d, d>& hs = curvature[static_cast<std::size_t>(i)];
    if (hs.allFinite()) K -= lambda[i] * f.P * hs * f.P;
  }
  if (mode == HessianMode::Projected) {
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, d, d>> eig(0.5 * (K + K.transpose()));
    K = eig.eigenvectors() * eig.eigenvalues().cwiseMax(0.0).asDiagonal() * eig.eigenvectors().transpose();
  }
  // A node held at a corner of a crease (no tangent left) keeps the mean diagonal of B.
  const double tangential = (f.P * B * f.P).trace();
  const double c = f.N.cols() == d ? B.trace() / d : tangential > 0.0 ? tangential / static_cast<double>(d - f.N.cols()) : 1.0;
  f.add = K + c * f.N * f.N.transpose();
  return f;
}

template <int d>
void FitProblem<d>::constrain_hessian(HessianMode mode, Assembly& out) {
  Eigen::SparseMatrix<double>& H = out.hessian;
  if (slide_offsets_.empty()) {
    std::vector<std::int32_t> nodes;
    for (const SlideNode& s : slides_) nodes.push_back(s.node);
    slide_offsets_ = node_blocks(H, nodes);
  }
  const int* outer = H.outerIndexPtr();
  const int* inner = H.innerIndexPtr();
  double* values = H.valuePtr();
  frames_.resize(slides_.size());
  for (std::size_t k = 0; k < slides_.size(); ++k) {
    const std::int64_t* o = slide_offsets_.data() + k * d * d;
    Eigen::Matrix<double, d, d> B;
    for (int l = 0; l < d; ++l)
      for (int i = 0; i < d; ++i) B(i, l) = values[o[l * d + i]];
    frames_[k] = slide_frame(slides_[k], B, out.gradient.segment<d>(slides_[k].first), mode);
  }
  // Rows: the d rows of a slide node are consecutive in every column that holds them.
  const auto n_cols = static_cast<std::ptrdiff_t>(H.outerSize());
#pragma omp parallel for num_threads(options_.threads > 0 ? options_.threads : omp_get_max_threads()) schedule(static)
  for (std::ptrdiff_t col = 0; col < n_cols; ++col)
    for (int t = outer[col]; t < outer[col + 1]; ++t)
      if (const std::int32_t k = slide_of_row_[static_cast<std::size_t>(inner[t])]; k >= 0) {
        Eigen::Map<Eigen::Matrix<double, d, 1>> v(values + t);
        v = frames_[static_cast<std::size_t>(k)].P * v;
        t += d - 1;
      }
  // Columns: the d columns of a node share their row pattern.
  for (std::size_t k = 0; k < slides_.size(); ++k) {
    const int c0 = slides_[k].first, len = outer[c0 + 1] - outer[c0];
    for (int t = 0; t < len; ++t) {
      Eigen::Matrix<double, d, 1> v;
      for (int l = 0; l < d; ++l) v[l] = values[outer[c0 + l] + t];
      v = frames_[k].P * v;
      for (int l = 0; l < d; ++l) values[outer[c0 + l] + t] = v[l];
    }
  }
  for (std::size_t k = 0; k < slides_.size(); ++k) {
    const std::int64_t* o = slide_offsets_.data() + k * d * d;
    for (int l = 0; l < d; ++l)
      for (int i = 0; i < d; ++i) values[o[l * d + i]] += frames_[k].add(i, l);
    auto g = out.gradient.segment<d>(slides_[k].first);
    g -= frames_[k].N * (frames_[k].N.transpose() * g);
  }
}

template <int d>
bool FitProblem<d>::step_to(const Eigen::VectorXd& p, double alpha, Eigen::MatrixXd& out) const {
  out = x_;
  dofs_.add_step(p, alpha, out);
  return slides_.empty() || project_slides(out);
}

template <int d>
double FitProblem<d>::metric_stiffness() {
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = HessianMode::Projected;
  o.threads = options_.threads;
  Assembly a;
  assembler_->assemble(*metric_, x_, o, a);
  const Eigen::VectorXd diagonal = a.hessian.diagonal();
  double sum = 0.0;
  int count = 0;
  for (const FitTerm& t : *terms_)
    for (std::int32_t s : t.nodes)
      for (int k = 0; k < d; ++k)
        if (const std::int32_t i = dofs_.reduced(static_cast<std::size_t>(d) * s + k); i >= 0) sum += diagonal[i], ++count;
  return count > 0 && sum > 0.0 ? sum / count : 1.0;
}

template <int d>
void FitProblem<d>::evaluate(HessianMode mode, Assembly& out) {
  AssemblyOptions o;
  o.want = Want::Hessian;
  o.hessian = mode;
  o.threads = options_.threads;
  assembler_->assemble(*metric_, x_, o, out);
  if (!std::isfinite(out.value)) return;
  add_penalty(x_, Want::Hessian, mode, out);
  if (!slides_.empty()) constrain_hessian(mode, out);
}

template <int d>
void FitProblem<d>::evaluate_action(HessianMode mode, Assembly& out) {
  MESHMORPH_CHECK(terms_->empty(), "FitProblem: the matrix-free Hessian has no fitted nodes");
  if (metric_at_current_.gradient.size() != static_cast<Eigen::Index>(dofs_.n_free())) remember_current();
  out.value = metric_at_current_.value;  // F and ∇F as remember_current() or accept() measured them
  out.gradient = metric_at_current_.gradient;
  out.element_values = metric_at_current_.element_values;
  if (std::isfinite(out.value) && !assembler_->prepare_hessian(*metric_, x_, mode, options_.threads, action_))
    out.value = std::numeric_limits<double>::infinity();
  if (!std::isfinite(out.value)) return;
  node_blocks_ = assembler_->hessian_blocks(action_, options_.threads);
  frames_.resize(slides_.size());
  for (std::size_t k = 0; k < slides_.size(); ++k) {
    const SlideNode& s = slides_[k];
    const Eigen::Map<const Eigen::Matrix<double, d, d>> B(node_blocks_.data() + static_cast<std::size_t>(s.node) * d * d);
    frames_[k] = slide_frame(s, B, out.gradient.segment<d>(s.first), mode);
    auto g = out.gradient.segment<d>(s.first);
    g -= frames_[k].N * (frames_[k].N.transpose() * g);
  }
}

template <int d>
void FitProblem<d>::apply_hessian(const Eigen::VectorXd& v, Eigen::VectorXd& y) {
  if (slides_.empty()) {
    assembler_->apply_hessian(action_, v, y, options_.threads);
    return;
  }
  // (P H P + the frames' additions) v, P the slide nodes' tangent projections.
  slide_v_ = v;
  for (std::size_t k = 0; k < slides_.size(); ++k) slide_v_.segment<d>(slides_[k].first) = frames_[k].P * v.segment<d>(slides_[k].first);
  assembler_->apply_hessian(action_, slide_v_, y, options_.threads);
  for (std::size_t k = 0; k < slides_.size(); ++k) {
    auto yk = y.segment<d>(slides_[k].first);
    yk = frames_[k].P * yk + frames_[k].add * v.segment<d>(slides_[k].first);
  }
}

template <int d>
HessianBlocks FitProblem<d>::hessian_blocks() {
  HessianBlocks b;
  b.size = d;
  const std::int32_t* red = dofs_.reduced_index().data();
  for (std::size_t i = 0; i < mesh_->n_nodes(); ++i) {
    int free[d], m = 0;
    for (int k = 0; k < d; ++k)
      if (red[d * i + k] >= 0) free[m++] = k;
    if (m == 0) continue;
    b.first.push_back(red[d * i + free[0]]);
    Eigen::Matrix<double, d, d> B = Eigen::Map<const Eigen::Matrix<double, d, d>>(node_blocks_.data() + i * d * d);
    // A slide node has all its DOFs free: its first one finds its slot.
    if (const std::int32_t k = m == d ? slide_of_row_[static_cast<std::size_t>(b.first.back())] : -1; k >= 0) {
      const SlideFrame& f = frames_[static_cast<std::size_t>(k)];
      B = f.P * B * f.P + f.add;
    }
    const std::size_t at = b.values.size();
    b.values.resize(at + d * d, 0.0);
    for (int l = 0; l < m; ++l)
      for (int r = 0; r < m; ++r) b.values[at + static_cast<std::size_t>(r + d * l)] = B(free[r], free[l]);
  }
  b.first.push_back(static_cast<std::int32_t>(dofs_.n_free()));
  return b;
}

template <int d>
bool FitProblem<d>::coarse_hessian(CoarseHessian& out) {
  if (!coarse_) return false;
  out.R = &coarse_->R();
  out.A = assembler_->coarse_hessian(action_, *coarse_, options_.threads);
  return true;
}

template <int d>
double FitProblem<d>::gradient_norm(const Eigen::MatrixXd& x, Assembly& metric) {
  AssemblyOptions o;
  o.want = Want::Gradient;
  o.threads = options_.threads;
  assembler_->assemble(*metric_, x, o, metric);
  Assembly a = metric;
  add_penalty(x, Want::Gradient, HessianMode::Projected, a);
  // A node sliding on one surface counts the descent that surface allows: at a crease of a
  // discrete surface, that of the facets' tangent cones (0 at a minimum on the crease, where
  // the projection on the mean tangent plane is not). A node on several, P g.
  double on_one = 0.0;
  for (const SlideNode& s : slides_) {
    auto g = a.gradient.segment<d>(s.first);
    if (s.m == 1) {
      on_one += std::pow(s.sigma[0]->stationarity(x.col(s.node), g), 2);
      g.setZero();
    } else {
      const Eigen::Matrix<double, d, Eigen::Dynamic> N = normals(s, x);
      g -= N * (N.transpose() * g);
    }
  }
  return std::sqrt(a.gradient.squaredNorm() + on_one);
}

template <int d>
void FitProblem<d>::remember_current() {
  gradient_norm_ = gradient_norm(x_, metric_at_current_);
  error_ = fit_error(x_);
}

template <int d>
double FitProblem<d>::trial_value(const Eigen::VectorXd& p, double alpha) {
  admitted_ = {};
  if (!step_to(p, alpha, trial_)) return std::numeric_limits<double>::infinity();
  const double v = assembler_->value(*metric_, trial_, {}, options_.threads);
  admitted_.alpha = alpha;
  admitted_.energy = std::isfinite(v) ? v + penalty_value(trial_) : v;
  return admitted_.energy;
}

template <int d>
bool FitProblem<d>::admissible(const Eigen::VectorXd& p, double alpha) {
  Measured m = admitted_.alpha == alpha ? admitted_ : Measured{};  // F from trial_value() at this point
  admitted_ = {};
  if (!step_to(p, alpha, trial_)) return false;
  m.min_det = min_det(trial_);
  if (!(m.min_det > std::max(0.0, options_.det_floor * min_det0_))) return false;  // det A > 0, eq. 15
  if (error_ > 0.0 && !(fit_error(trial_) < options_.growth * error_)) return false;  // eq. 14
  m.gradient_norm = gradient_norm(trial_, metric_at_trial_);
  if (!(m.gradient_norm < options_.growth * gradient_norm_)) return false;  // §2.2
  if (m.alpha != alpha) m = {alpha, assembler_->value(*metric_, trial_, {}, options_.threads) + penalty_value(trial_), m.min_det, m.gradient_norm};
  m.admitted = true;
  admitted_ = m;
  return true;
}

template <int d>
void FitProblem<d>::accept(const Eigen::VectorXd& p, double alpha) {
  // newton() accepts the point that admissible() passed last: trial_ holds it, measured.
  if (!(admitted_.admitted && admitted_.alpha == alpha)) {
    step_to(p, alpha, trial_);
    admitted_ = {alpha, assembler_->value(*metric_, trial_, {}, options_.threads) + penalty_value(trial_), min_det(trial_),
                 gradient_norm(trial_, metric_at_trial_), true};
  }
  x_.swap(trial_);
  std::swap(metric_at_current_, metric_at_trial_);
  gradient_norm_ = admitted_.gradient_norm;
  error_ = fit_error(x_);
  current_ = admitted_;
  admitted_ = {};
}

template class FitProblem<2>;
template class FitProblem<3>;

}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/fem/tensor_basis.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>
#include <utility>

#include "meshmorph/fem/reference_element.h"

namespace meshmorph {
namespace {

TensorBasis make_tensor_basis(ElementType type, int order) {
  TensorBasis t;
  if (type != ElementType::Quadrilateral && type != ElementType::Hexahedron) return t;
  const ReferenceElement& ref = reference_element(type, order);
  const int dim = ref.dim, n = ref.n_nodes();
  std::vector<double> xs(ref.nodes.row(0).begin(), ref.nodes.row(0).end());
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }), xs.end());
  const int P = static_cast<int>(xs.size());
  if (static_cast<int>(std::lround(std::pow(P, dim))) != n) return t;
  std::vector<std::int32_t> node(static_cast<std::size_t>(n), -1);
  for (int a = 0; a < n; ++a) {
    int lattice = 0;
    for (int k = dim - 1; k >= 0; --k) {
      const auto at = std::find_if(xs.begin(), xs.end(), [&](double v) { return std::abs(v - ref.nodes(k, a)) < 1e-12; });
      if (at == xs.end()) return t;
      lattice = lattice * P + static_cast<int>(at - xs.begin());
    }
    node[static_cast<std::size_t>(lattice)] = a;
  }
  if (std::count(node.begin(), node.end(), -1) > 0) return t;
  t.P = P;
  t.nodes = std::move(xs);
  t.node = std::move(node);
  return t;
}

}  // namespace

void TensorBasis::tabulate(const std::vector<double>& x, Eigen::MatrixXd& B, Eigen::MatrixXd& D) const {
  const auto m = static_cast<Eigen::Index>(x.size());
  B.resize(m, P);
  D.resize(m, P);
  for (Eigen::Index q = 0; q < m; ++q)
    for (int i = 0; i < P; ++i) {
      double value = 1.0, slope = 0.0;
      for (int j = 0; j < P; ++j) {
        if (j == i) continue;
        const double h = nodes[static_cast<std::size_t>(i)] - nodes[static_cast<std::size_t>(j)];
        const double f = (x[static_cast<std::size_t>(q)] - nodes[static_cast<std::size_t>(j)]) / h;
        slope = slope * f + value / h;  // product rule
        value *= f;
      }
      B(q, i) = value;
      D(q, i) = slope;
    }
}

const TensorBasis& tensor_basis(ElementType type, int order) {
  static std::mutex mutex;
  static std::map<std::pair<ElementType, int>, std::unique_ptr<TensorBasis>> cache;
  std::lock_guard lock(mutex);
  auto& slot = cache[{type, order}];
  if (!slot) slot = std::make_unique<TensorBasis>(make_tensor_basis(type, order));
  return *slot;
}

}  // namespace meshmorph

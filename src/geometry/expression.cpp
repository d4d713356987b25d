// SPDX-License-Identifier: MIT
// A muparser level set. A mu::Parser evaluates through its own stack and binds x, y, z by
// address, so one instance must not serve two threads at once. The node keeps a pool of
// parsers: each evaluation borrows one under a short lock (created on demand, so the pool
// grows to the number of concurrent callers) and returns it. The pool is the node's only
// mutable state, and it never changes a result.
#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

#include <muParser.h>

#include "geometry/detail/level_set_node.h"
#include "meshmorph/error.h"

namespace meshmorph::detail {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A parser bound to its own x, y, z (heap-allocated, so the bound addresses stay put).
struct BoundParser {
  double x = 0, y = 0, z = 0;
  mu::Parser parser;
  explicit BoundParser(const std::string& expression) {
    parser.DefineVar("x", &x);
    parser.DefineVar("y", &y);
    parser.DefineVar("z", &z);
    parser.DefineConst("pi", kPi);
    parser.SetExpr(expression);
  }
};

class Expression final : public LevelSetNode {
 public:
  Expression(std::string expression, double length_scale)
      : expression_(std::move(expression)), length_scale_(length_scale) {}

  // Builds and evaluates one parser so that errors surface at compile time.
  void check(const std::string& where) const {
    if (expression_.find_first_not_of(" \t\r\n") == std::string::npos)
      throw InputError(where + ": empty expression");
    try {
      auto p = std::make_unique<BoundParser>(expression_);
      p->x = 0.1, p->y = 0.2, p->z = 0.3;
      (void)p->parser.Eval();  // muparser parses lazily: the first Eval reports errors
      release(std::move(p));
    } catch (const mu::Parser::exception_type& e) {
      throw InputError(where + ": invalid expression \"" + expression_ + "\": " + e.GetMsg() +
                       " (at character " + std::to_string(e.GetPos() + 1) + ")");
    }
  }

  double value(const Vec& x) const override {
    auto p = acquire();
    const double v = eval(*p, x);
    release(std::move(p));
    return v;
  }

  // Fourth-order central differences, (−f(x+2h) + 8f(x+h) − 8f(x−h) + f(x−2h)) / 12h:
  // truncation h⁴·f⁽⁵⁾/30, rounding ≈ 1.5·ε·|f|/h; h = 2e-4·max(‖x‖, ℓ) puts both
  // near 1e-12 relative for σ smooth on the scale ℓ.
  double value_gradient(const Vec& x, Vec& g) const override {
    auto p = acquire();
    const double v = eval(*p, x);
    const double h = difference_step(x, length_scale_);
    g.resize(x.size());
    Vec y = x;
    for (Eigen::Index k = 0; k < x.size(); ++k) {
      auto at = [&](double t) {
        y(k) = x(k) + t;
        return eval(*p, y);
      };
      g(k) = (-at(2 * h) + 8 * at(h) - 8 * at(-h) + at(-2 * h)) / (12 * h);
      y(k) = x(k);
    }
    release(std::move(p));
    return v;
  }

  // Differences of the difference gradient: rounding ≈ 1.5·δg/h with δg ≈ 1e-12·|σ|/ℓ,
  // so about 1e-8 relative (docs/level-sets.md).
  Eigen::MatrixXd hessian(const Vec& x) const override {
    const auto gradient = [this](const Vec& y) {
      Vec g;
      value_gradient(y, g);
      return g;
    };
    return hessian_by_differences(gradient, x, difference_step(x, length_scale_));
  }

 private:
  static double eval(BoundParser& p, const Vec& x) {
    p.x = x(0);
    p.y = x(1);
    p.z = x.size() > 2 ? x(2) : 0.0;
    try {
      return p.parser.Eval();
    } catch (const mu::Parser::exception_type&) {
      return std::nan("");  // checked at compile time; only a runtime domain error lands here
    }
  }

  std::unique_ptr<BoundParser> acquire() const {
    {
      std::lock_guard lock(mutex_);
      if (!pool_.empty()) {
        auto p = std::move(pool_.back());
        pool_.pop_back();
        return p;
      }
    }
    return std::make_unique<BoundParser>(expression_);
  }
  void release(std::unique_ptr<BoundParser> p) const {
    std::lock_guard lock(mutex_);
    pool_.push_back(std::move(p));
  }

  std::string expression_;
  double length_scale_;
  mutable std::mutex mutex_;
  mutable std::vector<std::unique_ptr<BoundParser>> pool_;
};

}  // namespace

NodePtr make_expression(const std::string& expression, double length_scale, const std::string& where) {
  auto node = std::make_shared<Expression>(expression, length_scale);
  node->check(where);
  return node;
}

}  // namespace meshmorph::detail

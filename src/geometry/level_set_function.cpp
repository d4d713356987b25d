// SPDX-License-Identifier: MIT
#include "meshmorph/geometry/level_set_function.h"

#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>

#include "geometry/detail/level_set_node.h"
#include "meshmorph/error.h"
#include "meshmorph/geometry/distance_field.h"

namespace meshmorph {

namespace detail {

namespace {

class Checker {
 public:
  Checker(const CompileContext& ctx, const std::string& key_path, const char* kind) : ctx_(ctx) {
    where_ = ctx.source.empty() ? std::string() : ctx.source + ": ";
    where_ += key_path.empty() ? std::string(kind) : key_path + "." + kind;
  }
  const std::string& where() const { return where_; }
  [[noreturn]] void fail(const std::string& key, const std::string& what) const {
    throw InputError(where_ + (key.empty() ? "" : "." + key) + ": " + what);
  }
  void vector(const Vec& v, const char* key) const {
    if (v.size() != ctx_.dim)
      fail(key, "expected " + std::to_string(ctx_.dim) + " numbers for a " + std::to_string(ctx_.dim) +
                    "D level set, found " + std::to_string(v.size()));
    if (!v.allFinite()) fail(key, "expected finite numbers");
  }
  void direction(const Vec& v, const char* key) const {
    vector(v, key);
    if (!(v.stableNorm() > 0)) fail(key, "expected a non-zero direction");
  }
  void positive(double v, const char* key) const {
    if (!(v > 0) || !std::isfinite(v)) fail(key, "expected a positive number, found " + std::to_string(v));
  }
  void only_3d(const char* what) const {
    if (ctx_.dim != 3) fail("", std::string(what) + " exists only in 3D; the level set is 2D");
  }

 private:
  const CompileContext& ctx_;
  std::string where_;
};

std::vector<NodePtr> compile_operands(const std::vector<LevelSet>& operands, const CompileContext& ctx,
                                      const Checker& c, std::size_t min_count, std::size_t max_count) {
  if (operands.size() < min_count || operands.size() > max_count)
    c.fail("", min_count == max_count
                   ? "expected exactly " + std::to_string(min_count) + " level sets, found " +
                         std::to_string(operands.size())
                   : "expected at least " + std::to_string(min_count) + " level set");
  std::vector<NodePtr> nodes;
  nodes.reserve(operands.size());
  for (const auto& op : operands) nodes.push_back(compile_node(op, ctx));
  return nodes;
}

}  // namespace

NodePtr compile_node(const LevelSet& ls, const CompileContext& ctx) {
  return std::visit(
      [&](const auto& s) -> NodePtr {
        using S = std::decay_t<decltype(s)>;
        if constexpr (std::is_same_v<S, SphereLevelSet>) {
          const Checker c(ctx, ls.key_path, "sphere");
          c.vector(s.center, "center");
          c.positive(s.radius, "radius");
          return make_sphere(s);
        } else if constexpr (std::is_same_v<S, CylinderLevelSet>) {
          const Checker c(ctx, ls.key_path, "cylinder");
          c.only_3d("an infinite cylinder");
          c.vector(s.center, "center");
          c.direction(s.axis, "axis");
          c.positive(s.radius, "radius");
          return make_cylinder(s);
        } else if constexpr (std::is_same_v<S, PlaneLevelSet>) {
          const Checker c(ctx, ls.key_path, "plane");
          c.vector(s.point, "point");
          c.direction(s.normal, "normal");
          return make_plane(s);
        } else if constexpr (std::is_same_v<S, BoxLevelSet>) {
          const Checker c(ctx, ls.key_path, "box");
          c.vector(s.center, "center");
          c.vector(s.size, "size");
          if (!(s.size.minCoeff() > 0)) c.fail("size", "expected positive edge lengths");
          return make_box(s);
        } else if constexpr (std::is_same_v<S, TorusLevelSet>) {
          const Checker c(ctx, ls.key_path, "torus");
          c.only_3d("a torus");
          c.vector(s.center, "center");
          c.direction(s.axis, "axis");
          c.positive(s.major, "major");
          c.positive(s.minor, "minor");
          if (!(s.minor < s.major))
            c.fail("minor", "expected a minor radius smaller than the major radius (a ring torus)");
          return make_torus(s);
        } else if constexpr (std::is_same_v<S, ExprLevelSet>) {
          const Checker c(ctx, ls.key_path, "expr");
          return make_expression(s.expression, ctx.length_scale, c.where());
        } else if constexpr (std::is_same_v<S, UnionLevelSet>) {
          const Checker c(ctx, ls.key_path, "union");
          return make_csg(CsgOp::Union, compile_operands(s.operands, ctx, c, 1, SIZE_MAX), s.blend);
        } else if constexpr (std::is_same_v<S, IntersectionLevelSet>) {
          const Checker c(ctx, ls.key_path, "intersection");
          return make_csg(CsgOp::Intersection, compile_operands(s.operands, ctx, c, 1, SIZE_MAX), s.blend);
        } else if constexpr (std::is_same_v<S, DifferenceLevelSet>) {
          const Checker c(ctx, ls.key_path, "difference");
          return make_csg(CsgOp::Difference, compile_operands(s.operands, ctx, c, 2, 2), s.blend);
        } else if constexpr (std::is_same_v<S, MeshLevelSet>) {
          const Checker c(ctx, ls.key_path, "mesh");
          return load_background_field(s, ctx.dim, c.where());
        } else {
          static_assert(std::is_same_v<S, DistanceLevelSet>);
          const Checker c(ctx, ls.key_path, "distance");
          const NodePtr indicator = compile_operands(s.operands, ctx, c, 1, 1).front();
          c.vector(s.lower, "lower");
          c.vector(s.upper, "upper");
          DistanceFieldOptions o;
          o.lower = s.lower;
          o.upper = s.upper;
          o.cells = s.cells;
          o.levels = s.levels;
          o.order = s.order;
          try {
            DistanceField f = distance_field([&](const Vec& x) { return indicator->value(x) < 0; }, ctx.dim, o);
            return make_background_field(std::move(f.background), std::move(f.values), c.where());
          } catch (const std::invalid_argument& e) {
            c.fail("", std::string(e.what()).substr(std::string("distance_field: ").size()));
          }
        }
      },
      ls.shape);
}

namespace {

// The default answers at x: each one the node's function there.
class ForwardingPoint final : public NodePoint {
 public:
  ForwardingPoint(const LevelSetNode& node, const Vec& x) : node_(node), x_(x) {}
  double value() const override { return node_.value(x_); }
  Vec gradient() const override {
    Vec g;
    node_.value_gradient(x_, g);
    return g;
  }
  Eigen::MatrixXd hessian() const override { return node_.hessian(x_); }
  double stationarity(const Vec& g) const override { return node_.stationarity(x_, g); }
  Eigen::MatrixXd step_normals(const Vec& g) const override { return node_.step_normals(x_, g); }

 private:
  const LevelSetNode& node_;
  Vec x_;
};

}  // namespace

std::unique_ptr<const NodePoint> LevelSetNode::at(const Vec& x) const { return std::make_unique<ForwardingPoint>(*this, x); }

}  // namespace detail

double LevelSetPoint::value() const { return point_->value(); }
Eigen::VectorXd LevelSetPoint::gradient() const { return point_->gradient(); }
Eigen::MatrixXd LevelSetPoint::hessian() const { return point_->hessian(); }

double LevelSetPoint::stationarity(const Eigen::Ref<const Eigen::VectorXd>& g) const {
  MESHMORPH_CHECK(g.size() == dim_, "LevelSetPoint::stationarity: vector of the wrong dimension");
  return point_->stationarity(g);
}

Eigen::MatrixXd LevelSetPoint::step_normals(const Eigen::Ref<const Eigen::VectorXd>& g) const {
  MESHMORPH_CHECK(g.size() == dim_, "LevelSetPoint::step_normals: vector of the wrong dimension");
  return point_->step_normals(g);
}

LevelSetFunction::LevelSetFunction(const LevelSet& ls, int dim, const LevelSetOptions& options) : dim_(dim) {
  MESHMORPH_CHECK(dim == 2 || dim == 3, "LevelSetFunction: dim must be 2 or 3");
  MESHMORPH_CHECK(options.length_scale > 0, "LevelSetFunction: length_scale must be positive");
  root_ = detail::compile_node(ls, detail::CompileContext{options.source, options.length_scale, dim});
}

LevelSetFunction::LevelSetFunction(Mesh background, Eigen::VectorXd values) : dim_(background.dim) {
  if (dim_ != 2 && dim_ != 3) throw InputError("mesh level set: the background mesh must be 2D or 3D");
  root_ = detail::make_background_field(std::move(background), std::move(values), "mesh level set");
}

double LevelSetFunction::value(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  MESHMORPH_CHECK(x.size() == dim_, "LevelSetFunction::value: point of the wrong dimension");
  return root_->value(x);
}

Eigen::VectorXd LevelSetFunction::gradient(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  MESHMORPH_CHECK(x.size() == dim_, "LevelSetFunction::gradient: point of the wrong dimension");
  Eigen::VectorXd g;
  root_->value_gradient(x, g);
  return g;
}

Eigen::MatrixXd LevelSetFunction::hessian(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  MESHMORPH_CHECK(x.size() == dim_, "LevelSetFunction::hessian: point of the wrong dimension");
  return root_->hessian(x);
}

double LevelSetFunction::stationarity(const Eigen::Ref<const Eigen::VectorXd>& x,
                                      const Eigen::Ref<const Eigen::VectorXd>& g) const {
  MESHMORPH_CHECK(x.size() == dim_ && g.size() == dim_, "LevelSetFunction::stationarity: vector of the wrong dimension");
  return root_->stationarity(x, g);
}

Eigen::MatrixXd LevelSetFunction::step_normals(const Eigen::Ref<const Eigen::VectorXd>& x,
                                               const Eigen::Ref<const Eigen::VectorXd>& g) const {
  MESHMORPH_CHECK(x.size() == dim_ && g.size() == dim_, "LevelSetFunction::step_normals: vector of the wrong dimension");
  return root_->step_normals(x, g);
}

LevelSetPoint LevelSetFunction::at(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  MESHMORPH_CHECK(x.size() == dim_, "LevelSetFunction::at: point of the wrong dimension");
  return LevelSetPoint(root_, root_->at(x), dim_);
}

std::optional<Eigen::VectorXd> LevelSetFunction::closest_point(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  MESHMORPH_CHECK(x.size() == dim_, "LevelSetFunction::closest_point: point of the wrong dimension");
  if (!x.allFinite()) return std::nullopt;
  return root_->closest_point(x);
}

}  // namespace meshmorph

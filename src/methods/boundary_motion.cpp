// SPDX-License-Identifier: MIT
#include "meshmorph/methods/boundary_motion.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include "meshmorph/error.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/geometry/level_set_function.h"

namespace meshmorph {
namespace {

template <class... F>
struct Overloaded : F... {
  using F::operator()...;
};
template <class... F>
Overloaded(F...) -> Overloaded<F...>;

bool moves(const Motion& m) {
  return !std::holds_alternative<FixedMotion>(m) && !std::holds_alternative<SlideMotion>(m);
}

Eigen::MatrixXd rotation(const RotateMotion& r, int dim, double t) {
  const double angle = t * r.degrees * M_PI / 180.0;
  if (dim == 2) return Eigen::Rotation2D<double>(angle).toRotationMatrix();
  return Eigen::AngleAxis<double>(angle, Eigen::Vector3d(r.axis->normalized())).toRotationMatrix();
}

}  // namespace

BoundaryMotion::BoundaryMotion(const std::vector<BoundaryCondition>& boundary, const std::string& file, const Mesh& mesh,
                               const Topology& topology)
    : mesh_(&mesh) {
  const int d = mesh.dim;
  const auto n = static_cast<Eigen::Index>(mesh.n_nodes());
  const double length = (mesh.x.rowwise().maxCoeff() - mesh.x.rowwise().minCoeff()).norm();
  std::vector<std::uint8_t> on_boundary(mesh.n_nodes(), 0);
  for (std::int32_t node : boundary_nodes(mesh, topology)) on_boundary[node] = 1;

  targets_.role.assign(mesh.n_nodes(), NodeRole::Free);
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (on_boundary[i]) targets_.role[i] = NodeRole::Fixed;
  targets_.target = mesh.x;
  targets_.normal = Eigen::MatrixXd::Zero(d, n);
  end_ = mesh.x;
  owner_.assign(mesh.n_nodes(), -1);
  const std::unordered_map<std::int64_t, std::int32_t> index_of_tag = mesh.node_index_of_tag();

  for (std::size_t e = 0; e < boundary.size(); ++e) {
    const BoundaryCondition& bc = boundary[e];
    motions_.push_back(bc.motion);
    const std::vector<std::int32_t> nodes = mesh.group_nodes(*mesh.find_group(bc.group));
    // An embedded curve or an internal interface: its nodes are free, so the entry would do
    // nothing and the run report its goal reached.
    if (std::none_of(nodes.begin(), nodes.end(), [&](std::int32_t v) { return on_boundary[static_cast<std::size_t>(v)]; }))
      throw InputError(file + ": " + bc.key_path + ".group: no node of group \"" + bc.group +
                       "\" is on the boundary of the mesh (boundary entries move or hold boundary nodes; the others "
                       "follow)");
    if (!moves(bc.motion)) continue;
    // The final position of each boundary node of the group.
    auto place = [&](std::int32_t node, const Eigen::VectorXd& target) {
      if (owner_[node] >= 0) {
        if ((end_.col(node) - target).norm() > 1e-12 * length)
          throw InputError(file + ": " + bc.key_path + ": node " + std::to_string(mesh.node_tags[node]) +
                           " is also moved by " + boundary[owner_[node]].key_path + " to a different target");
        return;
      }
      owner_[node] = static_cast<std::int32_t>(e);
      end_.col(node) = target;
    };
    std::visit(Overloaded{
                   [&](const TranslateMotion& m) {
                     for (std::int32_t node : nodes)
                       if (on_boundary[node]) place(node, mesh.x.col(node) + m.displacement);
                   },
                   [&](const RotateMotion& m) {
                     const Eigen::MatrixXd R = rotation(m, d, 1.0);
                     for (std::int32_t node : nodes)
                       if (on_boundary[node]) place(node, m.center + R * (mesh.x.col(node) - m.center));
                   },
                   [&](const ScaleMotion& m) {
                     for (std::int32_t node : nodes)
                       if (on_boundary[node]) place(node, m.center + m.factor * (mesh.x.col(node) - m.center));
                   },
                   [&](const ProjectMotion& m) {
                     LevelSetOptions lo;
                     lo.source = file;
                     lo.length_scale = length;
                     const LevelSetFunction ls(m.target, d, lo);
                     for (std::int32_t node : nodes) {
                       if (!on_boundary[node]) continue;
                       const std::optional<Eigen::VectorXd> p = ls.closest_point(mesh.x.col(node));
                       if (!p)
                         throw InputError(file + ": " + bc.key_path + ".project: node " + std::to_string(mesh.node_tags[node]) +
                                          " cannot reach the level set (no closest point found from it)");
                       place(node, *p);
                     }
                   },
                   [&](const DisplaceMotion& m) {
                     std::vector<std::uint8_t> given(mesh.n_nodes(), 0);
                     for (std::size_t k = 0; k < m.table.node_tags.size(); ++k) {
                       const std::int32_t node = index_of_tag.at(m.table.node_tags[k]);  // of the group (case_check)
                       given[node] = 1;
                       if (on_boundary[node]) place(node, mesh.x.col(node) + m.table.displacement.col(static_cast<Eigen::Index>(k)));
                     }
                     for (std::int32_t node : nodes)
                       if (on_boundary[node] && !given[node])
                         throw InputError(file + ": " + bc.key_path + ".displace: " + m.table.file.string() +
                                          " has no row for node " + std::to_string(mesh.node_tags[node]) + " of group \"" +
                                          bc.group + "\"");
                   },
                   [](const auto&) {},
               },
               bc.motion);
  }
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (owner_[i] >= 0) targets_.role[i] = NodeRole::Prescribed;
  targets_.target = end_;
  if (const auto bad = coordinate_range_problem(end_); bad && bad->node >= 0)
    throw InputError(file + ": " + boundary[static_cast<std::size_t>(owner_[static_cast<std::size_t>(bad->node)])].key_path +
                     ": node " + std::to_string(mesh.node_tags[static_cast<std::size_t>(bad->node)]) + ": the target's " +
                     bad->what);

  // Nodes that stay put whatever slide group they are on: those of a `fixed` group (the rim of
  // a fixed wall against a sliding one: sliding would take it off the fixed wall), and those
  // on two slide planes at an angle (below).
  std::vector<std::uint8_t> held(mesh.n_nodes(), 0);
  for (const BoundaryCondition& bc : boundary)
    if (std::holds_alternative<FixedMotion>(bc.motion))
      for (std::int32_t node : mesh.group_nodes(*mesh.find_group(bc.group))) held[node] = 1;
  // Slide groups: the plane through the group's nodes (least squares), which must fit them.
  for (const BoundaryCondition& bc : boundary) {
    if (!std::holds_alternative<SlideMotion>(bc.motion)) continue;
    const std::vector<std::int32_t> nodes = mesh.group_nodes(*mesh.find_group(bc.group));
    Eigen::VectorXd centre = Eigen::VectorXd::Zero(d);
    for (std::int32_t node : nodes) centre += mesh.x.col(node);
    centre /= static_cast<double>(nodes.size());
    Eigen::MatrixXd cov = Eigen::MatrixXd::Zero(d, d);
    for (std::int32_t node : nodes) cov += (mesh.x.col(node) - centre) * (mesh.x.col(node) - centre).transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(cov);
    const Eigen::VectorXd normal = eig.eigenvectors().col(0);
    for (std::int32_t node : nodes)
      if (std::abs(normal.dot(mesh.x.col(node) - centre)) > 1e-9 * length)
        throw InputError(file + ": " + bc.key_path + ".slide: group \"" + bc.group +
                         "\" is not planar (node " + std::to_string(mesh.node_tags[node]) + " is off its plane)");
    for (std::int32_t node : nodes) {
      if (!on_boundary[node] || held[node]) continue;
      if (targets_.role[node] == NodeRole::Fixed) {
        targets_.role[node] = NodeRole::Slide;
        targets_.normal.col(node) = normal;
      } else if (targets_.role[node] == NodeRole::Slide && std::abs(targets_.normal.col(node).dot(normal)) < 1.0 - 1e-9) {
        // On two planes that meet at an angle (a corner of sliding walls): in 2D their
        // intersection is the node itself; in 3D it is a line, which one normal cannot hold,
        // so the node stays put rather than leave either plane. (Sliding on one of them let
        // the scale-free distortion blow the domain up: corners 10 box sizes away.)
        targets_.role[node] = NodeRole::Fixed;
        targets_.normal.col(node).setZero();
        held[node] = 1;
      }
    }
  }
}

Eigen::MatrixXd BoundaryMotion::at(double t) const {
  const Mesh& mesh = *mesh_;
  Eigen::MatrixXd x = mesh.x;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    if (owner_[i] < 0) continue;
    const Motion& motion = motions_[static_cast<std::size_t>(owner_[i])];
    const Eigen::VectorXd x0 = mesh.x.col(static_cast<Eigen::Index>(i));
    if (const auto* r = std::get_if<RotateMotion>(&motion))
      x.col(static_cast<Eigen::Index>(i)) = r->center + rotation(*r, mesh.dim, t) * (x0 - r->center);
    else
      // Translate, displace and project move along straight lines, scale too (1 + t(f − 1)).
      x.col(static_cast<Eigen::Index>(i)) = x0 + t * (end_.col(static_cast<Eigen::Index>(i)) - x0);
  }
  return x;
}

}  // namespace meshmorph

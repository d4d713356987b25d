// SPDX-License-Identifier: MIT
#include "meshmorph/methods/deform.h"

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/fem/trace.h"
#include "meshmorph/fem/validity.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

// The unit square (cube): "bottom" is the design, moved up by a Gaussian bump of height
// `height` (its nodes Prescribed to x + g(x) e_y), the other sides are the fixed far field.
BoundaryTargets bump(const Mesh& mesh, const Topology& topo, double height) {
  BoundaryTargets bc;
  bc.role.assign(mesh.n_nodes(), NodeRole::Free);
  for (std::int32_t v : boundary_nodes(mesh, topo)) bc.role[static_cast<std::size_t>(v)] = NodeRole::Fixed;
  bc.target = mesh.x;
  bc.normal = Eigen::MatrixXd::Zero(mesh.dim, mesh.x.cols());
  const int up = mesh.dim - 1;
  for (std::int32_t v : mesh.group_nodes(*mesh.find_group("bottom"))) {
    const double r2 = (mesh.x.col(v).head(mesh.dim - 1).array() - 0.5).square().sum();
    bc.role[static_cast<std::size_t>(v)] = NodeRole::Prescribed;
    bc.target(up, v) += height * std::exp(-r2 / 0.02);
  }
  return bc;
}

// The result is valid, the Fixed nodes within `fixed_tolerance` of where they were (0: exactly
// there) and, without the CVT step, the Prescribed nodes exactly on their targets.
void expect_valid_far_field_in_place(const Mesh& mesh, const BoundaryTargets& bc, const DeformResult& r, bool cvt,
                                     double fixed_tolerance) {
  Mesh moved = mesh;
  moved.x = r.x;
  EXPECT_EQ(count_invalid_cells(moved), 0u) << "cvt " << cvt;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
    const auto c = static_cast<Eigen::Index>(i);
    if (bc.role[i] == NodeRole::Fixed) {
      if (fixed_tolerance == 0.0) {
        EXPECT_TRUE(r.x.col(c) == mesh.x.col(c)) << i;
      } else {
        EXPECT_LE((r.x.col(c) - mesh.x.col(c)).norm(), fixed_tolerance) << i;
      }
    }
    if (bc.role[i] == NodeRole::Prescribed && !cvt) {
      EXPECT_TRUE(r.x.col(c) == bc.target.col(c)) << i;
    }
  }
}

TEST(Deform, NoMotionLeavesTheMeshAlone) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 8);
  const Topology topo = build_topology(mesh);
  DeformOptions o;
  o.cvt = false;
  const DeformResult r = deform(mesh, topo, bump(mesh, topo, 0.0), mesh.x, o);
  ASSERT_TRUE(r.converged) << r.message;
  EXPECT_LT((r.x - mesh.x).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_EQ(r.linear_solves, 2);
}

// A large local bump: the Eikonal extension keeps every cell valid, the design nodes reach
// their targets, the far field does not move; with the CVT step the design nodes stay on the
// raised (discrete) surface and are spread more evenly.
TEST(Deform, LargeBumpStaysValid) {
  for (ElementType type : {ElementType::Triangle, ElementType::Quadrilateral, ElementType::Tetrahedron})
    for (int order : {1, 2}) {
      SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order));
      const int n = type == ElementType::Tetrahedron ? 8 / order : 16;
      const Mesh mesh = structured_mesh(type, order, n);
      const Topology topo = build_topology(mesh);
      const BoundaryTargets bc = bump(mesh, topo, 0.3);
      for (bool cvt : {false, true}) {
        DeformOptions o;
        o.cvt = cvt;
        const DeformResult r = deform(mesh, topo, bc, mesh.x, o);
        ASSERT_TRUE(r.converged) << r.message;
        // The far field stays, but for the curved facets under the design's rim, which follow
        // the rim's corners (the bump's foot there: 0.3 e^(−12.5)).
        expect_valid_far_field_in_place(mesh, bc, r, cvt, order == 1 ? 0.0 : 0.3 * std::exp(-0.25 / 0.02) * (1 + 1e-12));
        if (cvt && mesh.dim == 2) {
          EXPECT_LT(r.cvt.spacing_ratio_after, r.cvt.spacing_ratio_before);
        }
      }
    }
}

// The top side (the design) translated as a whole, the other sides fixed: the displacement
// of a corner runs along the fixed side's first facet as it does on a linear mesh, and the
// side's curved-facet nodes stay on the line between their facet's corners.
TEST(Deform, CurvedSideFacetsFollowAMovingCorner) {
  std::size_t straightened = 0;
  for (ElementType type : {ElementType::Triangle, ElementType::Quadrilateral})
    for (int order : {1, 2, 3})
      for (const Eigen::Vector2d& shift : {Eigen::Vector2d(0.0, -0.05), Eigen::Vector2d(0.1, 0.0), Eigen::Vector2d(0.1, -0.1)}) {
        SCOPED_TRACE(std::string(name_of(type)) + " order " + std::to_string(order) + " shift " +
                     std::to_string(shift.x()) + ", " + std::to_string(shift.y()));
        const Mesh mesh = structured_mesh(type, order, 5);
        const Topology topo = build_topology(mesh);
        BoundaryTargets bc = bump(mesh, topo, 0.0);
        for (std::int32_t v : mesh.group_nodes(*mesh.find_group("bottom"))) bc.role[static_cast<std::size_t>(v)] = NodeRole::Fixed;
        for (std::int32_t v : mesh.group_nodes(*mesh.find_group("top"))) {
          bc.role[static_cast<std::size_t>(v)] = NodeRole::Prescribed;
          bc.target.col(v) += shift;
        }
        const DeformResult r = deform(mesh, topo, bc, mesh.x);
        ASSERT_TRUE(r.converged) << r.message;
        Mesh moved = mesh;
        moved.x = r.x;
        EXPECT_EQ(count_invalid_cells(moved), 0u);
        if (order == 1) {
          EXPECT_EQ(r.straightened_cells, 0u);
        }
        // The fixed sides' nodes below the top corners' facets stay; those in the facets
        // under the corners lie on the straight line from the fixed corner to the moved one.
        for (const char* side : {"left", "right"})
          for (std::int32_t v : mesh.group_nodes(*mesh.find_group(side))) {
            const double x0 = mesh.x(0, v), y0 = mesh.x(1, v), top = 1.0 - 1.0 / 5;
            if (y0 >= 1.0) continue;
            const double t = std::max(0.0, (y0 - top) / (1.0 - top));
            EXPECT_NEAR(r.x(0, v), x0 + t * shift.x(), 1e-14) << side << " node " << v;
            EXPECT_NEAR(r.x(1, v), y0 + t * shift.y(), 1e-14) << side << " node " << v;
          }
        straightened += r.straightened_cells;
      }
  EXPECT_GT(straightened, 0u);  // the sideways motions fold curved cells next to the walls
}

// Sides that slide keep their plane (x = 0, 1), and their nodes follow the bump upwards.
TEST(Deform, SlideNodesStayOnTheirPlane) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 16);
  const Topology topo = build_topology(mesh);
  BoundaryTargets bc = bump(mesh, topo, 0.3);
  for (const char* side : {"left", "right"})
    for (std::int32_t v : mesh.group_nodes(*mesh.find_group(side)))
      if (bc.role[static_cast<std::size_t>(v)] == NodeRole::Fixed && mesh.x(1, v) < 1.0) {
        bc.role[static_cast<std::size_t>(v)] = NodeRole::Slide;
        bc.normal(0, v) = 1.0;
      }
  const DeformResult r = deform(mesh, topo, bc, mesh.x);
  ASSERT_TRUE(r.converged) << r.message;
  Mesh moved = mesh;
  moved.x = r.x;
  EXPECT_EQ(count_invalid_cells(moved), 0u);
  double rise = 0.0;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (bc.role[i] == NodeRole::Slide) {
      const auto c = static_cast<Eigen::Index>(i);
      EXPECT_EQ(r.x(0, c), mesh.x(0, c));
      rise = std::max(rise, r.x(1, c) - mesh.x(1, c));
    }
  EXPECT_GT(rise, 0.0);
}

// Assembly and the CVT sweeps are parallel; the result is the same bits for 1 and 3 threads.
TEST(Deform, SameBitsForAnyThreadCount) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 2, 24);  // 1152 cells: parallel assembly
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = bump(mesh, topo, 0.3);
  DeformOptions one, three;
  one.threads = 1;
  three.threads = 3;
  EXPECT_TRUE(deform(mesh, topo, bc, mesh.x, one).x == deform(mesh, topo, bc, mesh.x, three).x);
}

TEST(Deform, NeedsADesignAndAFarField) {
  const Mesh mesh = structured_mesh(ElementType::Triangle, 1, 4);
  const Topology topo = build_topology(mesh);
  BoundaryTargets bc = bump(mesh, topo, 0.1);
  BoundaryTargets no_design = bc;
  for (NodeRole& r : no_design.role)
    if (r == NodeRole::Prescribed) r = NodeRole::Fixed;
  EXPECT_THROW(deform(mesh, topo, no_design, mesh.x), InputError);
  BoundaryTargets no_far = bc;
  for (NodeRole& r : no_far.role)
    if (r == NodeRole::Fixed) r = NodeRole::Prescribed;
  EXPECT_THROW(deform(mesh, topo, no_far, mesh.x), InputError);
  DeformOptions laplace;
  laplace.method = DeformMethod::Laplace;
  laplace.cvt = false;
  EXPECT_NO_THROW(deform(mesh, topo, no_far, mesh.x, laplace));
}

// The hybrid layer mesh (prisms and hexahedra under tetrahedra, pyramids between;
// tests/data/hybrid_layer.geo): its bottom raised by the bump of height 0.3, whose highest
// node (0.063) passes the layer's first row of prisms (0.033 thick). The extension carries
// the layer up: valid, the far field in place, with and without the CVT step.
TEST(Deform, AHybridLayerMeshFollowsABump) {
  const Mesh mesh = read_mesh(std::string(MESHMORPH_TEST_DATA) + "/hybrid_layer.msh");
  const Topology topo = build_topology(mesh);
  const BoundaryTargets bc = bump(mesh, topo, 0.3);
  Mesh raised = mesh;
  for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
    if (bc.role[i] == NodeRole::Prescribed) raised.x.col(static_cast<Eigen::Index>(i)) = bc.target.col(static_cast<Eigen::Index>(i));
  ASSERT_GT(count_invalid_cells(raised), 0u) << "moving the bottom alone must invert cells";
  for (bool cvt : {false, true}) {
    DeformOptions o;
    o.cvt = cvt;
    const DeformResult r = deform(mesh, topo, bc, mesh.x, o);
    ASSERT_TRUE(r.converged) << "cvt " << cvt << ": " << r.message;
    expect_valid_far_field_in_place(mesh, bc, r, cvt, 0.0);
  }
}

}  // namespace
}  // namespace meshmorph

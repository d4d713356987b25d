// SPDX-License-Identifier: MIT
// `{"mesh": {"file", "field"}}` level sets: the background mesh and its nodal field are read
// from a file (VTU PointData, MSH $NodeData) when the level set is compiled.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "geometry/level_set_fixtures.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;
using test::vec;

class MeshLevelSetFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("meshmorph_mesh_ls_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// A structured mesh with the field |x − c| − r at its nodes, written to `name`.
  fs::path write_distance_field(const std::string& name, ElementType type, int order, int n, const Eigen::VectorXd& c,
                                double r, bool binary) const {
    Mesh m = structured_mesh(type, order, n);
    Eigen::VectorXd phi(m.x.cols());
    for (Eigen::Index j = 0; j < phi.size(); ++j) phi(j) = (m.x.col(j) - c).norm() - r;
    m.node_fields["phi"] = phi;
    m.node_fields["other"] = Eigen::VectorXd::Zero(m.x.cols());
    const fs::path p = dir_ / name;
    WriteOptions opt;
    opt.binary = binary;
    if (name.ends_with("_22.msh")) opt.format = MeshFormat::Msh22;
    write_mesh(p, m, opt);
    return p;
  }

  static LevelSet from_file(const fs::path& file, std::string field = "phi") {
    return test::level_set(MeshLevelSet{file, std::move(field)}, "interface");
  }

  /// Compiling throws InputError whose message contains every fragment of `expected`.
  static void expect_input_error(const LevelSet& ls, int dim, std::initializer_list<std::string> expected) {
    try {
      LevelSetFunction f(ls, dim, {"case.json", 1.0});
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      for (const std::string& s : expected) EXPECT_NE(std::string(e.what()).find(s), std::string::npos) << e.what();
    }
  }

  fs::path dir_;
};

// P2 interpolation (h = 1/16) of the distance to a circle, whose third derivatives grow like
// 1/ρ² (ρ ≥ 0.15 from the centre here): measured errors 1.8e-4 in σ, 2.1e-2 in ∇σ, 2.5e-4
// in the closest points; every format gives the same field bit for bit.
TEST_F(MeshLevelSetFile, ReadsTheFieldFromEveryFormatAndApproximatesTheAnalyticLevelSet) {
  const Eigen::VectorXd c = vec({0.45, 0.5});
  const double r = 0.3;
  const LevelSetFunction exact(test::sphere(c, r), 2);
  std::optional<double> first_value;
  for (const auto& [name, binary] : {std::pair{"circle.msh", true}, std::pair{"circle_22.msh", false},
                                     std::pair{"circle.vtu", false}, std::pair{"circle_b.vtu", true}}) {
    SCOPED_TRACE(name);
    const fs::path file = write_distance_field(name, ElementType::Triangle, 2, 16, c, r, binary);
    const LevelSetFunction f(from_file(file), 2, {"case.json", 1.0});
    EXPECT_EQ(f.dim(), 2);
    const double v = f.value(vec({0.3, 0.7}));
    if (!first_value) first_value = v;
    EXPECT_EQ(v, *first_value);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(0.02, 0.98);
    double max_value_error = 0, max_gradient_error = 0;
    for (int i = 0; i < 200; ++i) {
      const Eigen::VectorXd x = vec({u(rng), u(rng)});
      if ((x - c).norm() < 0.15) continue;  // the cone's tip is not smooth
      max_value_error = std::max(max_value_error, std::abs(f.value(x) - exact.value(x)));
      max_gradient_error = std::max(max_gradient_error, (f.gradient(x) - exact.gradient(x)).norm());
    }
    EXPECT_LT(max_value_error, 5e-4);
    EXPECT_LT(max_gradient_error, 5e-2);
    for (const auto& x : {vec({0.1, 0.1}), vec({0.5, 0.55}), vec({0.95, 0.4})}) {
      const auto p = f.closest_point(x);
      ASSERT_TRUE(p.has_value());
      EXPECT_LT((*p - *exact.closest_point(x)).norm(), 5e-4);
    }
  }
}

TEST_F(MeshLevelSetFile, ThreeDimensionalBackgroundInACsgTree) {
  const Eigen::VectorXd c = vec({0.5, 0.5, 0.5});
  const fs::path file = write_distance_field("ball.vtu", ElementType::Tetrahedron, 2, 8, c, 0.3, true);
  // The ball minus the half space z < 0.5.
  const LevelSet tree = test::level_set(
      DifferenceLevelSet{{from_file(file), test::level_set(PlaneLevelSet{vec({0.5, 0.5, 0.5}), vec({0, 0, 1})})}},
      "interface");
  const LevelSetFunction f(tree, 3, {"case.json", 1.0});
  const LevelSetFunction ball(test::sphere(c, 0.3), 3);
  const Eigen::VectorXd above = vec({0.6, 0.4, 0.75});
  EXPECT_NEAR(f.value(above), ball.value(above), 1e-3);  // measured 1.9e-4
  EXPECT_NEAR(f.value(vec({0.5, 0.5, 0.2})), 0.3, 1e-12);  // the plane is active below its level
}

TEST_F(MeshLevelSetFile, ErrorsNameTheKeyPathTheFileAndWhatIsWrong) {
  const fs::path file = write_distance_field("bg.msh", ElementType::Triangle, 1, 4, vec({0.5, 0.5}), 0.3, false);
  expect_input_error(from_file(file, "psi"), 2,
                     {"case.json: interface.mesh.field: ", file.string(), "has no nodal field \"psi\"",
                      "its nodal fields: \"other\", \"phi\""});
  expect_input_error(from_file(file), 3,
                     {"case.json: interface.mesh.file: ", file.string(), "is a 2D mesh, but the level set is 3D"});

  Mesh bare = structured_mesh(ElementType::Triangle, 1, 2);
  write_mesh(dir_ / "bare.vtu", bare);
  expect_input_error(from_file(dir_ / "bare.vtu"), 2, {"interface.mesh.field: ", "(it has no nodal fields)"});

  // A non-finite value names the node (by its file tag).
  Mesh m = structured_mesh(ElementType::Triangle, 1, 2);
  for (std::size_t j = 0; j < m.n_nodes(); ++j) m.node_tags[j] = 100 + static_cast<std::int64_t>(j);
  Eigen::VectorXd phi = Eigen::VectorXd::Zero(m.x.cols());
  phi(4) = std::numeric_limits<double>::quiet_NaN();
  m.node_fields["phi"] = phi;
  write_mesh(dir_ / "nan.msh", m);
  expect_input_error(from_file(dir_ / "nan.msh"), 2,
                     {"case.json: interface.mesh.field: nodal field \"phi\" of ", "nan.msh",
                      "the value at node 104 is not finite"});

  // A malformed file: the reader's message (file and line) after the key path.
  std::ofstream(dir_ / "broken.msh") << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 x\n";
  expect_input_error(from_file(dir_ / "broken.msh"), 2,
                     {"case.json: interface.mesh.file: ", (dir_ / "broken.msh").string() + ": line 5: "});

  // A file that cannot be opened is an IoError, with the key path too.
  try {
    LevelSetFunction f(from_file(dir_ / "missing.msh"), 2, {"case.json", 1.0});
    ADD_FAILURE() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("case.json: interface.mesh.file: "), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace meshmorph

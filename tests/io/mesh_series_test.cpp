// SPDX-License-Identifier: MIT
// A moving mesh in one CGNS or Exodus II file: read back as its last step, with the cells and
// groups of a plain write; fields on a single mesh leave its coordinates as they were; steps
// that do not match are refused with nothing written.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "io/mesh_compare.h"
#include "meshmorph/error.h"
#include "meshmorph/fem/structured.h"
#include "meshmorph/io/mesh_io.h"
#include "meshmorph/io/mesh_series.h"

namespace meshmorph {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / ("meshmorph_series_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  return dir / name;
}

constexpr double k_dt = 0.25;

// Step k of a motion that bends the mesh more at each step (k = 0: the start).
Eigen::MatrixXd positions(const Mesh& m, int k) {
  Eigen::MatrixXd x = m.x;
  for (Eigen::Index j = 0; j < x.cols(); ++j) x(0, j) += 0.03 * k * std::sin(3.0 * m.x(1, j) + 0.1 * static_cast<double>(j));
  return x;
}

// The steps as a morph gives them: displacement from the start, velocity from the step before,
// a quality per cell.
MeshStep step_of(const Mesh& m, int k) {
  MeshStep s;
  s.time = (k + 1) * k_dt;
  s.x = positions(m, k + 1);
  s.point_vectors["displacement"] = s.x - m.x;
  s.point_vectors["mesh_velocity"] = (s.x - positions(m, k)) / k_dt;
  s.cell_data["quality"] = std::vector<double>(m.n_cells(), 0.5 + 0.1 * k);
  return s;
}

class MeshSeries : public ::testing::TestWithParam<std::string> {};

TEST_P(MeshSeries, ReadsAsItsLastStep) {
  for (const auto& [type, order] : {std::pair{ElementType::Triangle, 2}, std::pair{ElementType::Tetrahedron, 1}}) {
    const Mesh m = structured_mesh(type, order, 2);
    SCOPED_TRACE(std::string(name_of(type)) + " " + GetParam());
    const fs::path p = scratch("series" + GetParam());
    write_mesh_series(p, m, 3, [&](int k) { return step_of(m, k); });
    Mesh last = m;
    last.x = positions(m, 3);
    const fs::path plain = scratch("plain" + GetParam());
    write_mesh(plain, last);
    // Exodus keeps the start and adds the last displacement to it: equal to rounding.
    const double tolerance = GetParam() == ".cgns" ? 0.0 : 1e-15;
    test::expect_meshes_equal(read_mesh(plain), read_mesh(p), {.node_tags = true, .entities = false, .tolerance = tolerance});
    fs::remove(p);
    fs::remove(plain);
  }
}

TEST_P(MeshSeries, FieldsOnOneMeshKeepItsCoordinates) {
  const Mesh m = structured_mesh(ElementType::Hexahedron, 2, 2);
  const MeshStep s = step_of(m, 0);
  Mesh moved = m;
  moved.x = s.x;
  const fs::path p = scratch("fields" + GetParam()), plain = scratch("nofields" + GetParam());
  WriteOptions fields;
  fields.cell_data = s.cell_data;
  fields.point_vectors = s.point_vectors;
  write_mesh(p, moved, fields);
  write_mesh(plain, moved);
  test::expect_meshes_equal(read_mesh(plain), read_mesh(p), {.node_tags = true, .entities = false});
  fs::remove(p);
  fs::remove(plain);
}

TEST_P(MeshSeries, StepsWithOtherFieldsAreRefused) {
  const Mesh m = structured_mesh(ElementType::Quadrilateral, 1, 2);
  const fs::path p = scratch("mismatch" + GetParam());
  try {
    write_mesh_series(p, m, 2, [&](int k) {
      MeshStep s = step_of(m, k);
      if (k == 1) s.cell_data.clear();
      return s;
    });
    ADD_FAILURE() << "no exception";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(p.string() + ": step 2 of the series holds other fields than step 1"), std::string::npos)
        << e.what();
  }
  EXPECT_FALSE(fs::exists(p));
}

INSTANTIATE_TEST_SUITE_P(CgnsAndExodus, MeshSeries, ::testing::Values(".cgns", ".exo"),
                         [](const ::testing::TestParamInfo<std::string>& param) { return param.param.substr(1); });

TEST(MeshSeriesFormats, OnlyCgnsAndExodus) {
  EXPECT_TRUE(is_series_format("a.CGNS"));
  EXPECT_TRUE(is_series_format("dir/a.e"));
  EXPECT_TRUE(is_series_format("a.ex2"));
  EXPECT_FALSE(is_series_format("a.vtu"));
  const Mesh m = structured_mesh(ElementType::Triangle, 1, 1);
  const fs::path p = scratch("series.msh");
  EXPECT_THROW(write_mesh_series(p, m, 1, [&](int k) { return step_of(m, k); }), InputError);
  EXPECT_FALSE(fs::exists(p));
}

}  // namespace
}  // namespace meshmorph

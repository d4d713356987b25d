// SPDX-License-Identifier: MIT
#include <string>

#include <gtest/gtest.h>

#include "geometry/level_set_fixtures.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

using test::vec;

/// Compiling `ls` in `dim` throws InputError whose message contains `expected`.
void expect_input_error(const LevelSet& ls, int dim, const std::string& expected) {
  try {
    LevelSetFunction f(ls, dim, {"case.json", 1.0});
    ADD_FAILURE() << "no InputError, expected: " << expected;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(expected), std::string::npos) << e.what();
  }
}

LevelSet at(decltype(LevelSet::shape) shape, const char* key_path = "boundary[1].project") {
  return test::level_set(std::move(shape), key_path);
}

TEST(LevelSetErrors, WrongDimensionsNameTheKeyPath) {
  expect_input_error(at(SphereLevelSet{vec({0, 0, 0}), 1}), 2,
                     "case.json: boundary[1].project.sphere.center: expected 2 numbers for a 2D level set, found 3");
  expect_input_error(at(PlaneLevelSet{vec({0, 0}), vec({0, 0, 1})}), 3, "boundary[1].project.plane.point");
  expect_input_error(at(BoxLevelSet{vec({0, 0, 0}), vec({1, 1})}), 3, "boundary[1].project.box.size");
  expect_input_error(at(CylinderLevelSet{vec({0, 0}), vec({0, 1}), 1}), 2,
                     "boundary[1].project.cylinder: an infinite cylinder exists only in 3D");
  expect_input_error(at(TorusLevelSet{vec({0, 0}), vec({0, 1}), 2, 1}), 2, "boundary[1].project.torus: a torus");
}

TEST(LevelSetErrors, DegenerateShapes) {
  expect_input_error(at(SphereLevelSet{vec({0, 0}), 0}), 2, "sphere.radius: expected a positive number");
  expect_input_error(at(PlaneLevelSet{vec({0, 0}), vec({0, 0})}), 2, "plane.normal: expected a non-zero direction");
  expect_input_error(at(BoxLevelSet{vec({0, 0}), vec({1, -1})}), 2, "box.size: expected positive edge lengths");
  expect_input_error(at(CylinderLevelSet{vec({0, 0, 0}), vec({0, 0, 0}), 1}), 3, "cylinder.axis");
  expect_input_error(at(TorusLevelSet{vec({0, 0, 0}), vec({0, 0, 1}), 1, 1}), 3, "torus.minor");
  expect_input_error(at(SphereLevelSet{vec({0, std::nan("")}), 1}), 2, "sphere.center: expected finite numbers");
}

TEST(LevelSetErrors, CsgOperandCountsAndNestedOperands) {
  expect_input_error(at(UnionLevelSet{}), 2, "boundary[1].project.union: expected at least 1 level set");
  expect_input_error(at(DifferenceLevelSet{{test::sphere(vec({0, 0}), 1)}}), 2,
                     "project.difference: expected exactly 2 level sets, found 1");
  const LevelSet bad_operand = at(SphereLevelSet{vec({0, 0, 0}), 1}, "interface.intersection[1]");
  expect_input_error(at(IntersectionLevelSet{{test::sphere(vec({0, 0}), 1), bad_operand}}, "interface"), 2,
                     "case.json: interface.intersection[1].sphere.center");
}

// Reading the file is tested in mesh_level_set_file_test.cpp; one that cannot be opened
// is an IoError naming the key path.
TEST(LevelSetErrors, MeshFieldFromAMissingFileIsAnIoError) {
  try {
    LevelSetFunction f(at(MeshLevelSet{"no_such_background.msh", "phi"}, "interface"), 2, {"case.json", 1.0});
    ADD_FAILURE() << "no IoError";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("case.json: interface.mesh.file: no_such_background.msh"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/app/report.h"

#include <fstream>

#include <gtest/gtest.h>

#include "app/temp_dir.h"
#include "meshmorph/error.h"

namespace meshmorph {
namespace {

Report sample_report() {
  Report r;
  r.method = "morph";
  r.case_file = "examples/01/case.json";
  r.dim = 3;
  r.order = 2;
  r.nodes = 13522;
  r.elements = 71234;
  r.valid = true;
  r.inverted_elements = 0;
  r.flipped_elements = 0;
  r.cell_volume = 2.5;
  r.enclosed_volume = 2.5;
  r.min_quality = 0.575;
  r.mean_quality = 0.93;
  r.min_shape_quality = 0.31;
  r.min_scaled_jacobian = 0.22;
  r.boundary_error_max = 3e-9;
  r.boundary_error_l2 = 1e-9;
  r.iterations = IterationCounts{6, 8, 16, 16};
  r.seconds = 1.23;
  r.timings = Timings{{0.41, 0.05, 0.08, 0.21, 0.36, 0.04, 0.08}};
  r.converged = true;
  r.message = "converged: constraint norm 3e-9 < 1e-8";
  r.history = {{{"outer", 1}, {"constraint_norm", 0.8}, {"min_quality", 0.41}, {"mu", 10.0}},
               {{"outer", 2}, {"constraint_norm", 1e-3}, {"min_quality", 0.5}, {"mu", 100.0}}};
  return r;
}

TEST(Report, WritesTheDocumentedKeysInOrder) {
  const auto j = report_to_json(sample_report());
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  const std::vector<std::string> expected = {
      "meshmorph_version", "method", "case", "dim", "order", "nodes", "elements", "valid", "inverted_elements",
      "flipped_elements", "boundary_crossings", "cell_volume", "enclosed_volume", "min_quality", "mean_quality", "min_shape_quality", "min_scaled_jacobian", "boundary_error_max",
      "boundary_error_l2", "fit_error_max", "iterations", "seconds", "peak_memory_mb", "converged", "message",
      "history", "timings"};
  EXPECT_EQ(keys, expected);
  EXPECT_TRUE(j["fit_error_max"].is_null());
  EXPECT_EQ(j["iterations"]["newton"], 16);
  EXPECT_EQ(j["history"][1]["mu"], 100.0);
  EXPECT_EQ(j["history"][0].begin().key(), "outer");
  std::vector<std::string> phases;
  for (const auto& item : j["timings"].items()) phases.push_back(item.key());
  EXPECT_EQ(phases, (std::vector<std::string>{"assembly", "validity", "line_search", "solver_setup", "solve", "io", "other"}));
  EXPECT_EQ(j["timings"]["solver_setup"], 0.21);
}

TEST(Report, NotApplicableAndNonFiniteValuesAreNull) {
  Report r;
  r.method = "quality";
  r.min_quality = std::numeric_limits<double>::infinity();
  r.history = {{{"x", std::nan("")}}};
  const auto j = report_to_json(r);
  for (const char* key : {"case", "min_quality", "mean_quality", "min_shape_quality", "min_scaled_jacobian",
                          "boundary_error_max", "boundary_error_l2", "fit_error_max", "iterations", "peak_memory_mb"})
    EXPECT_TRUE(j[key].is_null()) << key;
  EXPECT_TRUE(j["history"][0]["x"].is_null());
}

TEST(Report, RoundTripsThroughAFile) {
  test::TempDir dir;
  const auto path = dir.path() / "report.json";
  const Report in = sample_report();
  write_report(path, in);
  const Report out = read_report(path);
  Report expected = in;
  expected.meshmorph_version = meshmorph_version();
  ASSERT_TRUE(out.peak_memory_mb);
  EXPECT_GT(*out.peak_memory_mb, 0.0);
  expected.peak_memory_mb = out.peak_memory_mb;
  EXPECT_EQ(out, expected);
  EXPECT_EQ(out.meshmorph_version, "0.1.0");
  // Only the report itself is left in the folder: the temporary file was renamed.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()), std::filesystem::directory_iterator()), 1);
}

// Reports written before the injectivity keys and timings existed read back, with 0 flipped
// cells and no timings.
TEST(Report, ReadsReportsWithoutTheInjectivityKeys) {
  auto j = report_to_json(sample_report());
  j.erase("flipped_elements");
  j.erase("boundary_crossings");
  j.erase("cell_volume");
  j.erase("enclosed_volume");
  j.erase("timings");
  const Report r = report_from_json(j, "r.json");
  EXPECT_FALSE(r.timings);
  EXPECT_EQ(r.flipped_elements, 0u);
  EXPECT_EQ(r.boundary_crossings, 0u);
  EXPECT_FALSE(r.cell_volume);
  EXPECT_FALSE(r.enclosed_volume);
  EXPECT_EQ(r.nodes, 13522u);
}

TEST(Report, CellTypeMinimaFollowTheTimingsAndRoundTrip) {
  Report in = sample_report();
  in.cell_types = {{"tetrahedron", 120, 0.61, 0.4, 0.35}, {"prism", 48, 0.97, std::nullopt, 0.08}};
  const auto j = report_to_json(in);
  std::vector<std::string> keys;
  for (const auto& item : j.items()) keys.push_back(item.key());
  ASSERT_GE(keys.size(), 2u);
  EXPECT_EQ(keys[keys.size() - 2], "timings");
  EXPECT_EQ(keys.back(), "cell_types");
  EXPECT_EQ(j["cell_types"].begin().key(), "tetrahedron");
  EXPECT_EQ(j["cell_types"]["prism"]["elements"], 48);
  EXPECT_EQ(j["cell_types"]["prism"]["min_quality"], 0.97);
  EXPECT_TRUE(j["cell_types"]["prism"]["min_shape_quality"].is_null());
  EXPECT_EQ(report_from_json(j, "r.json"), in);
  // A report without them has no such key and reads back with none.
  EXPECT_FALSE(report_to_json(sample_report()).contains("cell_types"));
  auto bad = j;
  bad["cell_types"]["prism"]["min_jacobian"] = 1.0;
  EXPECT_THROW(report_from_json(bad, "r.json"), InputError);
}

TEST(Report, PeakMemoryIsPositive) {
  EXPECT_GT(peak_memory_mb(), 1.0);
  EXPECT_LT(peak_memory_mb(), 1e6);
}

TEST(Report, ReadingRejectsUnknownAndMistypedKeys) {
  auto j = report_to_json(sample_report());
  j["extra"] = 1;
  EXPECT_THROW(report_from_json(j, "r.json"), InputError);
  j = report_to_json(sample_report());
  j["valid"] = "yes";
  try {
    report_from_json(j, "r.json");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "r.json: valid: expected true or false, found a string");
  }
}

}  // namespace
}  // namespace meshmorph

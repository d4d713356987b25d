// SPDX-License-Identifier: MIT
#include "meshmorph/quality/metric_registry.h"

#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

TEST(MetricRegistry, NamesPerDimension) {
  EXPECT_EQ(metric_names(2), (std::vector<std::string>{"distortion", "distortion2", "mu2", "mu77", "mu80", "edge_quality"}));
  EXPECT_EQ(metric_names(3), (std::vector<std::string>{"distortion", "distortion2", "mu303", "mu77", "mu80", "edge_quality"}));
}

TEST(MetricRegistry, EveryNameBuildsTheMetricOfThatName) {
  for (const auto& name : metric_names(2)) EXPECT_EQ(make_metric<2>(name)->name(), name);
  for (const auto& name : metric_names(3)) EXPECT_EQ(make_metric<3>(name)->name(), name);
}

TEST(MetricRegistry, ParametersReachTheMetric) {
  const MatT<2> T = Eigen::Vector2d(2, 1).asDiagonal();
  // γ = 1: μ80 = μ2 = 0.25; edge quality with n = −2: 1.25² (see edge_quality_test).
  EXPECT_DOUBLE_EQ(make_metric<2>("mu80", {{"gamma", 1.0}})->eval(T, Want::Value).mu, 0.25);
  EXPECT_NEAR(make_metric<2>("edge_quality", {{"n", -2.0}})->eval(T, Want::Value).mu, 1.5625, 1e-14);
}

void expect_input_error(const std::function<void()>& f, const std::string& needle) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(needle), std::string::npos) << e.what();
  }
}

TEST(MetricRegistry, BadNamesAndParametersAreInputErrorsNamingTheKey) {
  expect_input_error([] { make_metric<2>("mu303"); }, "mu303");  // a 3D-only metric
  expect_input_error([] { make_metric<3>("nonsense"); }, "nonsense");
  expect_input_error([] { make_metric<2>("mu2", {{"gamma", 0.5}}); }, "'gamma'");
  expect_input_error([] { make_metric<3>("mu80", {{"gama", 0.5}}); }, "'gama'");
  expect_input_error([] { make_metric<3>("mu80", {{"gamma", 2.0}}); }, "'gamma'");
  expect_input_error([] { make_metric<2>("edge_quality", {{"delta", -1.0}}); }, "'delta'");
  expect_input_error([] { make_metric<2>("edge_quality", {{"n", 1.0}}); }, "'n'");
  expect_input_error([] { metric_parameter_names("unknown"); }, "unknown");
}

}  // namespace
}  // namespace meshmorph

// SPDX-License-Identifier: MIT
#include "meshmorph/app/option_reader.h"

#include <gtest/gtest.h>

#include "meshmorph/error.h"

namespace meshmorph {
namespace {

using nlohmann::json;

struct Options {
  double tolerance = 1e-8;
  int max_newton = 50;
  bool verbose_history = false;
  std::string solver = "cholmod";
};

Options read_options(const json& j) {
  Options o;
  OptionReader r(j, "case.json");
  r.read("tolerance", o.tolerance, 0.0, 1.0);
  r.read("max_newton", o.max_newton, 1, 1000);
  r.read("verbose_history", o.verbose_history);
  r.read("solver", o.solver, {"cholmod", "cg"});
  r.finish();
  return o;
}

std::string error_of(const json& j) {
  try {
    read_options(j);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(OptionReader, KeepsDefaultsForAbsentOptions) {
  const Options o = read_options(json::object());
  EXPECT_EQ(o.tolerance, 1e-8);
  EXPECT_EQ(o.max_newton, 50);
  EXPECT_FALSE(o.verbose_history);
  EXPECT_EQ(o.solver, "cholmod");
}

TEST(OptionReader, ReadsEveryType) {
  const Options o = read_options(json::parse(R"({"tolerance": 0.5, "max_newton": 7.0, "verbose_history": true,
                                                  "solver": "cg"})"));
  EXPECT_EQ(o.tolerance, 0.5);
  EXPECT_EQ(o.max_newton, 7);
  EXPECT_TRUE(o.verbose_history);
  EXPECT_EQ(o.solver, "cg");
}

TEST(OptionReader, RejectsUnknownWrongTypeAndOutOfRange) {
  EXPECT_EQ(error_of(json::parse(R"({"max_newton": 5, "tolerence": 1})")),
            "case.json: options.tolerence: unknown option (expected one of: max_newton, solver, tolerance, "
            "verbose_history)");
  EXPECT_EQ(error_of(json::parse(R"({"tolerance": "1e-3"})")),
            "case.json: options.tolerance: expected a number, found a string");
  EXPECT_EQ(error_of(json::parse(R"({"tolerance": 2})")), "case.json: options.tolerance: expected a number in [0.0, 1.0], found 2");
  EXPECT_EQ(error_of(json::parse(R"({"max_newton": 2.5})")), "case.json: options.max_newton: expected an integer, found 2.5");
  EXPECT_EQ(error_of(json::parse(R"({"max_newton": 0})")),
            "case.json: options.max_newton: expected an integer in [1, 1000], found 0");
  EXPECT_EQ(error_of(json::parse(R"({"verbose_history": 1})")),
            "case.json: options.verbose_history: expected true or false, found a number");
  EXPECT_EQ(error_of(json::parse(R"({"solver": "lu"})")),
            "case.json: options.solver: expected one of: cholmod, cg; found \"lu\"");
}

TEST(OptionReader, MethodWithoutOptionsRejectsAny) {
  const json options = json::parse(R"({"x": 1})");
  OptionReader r(options, "c.json");
  try {
    r.finish();
    FAIL();
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "c.json: options.x: unknown option (this method takes none)");
  }
  const json array = json::array();
  EXPECT_THROW(OptionReader(array, "c.json"), InputError);
}

}  // namespace
}  // namespace meshmorph

// The validation suite's file (data/validation.toml, apps/cli/validate.cpp): the shipped suite
// has the eight views, each with its tolerance, and the clear sky's targets; a bad
// suite gets one line naming the key and what is allowed.
#include <gtest/gtest.h>

#include <algorithm>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "validate.h"

namespace {

using nephele::cli::parse_validation_suite;

TEST(ValidationSuite, TheShippedSuiteHasEightViewsThatParseAndTheSkyTargets) {
  const nephele::cli::ValidationSuite suite = nephele::cli::default_validation_suite();
  ASSERT_EQ(suite.views.size(), 8u);
  for (const auto& v : suite.views) {
    EXPECT_LE(v.max_mean_error, 0.05) << v.name;  // the target, never loosened
    nephele::Scene s = nephele::parse_scene_toml(v.scene_toml, v.name);
    s.output.width = suite.width;
    s.output.height = suite.height;
    EXPECT_NO_THROW(nephele::validate_scene(s)) << v.name;
    EXPECT_EQ(s.cirrus.coverage, 0.0f) << v.name;  // the reference traces no cirrus
  }
  EXPECT_EQ(suite.sky.sun_elevations_deg.front(), 90.0);
  EXPECT_EQ(suite.sky.sun_elevations_deg.back(), 0.0);
  EXPECT_EQ(suite.sky.max_pattern_mean, 0.02);
  EXPECT_EQ(suite.sky.max_pattern_horizon, 0.05);
  EXPECT_EQ(suite.sky.max_colour_ratio, 0.03);
  EXPECT_EQ(suite.sky.max_zenith_jump, 0.01);
}

void expect_refused(const std::string& text, const std::string& key) {
  try {
    parse_validation_suite(text, "suite.toml");
    ADD_FAILURE() << "accepted: " << text;
  } catch (const nephele::InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(key), std::string::npos) << what;
    EXPECT_EQ(std::count(what.begin(), what.end(), '\n'), 0) << what;
  }
}

TEST(ValidationSuite, BadSuitesAreRefusedWithOneLine) {
  const std::string view = "[[view]]\nname = \"a\"\nscene = \"preset = 'clear'\"\n";
  expect_refused("width = 4\n" + view + "max_mean_error = 0.05\n", "width");
  expect_refused(view, "max_mean_error");
  expect_refused(view + "max_mean_error = 0\n", "max_mean_error");
  expect_refused("block = 0\n", "block");
  expect_refused("x = 1\n", "view");
  expect_refused(view + "max_mean_error = 0.05\n" + view + "max_mean_error = 0.05\n", "used twice");
  expect_refused("[[view]]\nname = \"a b\"\nscene = \"x\"\nmax_mean_error = 0.1\n", "name");
  expect_refused(view + "max_mean_error = 0.05\n[sky]\nsun_elevations_deg = [95.0]\n",
                 "sun_elevations_deg");
  expect_refused(view + "max_mean_error = 0.05\n[sky]\nsun_elevations_deg = [5.0]\n"
                 "max_colour_ratio = 2.0\n", "max_colour_ratio");
  expect_refused("width = [", "suite.toml:1");
  expect_refused(view + "max_mean_error = 0.05\nmax_block_error = 0\n", "max_block_error");
  expect_refused(view + "max_mean_error = 0.05\nmax_block_error = \"10%\"\n", "max_block_error");
}

}  // namespace

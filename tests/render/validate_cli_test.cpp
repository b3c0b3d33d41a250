// `nephele validate` end to end on a small suite: the fast mode and the reference of each view,
// the table, the JSON and the side-by-side images (with the error map's scale); a reference
// folder read back; the clear sky's targets; the line that says what passed or failed; bad
// input in one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "nephele/image.h"
#include "support/process_run.h"

namespace fs = std::filesystem;

namespace {

using nephele::test::run_cli;

class ValidateCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("validate_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

// A JSON file validate wrote.
nlohmann::json read_json(const std::string& file) {
  return nlohmann::json::parse(std::ifstream(file));
}

// The last line a run printed (the summary after the table).
std::string last_line(const std::string& output) {
  std::string text = output;
  while (!text.empty() && text.back() == '\n') text.pop_back();
  return text.substr(text.rfind('\n') + 1);
}

// Two clear-sky views: the fast mode's sky is within a few per cent of the path-traced one
// (docs/validation.md), so a tolerance of 50% passes and one of 0.1% does not.
const char* kSuite = R"(width = 24
height = 16
block = 8
[[view]]
name = "up"
max_mean_error = 0.5
scene = """
preset = "clear"
[camera]
view_dir = [0.0, 0.3, 1.0]
"""
[[view]]
name = "strict"
max_mean_error = 0.001
scene = """
preset = "clear"
"""
[sky]
sun_elevations_deg = [30.0]
)";

TEST_F(ValidateCliTest, WritesTheTableTheJsonAndTheImagesAndReadsReferencesBack) {
  std::ofstream(path("suite.toml")) << kSuite;
  const std::string out = path("out"), refs = path("refs");
  const std::string args = "validate --suite " + path("suite.toml") + " --spp 30 --validation -q --out " +
                           out + " --references " + refs;
  const auto r = run_cli(args);
  EXPECT_EQ(r.status, 1) << r.output;  // "strict" misses
  const nlohmann::json j = read_json(out + "/results.json");
  EXPECT_TRUE(j["views"]["up"]["pass"].get<bool>()) << j.dump(1);
  EXPECT_FALSE(j["views"]["strict"]["pass"].get<bool>()) << j.dump(1);
  EXPECT_LT(j["views"]["up"]["mean_error"].get<double>(), 0.5);
  EXPECT_GT(j["views"]["up"]["mean_error"].get<double>(), 0.0);
  EXPECT_EQ(j["views"]["up"]["reference_spp"].get<int>(), 30);
  for (const char* f : {"up.png", "up_fast.exr", "strict.png", "results.md"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  EXPECT_TRUE(fs::exists(refs + "/up.exr"));
  EXPECT_NE(r.output.find("| up |"), std::string::npos) << r.output;
  // After the table, one line says what failed (issue 41): the views over, the worst of them.
  const std::string failed = last_line(r.output);
  EXPECT_TRUE(failed.starts_with(
      "nephele validate: FAILED: 1 of 2 views over their tolerances (worst: strict "))
      << r.output;
  EXPECT_NE(failed.find("% > 0.1%)"), std::string::npos) << failed;
  EXPECT_EQ(j["summary"].get<std::string>(), failed);
  std::ifstream md(out + "/results.md");
  const std::string table((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_EQ(last_line(table), failed) << table;
  EXPECT_NE(r.output.find("Error maps"), std::string::npos) << r.output;  // what the colours mean
  // The error map's scale under the images: black at 0, red at the tolerance (a quarter of the
  // way), white at 4 times it (the end); 24 x 16 pixels, three side by side, each scaled by a
  // whole factor of 2 or more so that its label (about 150 pixels) fits over it.
  const nephele::Image side = nephele::read_image(out + "/up.png");
  const int panel = (side.width - 2 * 4) / 3, scale = panel / 24;
  ASSERT_EQ(side.width, 3 * 24 * scale + 2 * 4);
  EXPECT_GE(panel, 140);
  EXPECT_LE(panel, 24 * 8);
  ASSERT_EQ(side.height, 16 * scale + 26);
  // The scale spans the map's panel, 120 pixels at least.
  const int length = std::max(panel, 120);
  const int bar_y = 16 * scale + 5, x1 = side.width - 1, x0 = side.width - length;
  EXPECT_LT(side.at(x0, bar_y).r, 0.05f);
  const glm::vec4 red = side.at(x0 + length / 4, bar_y), white = side.at(x1, bar_y);
  EXPECT_GT(red.r, 0.8f);
  EXPECT_LT(red.g, 0.1f);
  EXPECT_GT(std::min({white.r, white.g, white.b}), 0.8f);
  // Again: the references are read back (no time spent tracing), the errors the same.
  const auto again = run_cli("validate --suite " + path("suite.toml") + " --views up --spp 30 -q --out " +
                             path("out2") + " --references " + refs);
  EXPECT_EQ(again.status, 0) << again.output;
  EXPECT_EQ(last_line(again.output), "nephele validate: passed: 1 view within 50%") << again.output;
  const nlohmann::json k = read_json(path("out2") + "/results.json");
  EXPECT_EQ(k["views"]["up"]["reference_s"].get<double>(), 0.0);
  EXPECT_NEAR(k["views"]["up"]["mean_error"].get<double>(), j["views"]["up"]["mean_error"].get<double>(), 1e-6);
  // At another size the references are not traced again over the ones held (a shipped 40 x 25
  // set replaced by a few seconds' trace): one line says what the folder holds and how to use
  // it; nothing is rendered or written.
  const auto before = fs::last_write_time(refs + "/up.exr");
  const auto other =
      run_cli("validate --suite " + path("suite.toml") + " --views up --spp 30 " +
              "--width 16 --height 10 -q --out " + path("out3") + " --references " + refs);
  EXPECT_EQ(other.status, 2) << other.output;
  EXPECT_EQ(last_line(other.output),
            "nephele: error: --references \"" + refs +
                "\": up.exr is 24x16, the views are 16x10: "
                "pass --width 24 --height 16, or another folder to trace new ones into")
      << other.output;
  EXPECT_EQ(fs::last_write_time(refs + "/up.exr"), before);
  EXPECT_FALSE(fs::exists(path("out3") + "/results.json"));
}

// The lab suite nephele ships (data/lab.toml) runs from anywhere: its views' grids are found
// beside the suite's file, not in the working directory. One view, small and short.
TEST_F(ValidateCliTest, TheLabSuiteFindsItsGridsBesideItself) {
  const std::string suite = std::string(NEPHELE_SOURCE_DIR) + "/data/lab.toml";
  const auto r =
      run_cli("validate --suite " + suite + " --views cube-side --width 16 --height 10 " +
              "--spp 3 --validation -q --out " + path("out"));
  ASSERT_TRUE(r.status == 0 || r.status == 1) << r.output;  // it ran (3 samples miss or pass)
  const nlohmann::json j = read_json(path("out") + "/results.json");
  EXPECT_GT(j["views"]["cube-side"]["mean_error"].get<double>(), 0.0) << j.dump(1);
  EXPECT_EQ(j["views"]["cube-side"]["reference_spp"].get<int>(), 3);
  EXPECT_EQ(j["views"]["cube-side"]["max_lit_block_tolerance"].get<double>(), 0.10);
}

// A view's block tolerance (max_block_error): a view within its mean tolerance still fails
// when a block with light is further off than its own, and the summary says it was a block.
TEST_F(ValidateCliTest, ABlockOverItsToleranceFailsTheView) {
  std::ofstream(path("suite.toml")) << R"(width = 24
height = 16
block = 8
[[view]]
name = "up"
max_mean_error = 0.9
max_block_error = 0.0001
scene = """
preset = "clear"
[camera]
view_dir = [0.0, 0.3, 1.0]
"""
)";
  const auto r = run_cli("validate --suite " + path("suite.toml") +
                         " --spp 3 --validation -q --out " + path("out"));
  EXPECT_EQ(r.status, 1) << r.output;
  const nlohmann::json j = read_json(path("out") + "/results.json");
  EXPECT_LT(j["views"]["up"]["mean_error"].get<double>(), 0.9) << j.dump(1);
  EXPECT_GT(j["views"]["up"]["max_lit_block_error"].get<double>(), 0.0001) << j.dump(1);
  EXPECT_FALSE(j["views"]["up"]["pass"].get<bool>());
  EXPECT_TRUE(last_line(r.output).starts_with(
      "nephele validate: FAILED: 1 of 1 views over their tolerances (worst: up block "))
      << r.output;
}

// The sun's disk is left out of a view's comparison: at this size it is a fraction of a pixel,
// which the reference integrates and the fast mode samples at the pixel's centre, and its pixel
// alone would outweigh the whole sky. Looking at the sun, a few pixels around it are left out
// and the sky agrees; looking away, none are.
TEST_F(ValidateCliTest, TheSunsDiskIsLeftOutOfTheComparison) {
  std::ofstream(path("suite.toml")) << R"(width = 24
height = 16
block = 8
[[view]]
name = "sunward"
max_mean_error = 0.5
scene = """
preset = "clear"
[sun]
elevation_deg = 20.0
azimuth_deg = 180.0
[camera]
view_dir = [0.0, -0.94, 0.34]
"""
[[view]]
name = "away"
max_mean_error = 0.5
scene = """
preset = "clear"
[sun]
elevation_deg = 20.0
azimuth_deg = 180.0
[camera]
view_dir = [0.0, 0.94, 0.34]
"""
)";
  const auto r = run_cli("validate --suite " + path("suite.toml") +
                         " --spp 30 --validation -q --out " + path("out"));
  EXPECT_EQ(r.status, 0) << r.output;
  const nlohmann::json j = read_json(path("out") + "/results.json");
  const int sunward = j["views"]["sunward"]["sun_pixels_excluded"].get<int>();
  EXPECT_GE(sunward, 1) << j.dump(1);
  EXPECT_LE(sunward, 16) << j.dump(1);
  EXPECT_EQ(j["views"]["away"]["sun_pixels_excluded"].get<int>(), 0) << j.dump(1);
  EXPECT_LT(j["views"]["sunward"]["mean_error"].get<double>(), 0.1) << j.dump(1);
}

TEST_F(ValidateCliTest, TheSkyModeMeasuresThePatternAgainstTheReference) {
  std::ofstream(path("suite.toml")) << kSuite;
  const auto r = run_cli("validate --sky --suite " + path("suite.toml") + " --spp 30 -q --out " +
                         path("out"));
  ASSERT_TRUE(r.status == 0 || r.status == 1) << r.output;
  EXPECT_TRUE(last_line(r.output).starts_with(
      r.status == 0 ? "nephele validate --sky: passed: 1 sun elevation within the targets"
                    : "nephele validate --sky: FAILED: 1 of 1 sun elevations miss a target: 30 deg ("))
      << r.output;
  const nlohmann::json j = read_json(path("out") + "/sky.json");
  const nlohmann::json& e = j["sun_elevations"]["30.0"];
  for (const char* v : {"zenith", "horizon-away", "horizon-side", "horizon-near", "towards-sun"})
    EXPECT_TRUE(e["views"].contains(v)) << v;
  EXPECT_LT(e["pattern_mean"].get<double>(), 0.2);  // measured: 1.2% at 8192 spp
  EXPECT_LT(e["zenith_jump"].get<double>(), 0.01);
  EXPECT_NEAR(e["zenith_fast_over_reference"].get<double>(), 1.0, 0.1);
}

// The issue's targets for the clear sky, against the path-traced references that ship in
// data/validation/sky (8193 samples per pixel each, `nephele validate --sky --spp 8192
// --references data/validation/sky`; about 15 minutes on two cores): every sun elevation from
// 90 degrees to 0 passes (pattern within 2% on average and 5% one degree above the horizon,
// colour ratios within 3%, no step over 1% at the zenith). Before the multiple-scattering
// field, 7 of the 8 missed (colour 22% at sunset).
TEST_F(ValidateCliTest, TheClearSkyMeetsItsTargetsAgainstTheShippedReferences) {
  const fs::path shipped = fs::path(NEPHELE_SOURCE_DIR) / "data" / "validation" / "sky";
  fs::copy(shipped, path("refs"));  // a missing one would be traced and written: not into the tree
  const auto r = run_cli("validate --sky -q --references " + path("refs") + " --out " + path("out"));
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(last_line(r.output),
            "nephele validate --sky: passed: all 8 sun elevations within the targets (pattern 2%, "
            "at 1 deg 5%, colour 3%, zenith jump 1%)")
      << r.output;
  const nlohmann::json j = read_json(path("out") + "/sky.json");
  ASSERT_EQ(j["sun_elevations"].size(), 8u) << j.dump(1);
  for (const auto& [elevation, e] : j["sun_elevations"].items()) {
    EXPECT_TRUE(e["pass"].get<bool>()) << elevation << ": " << e.dump(1);
    for (const auto& [view, v] : e["views"].items())
      EXPECT_EQ(v["reference_spp"].get<int>(), 8193) << view << ": read back, not traced";
  }
  EXPECT_EQ(std::distance(fs::directory_iterator(path("refs")), fs::directory_iterator()), 40);
  // A sky reference of another size (a foreign file) is refused, not traced over.
  const std::string odd = path("refs") + "/sky_0_horizon-away.exr";
  nephele::write_image(nephele::Image(32, 16), odd);
  const auto before = fs::last_write_time(odd);
  const auto refused =
      run_cli("validate --sky -q --references " + path("refs") + " --out " + path("out2"));
  EXPECT_EQ(refused.status, 2) << refused.output;
  EXPECT_EQ(last_line(refused.output),
            "nephele: error: --references \"" + path("refs") +
                "\": sky_0_horizon-away.exr is 32x16, the views are 16x16: pass another folder "
                "to trace new ones into")
      << refused.output;
  EXPECT_EQ(fs::last_write_time(odd), before);
}

// The views whose shipped references are converged (0.1-0.2% noise a block) hold the errors
// measured at stop 68 with about a point of margin: the noon cumulus within the suite's 5%
// (3.8%), the inside of a cloud within 10% (8.9%; 9.7% since stop 73; its target is 5%), and
// since stop 73 the overcast within 10% (9.1%; 25.6% while the diffusion light's cap on D held
// the light in the deck's thin base, 35.4% while the air under it was lit as on a clear day).
// A bound is tightened when the model improves, never loosened. The inside view is also what the
// diffusion gather's corner rule holds: a gather whose diagonal rays slip between the cloud cells
// beside a corner (before stop 62) lets the light out of the clear pockets of an eroded cloud, and
// the view read 17.7% (-17.5%) at stop 64.
TEST_F(ValidateCliTest, TheConvergedViewsHoldTheirMeasuredErrors) {
  const fs::path shipped = fs::path(NEPHELE_SOURCE_DIR) / "data" / "validation" / "views";
  const struct {
    const char* view;
    double bound;
  } views[] = {{"noon-cumulus", 0.05}, {"inside-cloud", 0.10}, {"overcast-below", 0.10}};
  fs::create_directories(path("refs"));
  std::string names;
  for (const auto& [view, bound] : views) {
    fs::copy(shipped / (std::string(view) + ".exr"), path("refs"));
    names += (names.empty() ? "" : ",") + std::string(view);
  }
  const auto r = run_cli("validate -q --views " + names + " --references " + path("refs") +
                         " --out " + path("out"));
  ASSERT_TRUE(r.status == 0 || r.status == 1) << r.output;  // 1: a view over the suite's 5%
  const nlohmann::json j = read_json(path("out") + "/results.json");
  for (const auto& [view, bound] : views) {
    const nlohmann::json& v = j["views"][view];
    ASSERT_FALSE(v.is_null()) << view << ": " << j.dump(1);
    EXPECT_EQ(v["reference_s"].get<double>(), 0.0) << view << ": read back, not traced";
    const double error = v["mean_error"].get<double>();
    std::printf("%s: mean error %.4f, bias %+.4f (bound %.2f)\n", view, error,
                v["mean_bias"].get<double>(), bound);
    EXPECT_LE(error, bound) << view;
  }
}

TEST_F(ValidateCliTest, BadInputGetsOneLine) {
  std::ofstream(path("suite.toml")) << kSuite;
  for (const auto& [args, expected] :
       {std::pair<std::string, std::string>{"--views nope", "--views \"nope\": no such view"},
        {"--spp 1", "--spp 1"},
        {"--sky --views up", "--sky and --views"}}) {
    const auto r = run_cli("validate --suite " + path("suite.toml") + " -q --out " + path("o") + " " + args);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
  }
  const auto missing = run_cli("validate --suite " + path("none.toml"));
  EXPECT_EQ(missing.status, 2) << missing.output;
  EXPECT_NE(missing.output.find("none.toml"), std::string::npos) << missing.output;
}

}  // namespace

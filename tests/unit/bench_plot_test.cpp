// scripts/plot_bench.py, as `nephele bench` runs it (its copy embedded in the binary) and as
// docs/benchmark.md says to run it by hand, on a small bench.json (tests/data/bench_small.json).
// Skipped where /usr/bin/python3 cannot import matplotlib.
#include "bench_plot.h"

#include <gtest/gtest.h>
#include <stb/stb_image.h>
#include <sys/wait.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

namespace fs = std::filesystem;
using nephele::cli::BenchPlots;
using nephele::cli::draw_bench_plots;

namespace {

const std::string kFixture = std::string(NEPHELE_SOURCE_DIR) + "/tests/data/bench_small.json";

bool have_matplotlib() {
  static const bool have = std::system((std::string(nephele::cli::kPlotPython) +
                                        " -c 'import matplotlib' >/dev/null 2>&1")
                                           .c_str()) == 0;
  return have;
}

class BenchPlotTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("bench_plot_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // A PNG of at least 640x300 pixels (a figure, not an empty file).
  static void expect_figure(const std::string& file) {
    int w = 0, h = 0, channels = 0;
    ASSERT_TRUE(stbi_info(file.c_str(), &w, &h, &channels)) << file;
    EXPECT_GE(w, 640) << file;
    EXPECT_GE(h, 300) << file;
  }
  fs::path dir_;
};

}  // namespace

// The fixture has the seed's sweeps and per-frame times: both figures.
TEST_F(BenchPlotTest, DrawsTheSweepsAndTheFrameTimeTrace) {
  if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib";
  const BenchPlots plots = draw_bench_plots(kFixture, dir_.string());
  ASSERT_EQ(plots.outcome, BenchPlots::Outcome::kDrawn) << plots.reason;
  EXPECT_EQ(plots.files,
            (std::vector<std::string>{path("bench.png"), path("bench_frame_times.png")}));
  expect_figure(path("bench.png"));
  expect_figure(path("bench_frame_times.png"));
  // Each file replaced whole: no temporary file is left beside them.
  for (const auto& entry : fs::directory_iterator(dir_))
    EXPECT_TRUE(entry.path().extension() == ".png" && entry.path().filename().string()[0] != '.')
        << entry.path();
}

// Without frame_times_ms (today's bench.json) the trace is left out silently; without sweeps
// (a --realtime-only JSON) the sweeps are.
TEST_F(BenchPlotTest, LeavesOutWhatTheJsonLacks) {
  if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib";
  nlohmann::json full = nlohmann::json::parse(std::ifstream(kFixture));
  nlohmann::json no_times = full, no_sweeps = full;
  no_times.erase("frame_times_ms");
  no_sweeps.erase("sweeps");
  std::ofstream(path("no_times.json")) << no_times.dump();
  std::ofstream(path("no_sweeps.json")) << no_sweeps.dump();
  fs::create_directories(dir_ / "a");
  fs::create_directories(dir_ / "b");
  const BenchPlots a = draw_bench_plots(path("no_times.json"), path("a"));
  ASSERT_EQ(a.outcome, BenchPlots::Outcome::kDrawn) << a.reason;
  EXPECT_EQ(a.files, std::vector<std::string>{path("a/bench.png")});
  EXPECT_FALSE(fs::exists(path("a/bench_frame_times.png")));
  const BenchPlots b = draw_bench_plots(path("no_sweeps.json"), path("b"));
  ASSERT_EQ(b.outcome, BenchPlots::Outcome::kDrawn) << b.reason;
  EXPECT_EQ(b.files, std::vector<std::string>{path("b/bench_frame_times.png")});
  EXPECT_FALSE(fs::exists(path("b/bench.png")));
}

// docs/benchmark.md's command: the script in the source tree, run from another directory.
TEST_F(BenchPlotTest, TheScriptRunsByHandFromAnyDirectory) {
  if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib";
  const std::string command = "cd / && " + std::string(nephele::cli::kPlotPython) + " '" +
                              NEPHELE_SOURCE_DIR + "/scripts/plot_bench.py' '" + kFixture + "' '" +
                              dir_.string() + "' >/dev/null 2>&1";
  const int raw = std::system(command.c_str());
  ASSERT_TRUE(WIFEXITED(raw) && WEXITSTATUS(raw) == 0) << command;
  expect_figure(path("bench.png"));
  expect_figure(path("bench_frame_times.png"));
}

// No interpreter: skipped with the reason, nothing drawn, nothing thrown.
TEST_F(BenchPlotTest, WithoutPythonThePlotIsSkipped) {
  const BenchPlots plots = draw_bench_plots(kFixture, dir_.string(), "/nonexistent/python3");
  EXPECT_EQ(plots.outcome, BenchPlots::Outcome::kSkipped);
  EXPECT_EQ(plots.reason, "cannot run /nonexistent/python3 (No such file or directory)");
  EXPECT_TRUE(plots.files.empty());
  EXPECT_TRUE(fs::is_empty(dir_));
}

// An interpreter without matplotlib (the script exits with 3): skipped, saying so. A stand-in
// that only exits 3 plays that interpreter.
TEST_F(BenchPlotTest, WithoutMatplotlibThePlotIsSkipped) {
  const std::string python = path("python-without-matplotlib");
  std::ofstream(python) << "#!/bin/sh\nexit 3\n";
  fs::permissions(python, fs::perms::owner_all);
  const BenchPlots plots = draw_bench_plots(kFixture, dir_.string(), python);
  EXPECT_EQ(plots.outcome, BenchPlots::Outcome::kSkipped);
  EXPECT_EQ(plots.reason, python + " cannot import matplotlib (Debian: python3-matplotlib)");
  EXPECT_TRUE(plots.files.empty());
}

// A script error (here: the JSON is missing) is a failure with the script's last line.
TEST_F(BenchPlotTest, AFailingScriptSaysWhy) {
  if (!have_matplotlib()) GTEST_SKIP() << "/usr/bin/python3 cannot import matplotlib";
  const BenchPlots plots = draw_bench_plots(path("missing.json"), dir_.string());
  EXPECT_EQ(plots.outcome, BenchPlots::Outcome::kFailed);
  EXPECT_NE(plots.reason.find("exit 2"), std::string::npos) << plots.reason;
  EXPECT_NE(plots.reason.find("missing.json"), std::string::npos) << plots.reason;
}

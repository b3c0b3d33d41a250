// nephele-view, run as a user runs it: under xvfb-run (a virtual X display) with the validation
// layer on, at a small window size. Skipped where xvfb-run or the viewer is not there.
//
// The soak test is disabled by default (2,000 frames take minutes on lavapipe); run it with
//   build/tests/nephele_tests --gtest_also_run_disabled_tests --gtest_filter='ViewerTest.DISABLED_Soak*'
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>

#include "nephele/image.h"
#include "nephele/image_compare.h"

namespace fs = std::filesystem;

namespace {

struct ProcessRun {
  int status;
  std::string output;  // stdout and stderr
};

ProcessRun run(const std::string& command) {
  FILE* pipe = popen((command + " 2>&1").c_str(), "r");
  std::string output;
  std::array<char, 4096> buffer;
  size_t n;
  while ((n = fread(buffer.data(), 1, buffer.size(), pipe)) > 0) output.append(buffer.data(), n);
  const int raw = pclose(pipe);
  return {WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, output};
}

// The size every test renders at: lavapipe renders on the CPU.
constexpr const char* kSize = "160x120";

// The golden tests' tolerances (tests/golden/*.json): the viewer's still is the CLI's render.
nephele::CompareTolerance image_tolerance() {
  return nephele::load_tolerance_json(
      (fs::path(NEPHELE_SOURCE_DIR) / "tests" / "golden" / "ground-noon.json").string());
}

class ViewerTest : public ::testing::Test {
 protected:
  void SetUp() override {
#ifndef NEPHELE_VIEW_PATH
    GTEST_SKIP() << "nephele-view is not built (needs GLFW and Dear ImGui)";
#else
    viewer_ = NEPHELE_VIEW_PATH;
    if (!fs::exists(viewer_)) GTEST_SKIP() << "no " << viewer_;
    if (std::system("command -v xvfb-run > /dev/null 2>&1") != 0)
      GTEST_SKIP() << "xvfb-run is not installed (Debian: xvfb xauth)";
#endif
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("viewer_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // The viewer in a virtual display, with validation.
  ProcessRun view(const std::string& args) const {
    const std::string size = args.find("--size") == std::string::npos ? std::string(" --size ") + kSize : "";
    return run("xvfb-run -a -s '-screen 0 1280x800x24' " + viewer_ + " --validation" + size + " " +
               args);
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name)) << text;
    return path(name);
  }
  std::string viewer_;
  fs::path dir_;
};

void expect_clean(const ProcessRun& r) {
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_EQ(r.output.find("validation"), std::string::npos) << r.output;
}

TEST_F(ViewerTest, ScreenshotOfTheDefaultSceneIsTheCliRender) {
  const ProcessRun r = view("--preset default --frames 3 --screenshot " + path("view.png") +
                     " --window-screenshot " + path("window.png"));
  expect_clean(r);
  std::printf("%s", r.output.c_str());  // the frame times, for the record
  const ProcessRun cli = run(std::string(NEPHELE_CLI_PATH) +
                      " render --preset default --width 160 --height 120 -o " + path("cli.png"));
  ASSERT_EQ(cli.status, 0) << cli.output;

  const nephele::Image view = nephele::read_image(path("view.png"));
  const nephele::Image reference = nephele::read_image(path("cli.png"));
  const nephele::CompareResult result = nephele::compare_images(view, reference, image_tolerance());
  std::printf("viewer's still against nephele render: %s\n", result.summary.c_str());
  if (!result.pass) nephele::write_image(result.diff, path("diff.png"));
  EXPECT_TRUE(result.pass) << result.summary << " (images in " << dir_ << ")";

  // The window as shown: the window's size, and not one colour (the panel is drawn on it).
  const nephele::Image window = nephele::read_image(path("window.png"));
  EXPECT_EQ(window.width, 160);
  EXPECT_EQ(window.height, 120);
  bool varied = false;
  for (const glm::vec4& p : window.pixels) varied = varied || p != window.pixels[0];
  EXPECT_TRUE(varied);
}

TEST_F(ViewerTest, ScriptedCoverageChangesTheImage) {
  const std::string script = write("script.txt",
                                   "# few clouds, then many\n"
                                   "frame 0 set clouds.coverage 0.15\n"
                                   "frame 1 screenshot " + path("few.exr") + "\n"
                                   "frame 2 set clouds.coverage 0.95\n"
                                   "frame 3 screenshot " + path("many.exr") + "\n"
                                   "frame 4 quit\n");
  const ProcessRun r = view("--preset default --script " + script);
  expect_clean(r);
  const nephele::Image few = nephele::read_image(path("few.exr"));
  const nephele::Image many = nephele::read_image(path("many.exr"));
  ASSERT_EQ(few.width, 160);
  ASSERT_EQ(many.width, 160);
  // More cloud: the image differs by more than a tenth of its brightness on average.
  const double error = nephele::luminance_error(many, few);
  std::printf("coverage 0.15 -> 0.95: mean luminance change %.3f of the image's\n", error);
  EXPECT_GT(error, 0.1) << "mean luminance change relative to the few-cloud image";
}

TEST_F(ViewerTest, InvalidScriptValueIsReportedAndThePreviousSceneKeepsRendering) {
  const std::string script = write("script.txt",
                                   "frame 1 screenshot " + path("before.png") + "\n"
                                   "frame 2 set clouds.coverage 1.5\n"
                                   "frame 2 set clouds.density \"thick\"\n"
                                   "frame 3 screenshot " + path("after.png") + "\n"
                                   "frame 4 quit\n");
  const ProcessRun r = view("--preset default --script " + script);
  expect_clean(r);
  EXPECT_NE(r.output.find("script.txt:2: clouds.coverage = 1.5: must be in [0, 1]\n"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("script.txt:3: clouds.density = \"thick\": expected a number\n"),
            std::string::npos)
      << r.output;
  const nephele::CompareResult same = nephele::compare_images(
      nephele::read_image(path("after.png")), nephele::read_image(path("before.png")),
      image_tolerance());
  EXPECT_TRUE(same.pass) << same.summary;
}

TEST_F(ViewerTest, ResizingTheWindowRecreatesTheSwapchain) {
  const std::string script = write("script.txt",
                                   "frame 2 resize 200x150\n"
                                   "frame 4 window-screenshot " + path("large.png") + "\n"
                                   "frame 5 resize 120x90\n"
                                   "frame 8 window-screenshot " + path("small.png") + "\n"
                                   "frame 9 quit\n");
  const ProcessRun r = view("--preset default --script " + script);
  expect_clean(r);
  const nephele::Image large = nephele::read_image(path("large.png"));
  const nephele::Image small = nephele::read_image(path("small.png"));
  EXPECT_EQ(large.width, 200);
  EXPECT_EQ(large.height, 150);
  EXPECT_EQ(small.width, 120);
  EXPECT_EQ(small.height, 90);
}

TEST_F(ViewerTest, BadFlagsAndScriptLinesAreOneLineAndExitTwo) {
  const struct {
    std::string args, expected;
  } cases[] = {
      {"--size 0x10", "nephele-view: error: --size 0x10: expected WxH, each in [1, 16384]"},
      {"--coverage 2", "nephele-view: error: --coverage 2: must be in [0, 1]"},
      {"--frames 2 --screenshot out.jpg", "--screenshot 'out.jpg': unsupported image format"},
      {"--screenshot out.png", "need --frames N"},
      {"--script " + write("bad1.txt", "frame 1 jump\n"),
       "bad1.txt:1: unknown command 'jump' (allowed: set, preset, load, camera-path, screenshot, "
       "window-screenshot, resize, quit)"},
      {"--script " + write("bad5.txt", "frame 1 resize 0x10\n"),
       "bad5.txt:1: resize '0x10': expected WxH, each in [1, 16384]"},
      {"--script " + write("bad2.txt", "\nframe x set clouds.coverage 1\n"),
       "bad2.txt:2: frame 'x': expected an integer in [0, 16000000]"},
      {"--script " + write("bad3.txt", "frame 1 set clouds.cover 1\n"),
       "bad3.txt:1: set: unknown scene key 'clouds.cover' (allowed in [clouds]:"},
      {"--script " + write("bad4.txt", "frame 1 camera-path p.toml\n"),
       "bad4.txt:1: camera-path: camera paths are not available"},
      {"--script " + path("missing.txt"), "missing.txt: cannot read the script"},
  };
  for (const auto& c : cases) {
    const ProcessRun r = view(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.args << "\n" << r.output;
  }
}

// 2,000 frames; the viewer measures its RSS at frame 100 and at the end (--soak) and fails on
// growth over 8 MiB. Not in the default suite: see the top of this file.
TEST_F(ViewerTest, DISABLED_SoakTwoThousandFramesWithoutMemoryGrowth) {
  const ProcessRun r = view("--preset default --frames 2000 --soak");
  std::printf("%s", r.output.c_str());
  expect_clean(r);
  EXPECT_NE(r.output.find("nephele-view: soak: RSS"), std::string::npos) << r.output;
}

}  // namespace

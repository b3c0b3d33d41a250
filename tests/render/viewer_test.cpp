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
#include <map>
#include <sstream>

#include "nephele/camera_path.h"
#include "nephele/exposure.h"
#include "nephele/image.h"
#include "nephele/image_compare.h"
#include "nephele/scene_io.h"

#include "support/process_run.h"

namespace fs = std::filesystem;

namespace {

using nephele::test::ProcessRun;
ProcessRun run(const std::string& command) { return nephele::test::run_process(command); }

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

// The cameras a script's print-camera lines wrote, in order: each key of the [camera] table
// ("position_m", "view_dir", "roll_deg", ...) with its numbers.
using PrintedCamera = std::map<std::string, std::vector<double>>;
std::vector<PrintedCamera> printed_cameras(const std::string& output) {
  std::vector<PrintedCamera> cameras;
  std::istringstream in(output);
  std::string line;
  bool inside = false;
  while (std::getline(in, line)) {
    if (line.starts_with("# print-camera:")) {
      cameras.emplace_back();
      inside = true;
      continue;
    }
    if (!inside || line == "[camera]") continue;
    const size_t equals = line.find(" = ");
    if (equals == std::string::npos) {
      inside = false;
      continue;
    }
    std::string value = line.substr(equals + 3);
    for (char& c : value)
      if (c == '[' || c == ']' || c == ',') c = ' ';
    std::istringstream numbers(value);
    std::vector<double>& out = cameras.back()[line.substr(0, equals)];
    for (double x; numbers >> x;) out.push_back(x);
  }
  return cameras;
}

// The printed camera is `expected` (CameraPath::at): position to a millimetre, direction and
// roll to float rounding.
void expect_camera(const PrintedCamera& printed, const nephele::CameraParams& expected) {
  ASSERT_EQ(printed.count("position_m"), 1u);
  ASSERT_EQ(printed.at("position_m").size(), 3u);
  ASSERT_EQ(printed.count("view_dir"), 1u);
  ASSERT_EQ(printed.at("view_dir").size(), 3u);
  ASSERT_EQ(printed.count("roll_deg"), 1u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(printed.at("position_m")[size_t(i)], expected.position_m[i], 1e-3) << i;
    EXPECT_NEAR(printed.at("view_dir")[size_t(i)], expected.view_dir[i], 1e-6) << i;
  }
  EXPECT_NEAR(printed.at("roll_deg")[0], expected.roll_deg, 1e-4);
}

// A flight of two keys, rolling and turning as it climbs.
constexpr const char* kTwoKeyPath =
    "[[key]]\n"
    "time_s = 0\n"
    "position_m = [0, -2000, 300]\n"
    "heading_deg = 0\n"
    "pitch_deg = 8\n"
    "\n"
    "[[key]]\n"
    "time_s = 4\n"
    "position_m = [600, -1000, 900]\n"
    "heading_deg = 40\n"
    "pitch_deg = 15\n"
    "roll_deg = 25\n";

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

// The window exposes itself (output.auto_exposure, the default) from the device's meter: in
// civil twilight (the sun 4 degrees down) the live window's EV100 is the one `nephele render`
// meters for the same frame, within 0.3 EV (the viewer meters its dynamic-resolution frame),
// where before the window stayed at the manual EV100 of 15 and drew the dusk black.
TEST_F(ViewerTest, TheWindowExposesItselfAtDusk) {
  const std::string args = " --preset default --sun-elevation-deg -4 --sun-azimuth-deg 270"
                           " --view-dir 0,1,0.3";
  const ProcessRun r = view(args + " --frames 6 --window-screenshot " + path("window.png"));
  expect_clean(r);
  const size_t at = r.output.find("EV100 ");
  ASSERT_NE(at, std::string::npos) << r.output;
  const double live = std::atof(r.output.c_str() + at + 6);
  EXPECT_NE(r.output.find(" auto)", at), std::string::npos) << r.output;
  const ProcessRun cli = run(std::string(NEPHELE_CLI_PATH) + " render" + args +
                             " --width 160 --height 120 --exr-float -o " + path("still.exr"));
  ASSERT_EQ(cli.status, 0) << cli.output;
  nephele::Scene scene = nephele::load_preset("default");
  const double expected =
      nephele::frame_ev100(scene.output, nephele::read_image(path("still.exr")), nullptr, 0.0);
  std::printf("dusk: window EV100 %.2f, the still's %.2f\n", live, expected);
  EXPECT_LT(expected, 8.0);  // a dusk, far from the day's 15
  EXPECT_NEAR(live, expected, 0.3);
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

// A paused view settles (every cloud pixel marched twice, the exposure adapted) and is then
// drawn from its last frame with nothing rendered (FrameOptions::reuse_settled); a change
// renders again.
TEST_F(ViewerTest, APausedViewStopsRenderingOnceSettled) {
  const std::string script = write("settle.txt",
                                   "frame 0 set clouds.coverage 0.15\n"
                                   "frame 69 window-screenshot " +
                                       path("few.png") +
                                       "\n"
                                       "frame 70 set clouds.coverage 0.95\n"
                                       "frame 89 window-screenshot " +
                                       path("many.png") +
                                       "\n"
                                       "frame 90 quit\n");
  const ProcessRun r =
      view("--preset default --size 480x320 --no-dynamic-resolution --script " + script);
  expect_clean(r);
  const size_t at = r.output.find(" of them the settled frame again");
  ASSERT_NE(at, std::string::npos) << r.output;
  const long reused = std::stol(r.output.substr(r.output.rfind(' ', at - 1) + 1));
  std::printf("%ld of 90 frames the settled frame again\n", reused);
  // Not before frame 32 (2 x 4^2 frames of a march stride of 4) nor in the 20 frames after
  // the coverage changed (it would settle after 32 more); settled by frame 50 at the latest
  // (the exposure's adaptation).
  EXPECT_GE(reused, 20);
  EXPECT_LE(reused, 70 - 32);
  // The sky right of the panel and below the timings (x >= 400, y >= 270 of 480 x 320) is
  // drawn again after the change: more cloud.
  const auto corner = [](const nephele::Image& window) {
    nephele::Image part;
    part.width = window.width - 400;
    part.height = window.height - 270;
    for (int y = 270; y < window.height; ++y)
      for (int x = 400; x < window.width; ++x)
        part.pixels.push_back(window.pixels[size_t(y) * size_t(window.width) + size_t(x)]);
    return part;
  };
  const nephele::Image few = nephele::read_image(path("few.png"));
  const nephele::Image many = nephele::read_image(path("many.png"));
  ASSERT_EQ(few.width, 480);
  ASSERT_EQ(many.height, 320);
  const double change = nephele::luminance_error(corner(many), corner(few));
  std::printf("the sky's corner after the change: mean luminance change %.3f\n", change);
  EXPECT_GT(change, 0.05) << "the window after the change of coverage";
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
       "bad1.txt:1: unknown command 'jump' (allowed: set, preset, load, camera-path, record-start, "
       "record-stop, print-camera, screenshot, window-screenshot, resize, quit)"},
      {"--script " + write("bad5.txt", "frame 1 resize 0x10\n"),
       "bad5.txt:1: resize '0x10': expected WxH, each in [1, 16384]"},
      {"--script " + write("bad2.txt", "\nframe x set clouds.coverage 1\n"),
       "bad2.txt:2: frame 'x': expected an integer in [0, 16000000]"},
      {"--script " + write("bad3.txt", "frame 1 set clouds.cover 1\n"),
       "bad3.txt:1: set: unknown scene key 'clouds.cover' (allowed in [clouds]:"},
      {"--script " + write("bad4.txt", "frame 1 camera-path\n"),
       "bad4.txt:1: camera-path: expected a path file"},
      {"--script " + write("bad6.txt", "frame 1 record-stop " + path("none/p.toml") + "\n"),
       "bad6.txt:1: record-stop '"},
      {"--camera-path " + write("one-key.toml",
                                "[[key]]\ntime_s = 0\nposition_m = [0, 0, 10]\n"
                                "heading_deg = 0\npitch_deg = 0\n"),
       "nephele-view: error: --camera-path " + path("one-key.toml") +
           ": 1 key: a camera path needs at least 2 keys ([[key]] tables)"},
      {"--camera-path " + path("missing.toml"), "nephele-view: error: --camera-path "},
      {"--script " + path("missing.txt"), "missing.txt: cannot read the script"},
  };
  for (const auto& c : cases) {
    const ProcessRun r = view(c.args);
    EXPECT_EQ(r.status, 2) << c.args << "\n" << r.output;
    EXPECT_NE(r.output.find(c.expected), std::string::npos) << c.args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << c.args << "\n" << r.output;
  }
}

// A script flies a two-key path (camera-path): the screenshots at path times 1 and 3 differ, the
// second is what `nephele render --camera-path` makes of the same path at the same time, and
// the camera the viewer reports (print-camera) is CameraPath::at of those times. The path runs
// in scene time from when it started (time_s 0 here), so `set time_s` puts it at a known time.
TEST_F(ViewerTest, PlaysACameraPathAsNepheleRenderFliesIt) {
  const std::string flight = write("flight.toml", kTwoKeyPath);
  const std::string script = write("script.txt",
                                   "frame 1 camera-path " + flight + "\n"
                                   "frame 2 set time_s 1\n"
                                   "frame 2 screenshot " + path("first.png") + "\n"
                                   "frame 2 print-camera\n"
                                   "frame 4 set time_s 3\n"
                                   "frame 4 screenshot " + path("second.png") + "\n"
                                   "frame 4 print-camera\n"
                                   "frame 5 quit\n");
  // At the exposure the tolerances were set for (the old default, EV100 13.38): the two
  // programs' clouds differ by a little noise, which a darker exposure brings out of the tone
  // curve's shoulder.
  const ProcessRun r = view("--preset default --ev100 13.38 --script " + script);
  expect_clean(r);

  const nephele::CameraPath expected =
      nephele::load_camera_path(flight, nephele::load_preset("default"));
  const std::vector<PrintedCamera> cameras = printed_cameras(r.output);
  ASSERT_EQ(cameras.size(), 2u) << r.output;
  expect_camera(cameras[0], expected.at(1.0));
  expect_camera(cameras[1], expected.at(3.0));

  const nephele::Image first = nephele::read_image(path("first.png"));
  const nephele::Image second = nephele::read_image(path("second.png"));
  const nephele::CompareResult moved = nephele::compare_images(second, first, image_tolerance());
  std::printf("path time 1 s against 3 s: %s\n", moved.summary.c_str());
  EXPECT_FALSE(moved.pass) << "the camera moved between the screenshots: " << moved.summary;

  // Frame 3 at 1 frame a second is path time 3, the scene's clock 3 s on from time_s 0.
  const ProcessRun cli =
      run(std::string(NEPHELE_CLI_PATH) +
          " render --preset default --ev100 13.38 --width 160 --height 120 --camera-path " +
          flight + " --fps 1 --start-frame 3 --frames 1 -o " + path("cli_%d.png"));
  ASSERT_EQ(cli.status, 0) << cli.output;
  const nephele::Image reference = nephele::read_image(path("cli_3.png"));
  // The viewer's frame is an animation's (reprojected, its lighting following the camera over
  // frames), the CLI's built at once: with the droplets' water their cloud edges and the ground
  // under them differ by more than 0.02 on 3.4% of the pixels (mean 0.005), where the camera's
  // move between the screenshots changes 92%.
  nephele::CompareTolerance tolerance = image_tolerance();
  tolerance.max_failing_fraction = 0.05f;
  const nephele::CompareResult result = nephele::compare_images(second, reference, tolerance);
  std::printf("viewer at path time 3 s against nephele render --camera-path: %s\n",
              result.summary.c_str());
  if (!result.pass) nephele::write_image(result.diff, path("diff.png"));
  EXPECT_TRUE(result.pass) << result.summary << " (images in " << dir_ << ")";
}

// record-start ... record-stop FILE writes the flown camera as a path file: the keys are the
// cameras the script placed, at increasing times, and the file reads back (load_camera_path).
TEST_F(ViewerTest, RecordsTheFlownCameraAsAPathFile) {
  const std::string script = write("script.txt",
                                   "frame 2 record-start\n"
                                   "frame 3 set camera.position_m [100.0, 200.0, 300.0]\n"
                                   "frame 3 set time_s 5\n"
                                   "frame 6 set camera.position_m [500.0, 600.0, 700.0]\n"
                                   "frame 6 set camera.roll_deg 20\n"
                                   "frame 6 set time_s 10\n"
                                   "frame 8 record-stop " + path("recorded.toml") + "\n"
                                   "frame 9 quit\n");
  const ProcessRun r = view("--preset default --script " + script);
  expect_clean(r);
  EXPECT_NE(r.output.find("nephele-view: wrote " + path("recorded.toml")), std::string::npos)
      << r.output;

  const nephele::Scene scene = nephele::load_preset("default");
  const nephele::CameraPath recorded = nephele::load_camera_path(path("recorded.toml"), scene);
  const std::vector<nephele::CameraKey>& keys = recorded.keys();
  ASSERT_GE(keys.size(), 3u) << r.output;
  const glm::dvec3 start(scene.camera.position_m), a(100.0, 200.0, 300.0), b(500.0, 600.0, 700.0);
  EXPECT_EQ(keys.front().position_m, start);
  EXPECT_DOUBLE_EQ(keys.front().time_s, 0.0);
  EXPECT_EQ(keys.back().position_m, b);
  EXPECT_NEAR(keys.back().roll_deg, 20.0, 1e-4);
  bool saw_a = false;
  for (const nephele::CameraKey& k : keys) {
    EXPECT_TRUE(k.position_m == start || k.position_m == a || k.position_m == b)
        << k.position_m.x << ", " << k.position_m.y << ", " << k.position_m.z;
    saw_a = saw_a || k.position_m == a;
  }
  EXPECT_TRUE(saw_a);
  // The keys are in scene time since record-start: A after 5 s, B after 10 s (plus a frame).
  for (const nephele::CameraKey& k : keys) {
    if (k.position_m == b) EXPECT_GE(k.time_s, 10.0 - 1.0);
  }
}

// A malformed or missing path in a script is one line with the script's line and the path's
// own message; the run goes on (exit 0) and the flight already under way keeps flying.
TEST_F(ViewerTest, MalformedPathInAScriptIsReportedAndTheFlightGoesOn) {
  const std::string good = write("good.toml", kTwoKeyPath);
  write("bad.toml",
        "[[key]]\ntime_s = 5\nposition_m = [0, 0, 100]\nheading_deg = 0\npitch_deg = 0\n"
        "[[key]]\ntime_s = 1\nposition_m = [0, 0, 200]\nheading_deg = 0\npitch_deg = 0\n");
  const std::string script = write("script.txt",
                                   "frame 1 camera-path " + good + "\n"
                                   "frame 2 camera-path " + path("bad.toml") + "\n"
                                   "frame 2 camera-path " + path("missing.toml") + "\n"
                                   "frame 3 set time_s 2\n"
                                   "frame 3 print-camera\n"
                                   "frame 4 quit\n");
  const ProcessRun r = view("--preset default --script " + script);
  expect_clean(r);
  EXPECT_NE(r.output.find("script.txt:2: " + path("bad.toml") +
                          ": key[1].time_s = 1: must be greater than key[0].time_s = 5\n"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("script.txt:3: " + path("missing.toml") +
                          ": cannot read the camera path: No such file or directory\n"),
            std::string::npos)
      << r.output;
  const std::vector<PrintedCamera> cameras = printed_cameras(r.output);
  ASSERT_EQ(cameras.size(), 1u) << r.output;
  expect_camera(cameras[0],
                nephele::load_camera_path(good, nephele::load_preset("default")).at(2.0));
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

// Issue 40: what `nephele` reads is never what it writes, an output that cannot be written is
// refused before any work, meshes hold numbers, and nothing a file or a flag holds reaches the
// terminal raw. Each refusal: exit status 2, one line naming the parameter, nothing written,
// every input unchanged.
#include <gtest/gtest.h>
#include <stb/stb_image_write.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <vector>

#include "support/grib_files.h"
#include "support/process_run.h"

namespace fs = std::filesystem;

namespace {

using nephele::test::ProcessRun;
using nephele::test::run_cli;

class CliInputs : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("cli_inputs_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  static std::string read(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), {});
  }
  std::string write(const std::string& name, const std::string& text) const {
    std::ofstream(path(name), std::ios::binary) << text;
    return path(name);
  }
  // An 8 x 8 RGBA weather map: half coverage, no storm cells, the scene's type, density 1.
  std::string weather_map(const std::string& name) const {
    std::vector<unsigned char> rgba(8 * 8 * 4);
    for (size_t i = 0; i < rgba.size(); i += 4) rgba[i] = 128, rgba[i + 2] = 128, rgba[i + 3] = 128;
    EXPECT_TRUE(stbi_write_png(path(name).c_str(), 8, 8, 4, rgba.data(), 8 * 4));
    return path(name);
  }
  // `nephele args` must fail with status 2 and one line holding each of `expected`, leaving
  // every file of the folder as it was (no output, no input changed, no temporary file).
  void expect_refused(const std::string& args, std::initializer_list<std::string> expected) {
    std::vector<std::pair<fs::path, std::string>> before;
    for (const auto& entry : fs::directory_iterator(dir_))
      before.emplace_back(entry.path(), entry.is_regular_file() ? read(entry.path()) : "");
    const ProcessRun r = run_cli(args);
    EXPECT_EQ(r.status, 2) << args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
    for (const std::string& e : expected)
      EXPECT_NE(r.output.find(e), std::string::npos) << "'" << e << "' not in: " << r.output;
    std::vector<std::pair<fs::path, std::string>> after;
    for (const auto& entry : fs::directory_iterator(dir_))
      after.emplace_back(entry.path(), entry.is_regular_file() ? read(entry.path()) : "");
    std::sort(before.begin(), before.end());
    std::sort(after.begin(), after.end());
    EXPECT_TRUE(before == after) << args << ": the folder changed";
  }
  fs::path dir_;
};

constexpr const char* kTiny = "render -q --width 8 --height 8 ";

// A closed unit cube (metres), its first vertex's line replaced by `first_vertex`.
std::string cube_obj(const std::string& first_vertex = "v 0 0 0", float size_m = 1.0f) {
  std::string obj = first_vertex + "\n";
  for (int v = 1; v < 8; ++v)
    obj += "v " + std::to_string(size_m * float(v & 1)) + " " +
           std::to_string(size_m * float((v >> 1) & 1)) + " " +
           std::to_string(size_m * float((v >> 2) & 1)) + "\n";
  // Corners: bit 0 x, bit 1 y, bit 2 z (1-based in OBJ), faces outward.
  obj += "f 1 3 4 2\nf 5 6 8 7\nf 1 2 6 5\nf 3 7 8 4\nf 1 5 7 3\nf 2 4 8 6\n";
  return obj;
}

}  // namespace

// Case 10: an output may not be a file the render reads, through any name: the same path,
// another spelling of it, a symbolic link or a hard link.
TEST_F(CliInputs, AnOutputIsNeverAnInput) {
  const std::string wm = weather_map("wm.png");
  expect_refused(kTiny + std::string("--weather-map ") + wm + " -o " + wm,
                 {"--output", "is the same file as the input clouds.weather_map"});
  fs::create_directory(path("sub"));
  expect_refused(
      kTiny + std::string("--weather-map ") + wm + " -o " + dir_.string() + "/./sub/../wm.png",
      {"--output", "clouds.weather_map"});
  fs::create_symlink(wm, path("link.png"));
  expect_refused(kTiny + std::string("--weather-map ") + wm + " -o " + path("link.png"),
                 {"--output", "clouds.weather_map"});
  fs::create_hard_link(wm, path("hard.png"));
  expect_refused(kTiny + std::string("--weather-map ") + wm + " -o " + path("hard.png"),
                 {"--output", "clouds.weather_map"});
  // The stats, the scene file, a terrain, a voxel cloud, a camera path, frames of a sequence.
  const std::string scene = write("scene.toml", "[output]\nwidth = 8\nheight = 8\n");
  expect_refused("render -q --scene " + scene + " -o " + path("x.png") + " --stats-json " + scene,
                 {"--stats-json", "is the same file as the input --scene"});
  const std::string terrain = path("hf.exr");
  ASSERT_EQ(run_cli(std::string(kTiny) + "--light-volume-km 0 -o " + terrain).status, 0);
  expect_refused(kTiny + std::string("--terrain ") + terrain + " -o " + terrain,
                 {"--output", "terrain.file"});
  ASSERT_EQ(run_cli("make-cloud --type cumulus --resolution 16 -o " + path("c.vdb")).status, 0);
  fs::create_symlink(path("c.vdb"), path("c.exr"));
  expect_refused(
      kTiny + std::string("--voxel-cloud ") + path("c.vdb") + "@0,3000,1200 -o " + path("c.exr"),
      {"--output", "voxel_clouds[0].file"});
  const std::string flight =
      write("flight.toml",
            "[[key]]\ntime_s = 0\nposition_m = [0, 0, 2]\nheading_deg = 0\npitch_deg = 5\n"
            "[[key]]\ntime_s = 1\nposition_m = [10, 0, 2]\nheading_deg = 0\npitch_deg = 5\n");
  fs::create_hard_link(flight, path("f_0001.png"));
  expect_refused(kTiny + std::string("--camera-path ") + flight + " --fps 2 -o " + path("f.png"),
                 {"--output", "f_0001.png", "is the same file as the input --camera-path"});
  fs::create_hard_link(wm, path("seq_0002.png"));
  expect_refused(kTiny + std::string("--weather-map ") + wm + " --frames 3 -o " + path("seq.png"),
                 {"--output", "seq_0002.png", "clouds.weather_map"});
  // The other commands: a mesh and a validation suite.
  const std::string mesh = write("mesh.obj", cube_obj());
  fs::create_symlink(mesh, path("mesh.vdb"));
  expect_refused("voxelize " + mesh + " -o " + path("mesh.vdb"), {"--output", "input mesh"});
  const std::string suite = write("suite.toml", "width = 8\n");
  expect_refused("validate --suite " + suite + " --json " + suite + " --out " + path("v"),
                 {"--json", "--suite"});
}

// Case 11: a place that cannot take a new file is refused before rendering, for every output.
// (Root passes the permission check on /proc; the file created and removed there does not.)
TEST_F(CliInputs, AnUnwritableOutputIsRefusedBeforeRendering) {
  if (!fs::is_directory("/proc/self")) GTEST_SKIP() << "no /proc";
  expect_refused(kTiny + std::string("-o /proc/x.png"),
                 {"--output '/proc/x.png': directory '/proc'"});
  expect_refused(kTiny + std::string("-o ") + path("x.png") + " --stats-json /proc/x.json",
                 {"--stats-json '/proc/x.json': directory '/proc'"});
  expect_refused(kTiny + std::string("--frames 2 -o /proc/self/seq.exr"),
                 {"--output '/proc/self/seq_0000.exr': directory '/proc/self'"});
  expect_refused("make-cloud --type cumulus --resolution 16 -o /proc/c.vdb",
                 {"--output '/proc/c.vdb': directory '/proc'"});
  if (fs::is_directory("/sys/kernel"))
    expect_refused(kTiny + std::string("--layers -o /sys/kernel/x.exr"),
                   {"--output '/sys/kernel/x.exr': directory '/sys/kernel'"});
}

// Case 2: an OBJ's numbers are numbers. tinyobjloader reads these as 0 and bakes a deformed
// cloud; each is refused naming the line.
TEST_F(CliInputs, MeshCoordinatesMustBeFiniteDecimals) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"v 1 1 nan", "'nan' is not a finite decimal number"},
      {"v 1 inf 1", "'inf' is not a finite decimal number"},
      {"v abc 1 1", "'abc' is not a finite decimal number"},
      {"v 1 1 -infinity", "'-infinity' is not a finite decimal number"},
      {"v 0x10 1 1", "'0x10' is not a finite decimal number"},
      {"v 1,5 1 1", "'1,5' is not a finite decimal number"},
      {"v 1 1", "2 numbers (v needs at least 3)"},
      {"v 1 1 1e39", "'1e39' is not a finite decimal number"}};
  for (const auto& [line, why] : cases) {
    const std::string mesh = write("bad.obj", cube_obj(line));
    expect_refused("voxelize " + mesh + " --resolution 16 -o " + path("out.vdb"),
                   {"bad.obj: line 1 ('" + line + "'): " + why});
  }
  const std::string face = write("face.obj", cube_obj() + "f 1 2 x\n");
  expect_refused("voxelize " + face + " --resolution 16 -o " + path("out.vdb"),
                 {"line 15", "'x' is not a face corner"});
  // Comments and the optional w stay readable.
  const std::string good = write("good.obj", "# a cube\n" + cube_obj("v 0 0 0 1.0 # w"));
  const ProcessRun ok = run_cli("voxelize " + good + " --resolution 16 -o " + path("good.vdb"));
  EXPECT_EQ(ok.status, 0) << ok.output;
}

// Case 3: a mesh baked into voxels finer than 1 mm is refused with the sizes that work (it
// ended in OpenVDB's "ArithmeticError: Non-zero scale values required", exit 1).
TEST_F(CliInputs, VoxelsFinerThanAMillimetreAreRefused) {
  const std::string mm = write("mm.obj", cube_obj("v 0 0 0", 0.001f));
  expect_refused("voxelize " + mm + " --resolution 256 -o " + path("out.vdb"),
                 {"mm.obj: extent 0.001 m at resolution 256", "at least 0.001 m",
                  "a mesh of at least 0.252 m"});
  expect_refused("voxelize " + mm + " --resolution 16 -o " + path("out.vdb"), {"at least 0.001 m"});
  const std::string tenth = write("tenth.obj", cube_obj("v 0 0 0", 0.0001f));
  expect_refused("voxelize " + tenth + " --resolution 16 -o " + path("out.vdb"),
                 {"a mesh of at least 0.012 m"});
  const std::string fifth = write("fifth.obj", cube_obj("v 0 0 0", 0.2f));
  expect_refused("voxelize " + fifth + " --resolution 256 -o " + path("out.vdb"),
                 {"extent 0.2 m at resolution 256 gives voxels of 0.00079", "at least 0.001 m"});
  // At the limit it bakes.
  const std::string small = write("small.obj", cube_obj("v 0 0 0", 0.03f));
  const ProcessRun ok = run_cli("voxelize " + small + " --resolution 24 -o " + path("small.vdb"));
  EXPECT_EQ(ok.status, 0) << ok.output;
}

// Names from a file or a command line reach the terminal with their control and invisible
// reordering characters as '?': a right-to-left override would reverse the rest of the line.
TEST_F(CliInputs, ErrorLinesCarryNoControlOrBidiCharacters) {
  for (const std::string& name : {std::string("evil\u202egnp.toml"), std::string("a\u2066b.toml"),
                                  std::string("c\xc2\x9b.toml"), std::string("bad\xff\xfe.toml")}) {
    const ProcessRun r = run_cli(std::string(kTiny) + "--scene '" + path(name) + "'");
    EXPECT_EQ(r.status, 2) << r.output;
    for (const char* raw : {"\u202e", "\u2066", "\xc2\x9b", "\xff"})
      EXPECT_EQ(r.output.find(raw), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("?"), std::string::npos) << r.output;
  }
  const ProcessRun flag = run_cli(std::string(kTiny) + "--coverage '0.5\u202e'");
  EXPECT_EQ(flag.status, 2) << flag.output;
  EXPECT_EQ(flag.output.find("\u202e"), std::string::npos) << flag.output;
}

// `--verbose` reports the process's own peak memory.
TEST_F(CliInputs, VerboseReportsPeakResidentMemory) {
  const ProcessRun r =
      run_cli("render --width 8 --height 8 --light-volume-km 0 -v -o " + path("x.png"));
  ASSERT_EQ(r.status, 0) << r.output;
  std::smatch m;
  ASSERT_TRUE(std::regex_search(r.output, m, std::regex("peak resident memory ([0-9]+) MiB")))
      << r.output;
  EXPECT_GT(std::stoi(m[1]), 20);
  EXPECT_LT(std::stoi(m[1]), 4096);
}

namespace {

// The weather as a report gives it on the command line: a wind's direction without a speed, two
// speeds, rain that would end above its cloud base; each one line naming the flags, exit 2,
// nothing written.
TEST_F(CliInputs, WeatherFlagsAreRefusedNamingThem) {
  const std::string out = path("x.png");
  expect_refused(kTiny + std::string("--wind-from-deg 240 -o ") + out,
                 {"--wind-from-deg 240", "needs a speed, --wind-speed-kt or --wind-speed-mps"});
  expect_refused(
      kTiny + std::string("--wind-from-deg 240 --wind-speed-kt 5 --wind-speed-mps 3 -o ") + out,
      {"--wind-speed-kt 5", "(--wind-speed-mps 3)"});
  expect_refused(
      kTiny + std::string("--precipitation-kind hail --precipitation-mm-per-h 2 -o ") + out,
      {"--precipitation-kind", "hail", "\"snow\""});
  EXPECT_FALSE(fs::exists(out));
}

// --cloud-layer GENUS,BASE_M,TOP_M,OKTAS: a malformed one, a genus the layer cannot draw and
// clouds that overlap another layer's are refused in one line naming the flag; nothing written.
TEST_F(CliInputs, CloudLayerFlagsAreRefusedNamingThem) {
  const std::string out = path("x.png");
  expect_refused(kTiny + std::string("--cloud-layer altocumulus,2500,3200 -o ") + out,
                 {"--cloud-layer altocumulus,2500,3200", "3 comma-separated parts",
                  "expected GENUS,BASE_M,TOP_M,OKTAS"});
  expect_refused(kTiny + std::string("--cloud-layer altocumulus,low,3200,4 -o ") + out,
                 {"--cloud-layer", "'low' is not a number"});
  expect_refused(kTiny + std::string("--cloud-layer cirrus,7000,7500,2 -o ") + out,
                 {"--cloud-layer #1 genus cirrus", "\"cumulonimbus\""});
  expect_refused(kTiny +
                     std::string("--cloud-layer altocumulus,4500,5000,3 --cloud-layer "
                                 "cumulus,4800,6000,2 -o ") +
                     out,
                 {"--cloud-layer #2 base_m 4800", "overlap cloud_layers[0]'s clouds (4500-5000 m"});
  EXPECT_FALSE(fs::exists(out));
}

// A forecast that cannot serve: one line naming --grib, the file and why; nothing written.
TEST_F(CliInputs, ForecastFilesAreRefusedNamingTheFlag) {
  const std::string out = path("x.png");
  const std::string notes = path("notes.grib2");
  std::ofstream(notes) << "not a forecast\n";
  expect_refused(kTiny + std::string("--grib ") + notes + " -o " + out,
                 {"--grib", "holds no GRIB message"});
  const std::string europe = path("europe.grib2");
  nephele::test::write_grib(europe, {{.short_name = "lcc"}});  // 30-60 N, 10 W-30 E
  expect_refused(
      kTiny + std::string("--grib ") + europe + " --lat-deg -33.9 --lon-deg 151.2 -o " + out,
      {"--grib", "does not cover the observer at latitude -33.9000, longitude 151.2000"});
  EXPECT_FALSE(fs::exists(out));
}

}  // namespace

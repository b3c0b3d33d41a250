// `nephele render` with hostile image inputs (issue 40, items 5 to 9): a weather map or a
// terrain file that is corrupt, over its limit or off the globe gives exactly one line on
// stderr naming the key or flag, exit status 2, and no image. The files are a few kilobytes.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "support/process_run.h"
#include "support/terrain_files.h"

namespace nephele {
namespace {

namespace fs = std::filesystem;

class InputLimitsCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("input_limits_cli_" +
            std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // One line on stderr (stdout is dropped) holding each of `expected`, exit 2, no image; the
  // line.
  std::string expect_refused(const std::string& args, const std::vector<std::string>& expected) {
    const std::string out = path("out.png");
    const test::ProcessRun r =
        test::run_cli("render -q --width 8 --height 8 " + args + " -o " + out, "2>&1 >/dev/null");
    EXPECT_EQ(r.status, 2) << args << ": " << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_EQ(r.output.rfind("nephele: error: ", 0), 0u) << r.output;
    for (const std::string& e : expected)
      EXPECT_NE(r.output.find(e), std::string::npos) << "'" << e << "' in " << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
    return r.output;
  }
  fs::path dir_;
};

// Item 8: a map whose data is corrupt (found only when it is decoded) names the key and says
// what a weather map must be; so do a truncated one and one whose data inflates too far.
TEST_F(InputLimitsCli, CorruptWeatherMapsNameTheKey) {
  std::string rows;
  for (int y = 0; y < 8; ++y) rows += '\0' + std::string(8 * 4, char(90));
  std::string bad = test::zlib_stored(rows);
  bad[2] = char(0x07);  // a reserved deflate block type
  const std::string requirement =
      "a weather map is an RGBA PNG (8 or 16 bits) or an EXR of at most 8192 x 8192";
  test::write_bytes(path("bad.png"), test::png_bytes(8, 8, 8, 6, bad));
  expect_refused("--weather-map " + path("bad.png"),
                 {"clouds.weather_map '", "cannot decode the PNG", requirement});
  const std::string good = test::png_rgba8_bytes(8, 8, 90);
  test::write_bytes(path("cut.png"), good.substr(0, good.size() - 30));
  expect_refused("--weather-map " + path("cut.png"),
                 {"--weather-map ", ": is truncated", requirement});
  test::write_bytes(
      path("long.png"),
      test::png_bytes(8, 8, 8, 6, test::zlib_stored(rows + std::string(20000, '\0'))));
  expect_refused("--weather-map " + path("long.png"),
                 {"clouds.weather_map '", "inflates to more than", requirement});
}

// Item 7: wider or taller than the device's 16384 was accepted and then refused by the device
// (exit 1, and under --validation the image was still written); the limit refuses it first.
TEST_F(InputLimitsCli, WeatherMapsOverTheLimitAreRefusedBeforeRendering) {
  const std::string idat = test::zlib_stored(std::string(16, '\0'));
  for (const auto& [w, h] : {std::pair{16385u, 1u}, {1u, 16385u}, {12000u, 12000u}}) {
    const std::string file = path("map_" + std::to_string(w) + "x" + std::to_string(h) + ".png");
    test::write_bytes(file, test::png_bytes(w, h, 8, 6, idat));
    expect_refused("--validation --weather-map " + file,
                   {"--weather-map ", ": " + std::to_string(w) + " x " + std::to_string(h) +
                                          " pixels: at most 8192 a side are allowed"});
  }
}

// Items 5 and 6: GDAL's own "ERROR 1: ..." lines no longer precede nephele's; a model beyond a
// pole is refused.
TEST_F(InputLimitsCli, GeoTiffRefusalsAreOneLine) {
  const int n = 64;
  std::vector<float> heights(size_t(n * n));
  for (size_t i = 0; i < heights.size(); ++i) heights[i] = 700.0f + float((i * 7919) % 1013);
  test::write_geotiff(path("dem.tif"), n, n, heights, 0.03, 0.0, 0.001, true, true);
  test::corrupt_first_strip(path("dem.tif"), 40);
  expect_refused("--terrain " + path("dem.tif"),
                 {"terrain.file '", "cannot read its heights", "(GDAL: "});
  test::write_geotiff(path("pole.tif"), 8, 8, std::vector<float>(64, 1.0f), 95.0, 0.0, 0.01);
  expect_refused("--terrain " + path("pole.tif"),
                 {"--terrain ", ": spans latitudes [94.92, 95], beyond a pole"});
  test::write_bytes(path("t.png"),
                    test::png_bytes(16384, 16384, 16, 0, test::zlib_stored(std::string(8, '\0'))));
  expect_refused("--terrain " + path("t.png"),
                 {"--terrain ", ": 16384 x 16384 points: at most 8192 a side"});
}

// A corrupt albedo map (found when the terrain module decodes it) is one line naming the key
// and its path once: it read "terrain.albedo_map '...': image '...': cannot decode PNG: ...".
TEST_F(InputLimitsCli, ACorruptAlbedoMapIsOneLineNamingItsPathOnce) {
  std::string rows;
  for (int y = 0; y < 8; ++y) rows += '\0' + std::string(8 * 4, char(90));
  std::string bad = test::zlib_stored(rows);
  bad[2] = char(0x07);  // a reserved deflate block type
  test::write_bytes(path("albedo.png"), test::png_bytes(8, 8, 8, 6, bad));
  std::ofstream(path("scene.toml")) << "[terrain]\npreset = \"mountains\"\nresolution = 16\n"
                                    << "albedo_map = \"" << path("albedo.png") << "\"\n";
  const std::string line =
      expect_refused("--light-volume-km 0 --scene " + path("scene.toml"),
                     {"terrain.albedo_map '" + path("albedo.png") + "': cannot decode the PNG (",
                      "; an albedo map is a PNG or an EXR of at most 4096 x 4096 pixels"});
  EXPECT_EQ(line.find("albedo.png"), line.rfind("albedo.png")) << line;
  EXPECT_EQ(line.find("image '"), std::string::npos) << line;
}

}  // namespace
}  // namespace nephele

// The terrain's heightfields (src/terrain): each file format read into heights in metres, north
// up, at the right place; the procedural mountains; bad input refused with one line naming the
// parameter, the value and what is allowed, at validation (before anything is rendered) and
// from the command line (nothing written).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "nephele/camera_path.h"
#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "support/process_run.h"
#include "support/terrain_files.h"
#include "terrain/heightfield.h"
#include "voxel/voxel_grid.h"

namespace nephele {
namespace {

namespace fs = std::filesystem;

class TerrainFiles : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(NEPHELE_TEST_OUTPUT_DIR) /
           ("terrain_" + std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // The message validate_scene throws for the scene's terrain, "" when it accepts it.
  static std::string rejection(const Scene& scene) {
    try {
      validate_scene(scene);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
};

Scene with_file(const std::string& file) {
  Scene s = load_preset("default");
  s.terrain.file = file;
  s.terrain.extent_m = glm::vec2(3000.0f, 2000.0f);
  s.terrain.center_m = glm::vec2(100.0f, 5000.0f);
  s.terrain.height_m = 1200.0f;
  s.terrain.base_m = 50.0f;
  return s;
}

TEST_F(TerrainFiles, Png16IsReadNorthUpScaledToTheHeightAndPlaced) {
  // 4 x 3 points: 0 everywhere but 1000 at the north-east corner and 4000 at the south-west.
  std::vector<unsigned short> v(12, 0);
  v[3] = 1000;
  v[8] = 4000;
  test::write_png16(path("h.png"), 4, 3, 1, v);
  const Scene s = with_file(path("h.png"));
  ASSERT_EQ(rejection(s), "");
  const terrain::Heightfield f = terrain::load_heightfield(s);
  ASSERT_EQ(f.width, 4);
  ASSERT_EQ(f.height, 3);
  EXPECT_FLOAT_EQ(f.at(0, 2), 1250.0f);  // the largest value: base + height
  EXPECT_FLOAT_EQ(f.at(3, 0), 50.0f + 1200.0f * 0.25f);
  EXPECT_FLOAT_EQ(f.at(1, 1), 50.0f);
  // The south-west corner is at centre - extent / 2, the north-east at centre + extent / 2.
  EXPECT_NEAR(f.sample({100.0f - 1500.0f, 5000.0f - 1000.0f}, -1.0f), 1250.0f, 1e-3f);
  EXPECT_NEAR(f.sample({100.0f + 1500.0f, 5000.0f + 1000.0f}, -1.0f), 350.0f, 1e-3f);
  EXPECT_EQ(f.sample({100.0f + 1600.0f, 5000.0f}, -7.0f), -7.0f);  // off the extent
}

TEST_F(TerrainFiles, ExrHeightsAreReadFromItsFirstColourChannel) {
  Image image(3, 2);
  for (int i = 0; i < 6; ++i) image.pixels[size_t(i)] = glm::vec4(float(i * 100), 9999.0f, 9999.0f, 1.0f);
  write_image(image, path("h.exr"), 1.0f, ExrPixels::kFloat);
  const terrain::Heightfield f = terrain::load_heightfield(with_file(path("h.exr")));
  ASSERT_EQ(f.width, 3);
  EXPECT_FLOAT_EQ(f.at(2, 1), 1250.0f);              // R 500, the largest
  EXPECT_FLOAT_EQ(f.at(1, 0), 50.0f + 1200.0f * 0.2f);  // R 100
}

// tinyobjloader ends its own error with a newline: the message stays one line, for a terrain
// mesh and a mesh to voxelize alike (a face index of 0, found by FuzzFiles).
TEST_F(TerrainFiles, ObjReadErrorsAreOneLine) {
  const std::string text = "v -1000 0 1000\nv 1000 0 1000\nv 200 400 -300\nf 1 2 0\n";
  std::ofstream(path("zero.obj")) << text;
  std::string terrain_message, voxel_message;
  try {
    terrain::load_heightfield(with_file(path("zero.obj")));
  } catch (const InputError& e) {
    terrain_message = e.what();
  }
  try {
    voxel::voxelize_mesh_text(text, "zero.obj", 16);
  } catch (const InputError& e) {
    voxel_message = e.what();
  }
  for (const std::string& message : {terrain_message, voxel_message}) {
    EXPECT_NE(message.find("is not a readable OBJ mesh (Failed parse `f' line"), std::string::npos)
        << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    EXPECT_EQ(message.back(), ')') << message;
    EXPECT_EQ(message.find("?)"), std::string::npos) << message;  // the newline, made printable
  }
}

TEST_F(TerrainFiles, ObjMeshIsSeenFromAbove) {
  // A pyramid 400 m high on a 2 km square (x east, y up, -z north), its apex north-east of
  // the square's centre by (200, 300) m.
  std::ofstream(path("p.obj")) << "v -1000 0 1000\nv 1000 0 1000\nv 1000 0 -1000\nv -1000 0 -1000\n"
                                  "v 200 400 -300\nf 1 2 5\nf 2 3 5\nf 3 4 5\nf 4 1 5\n";
  Scene s = with_file(path("p.obj"));
  s.terrain.resolution = 201;  // 10 m cells
  const terrain::Heightfield f = terrain::load_heightfield(s);
  EXPECT_NEAR(f.extent_m.x, 2000.0f, 1e-3f);
  EXPECT_NEAR(f.max_height_m(), 400.0f, 1.0f);
  EXPECT_NEAR(f.sample(s.terrain.center_m + glm::vec2(200.0f, 300.0f), -1.0f), 400.0f, 1.0f);
  // Halfway from the apex to the south edge's middle, on the south face: 200 m.
  EXPECT_NEAR(f.sample(s.terrain.center_m + glm::vec2(100.0f, -350.0f), -1.0f), 200.0f, 2.0f);
  EXPECT_NEAR(f.sample(s.terrain.center_m + glm::vec2(-1000.0f, -1000.0f), -1.0f), 0.0f, 1e-3f);
}

TEST_F(TerrainFiles, GeoTiffIsPlacedByItsCoordinates) {
  // 41 x 41 cells of 0.001 deg, a 1500 m plateau of 5 x 5 cells about (46.52 N, 7.98 E),
  // 800 m elsewhere.
  const int n = 41;
  std::vector<float> h(size_t(n * n), 800.0f);
  for (int y = 18; y <= 22; ++y)
    for (int x = 18; x <= 22; ++x) h[size_t(y * n + x)] = 1500.0f;
  test::write_geotiff(path("dem.tif"), n, n, h, 46.5405, 7.9595, 0.001);
  Scene s = load_preset("default");
  s.terrain.file = path("dem.tif");
  s.location.lat_deg = 46.5f;
  s.location.lon_deg = 7.95f;
  s.location.altitude_m = 600.0f;
  ASSERT_EQ(rejection(s), "");
  const terrain::Heightfield f = terrain::load_heightfield(s);
  // The plateau's middle cell's centre is at (46.5405 - 20.5 x 0.001, 7.9595 + 20.5 x 0.001).
  const glm::dvec3 centre = enu_from_lat_lon(s, 46.5405 - 0.0205, 7.9595 + 0.0205, 0.0);
  EXPECT_NEAR(f.sample(glm::vec2(centre), -1.0f), 1500.0f - 600.0f, 1.0f);
  EXPECT_NEAR(f.sample(glm::vec2(centre) + glm::vec2(300.0f, 0.0f), -1.0f), 200.0f, 1.0f);
  EXPECT_NEAR(f.sample(glm::vec2(centre) + glm::vec2(0.0f, -350.0f), -1.0f), 200.0f, 1.0f);
  EXPECT_NEAR(f.max_height_m(), 900.0f, 1e-3f);
  // About 41 x 0.001 deg: 3.1 km east-west at this latitude, 4.6 km north-south.
  EXPECT_NEAR(f.extent_m.x, 41 * 0.001 * 111195.0 * std::cos(46.52 * 3.14159265 / 180.0), 60.0);
  EXPECT_NEAR(f.extent_m.y, 41 * 0.001 * 111195.0 * 6360.0 / 6371.0, 60.0);
}

// Item 6: a GeoTIFF on a latitude-longitude grid must lie on the globe: beyond a pole PROJ
// wraps it onto the other side; longitudes beyond [-360, 360], or spanning more than a turn,
// mean nothing; a geotransform without area places nothing. Refused when the scene is checked.
TEST_F(TerrainFiles, GeoTiffsOffTheGlobeAreRefused) {
  const std::vector<float> h(64, 100.0f);
  const struct {
    std::string name;
    double north_deg, west_deg, cell_deg;
    int w;
    std::string expected;
  } cases[] = {
      {"north95.tif", 95.0, 7.0, 0.01, 8, "spans latitudes [94.92, 95], beyond a pole; latitudes must be in [-90, 90]"},
      {"south91.tif", -90.95, 7.0, 0.01, 8, "spans latitudes [-91.03, -90.95], beyond a pole"},
      {"north_edge.tif", 90.04, 7.0, 0.01, 8, "spans latitudes [89.96, 90.04], beyond a pole"},
      {"east400.tif", 10.0, 400.0, 0.01, 8, "spans longitudes [400, 400.08]; longitudes must be in [-360, 360]"},
      {"west370.tif", 10.0, -370.0, 0.01, 8, "spans longitudes [-370, -369.92]; longitudes must be in [-360, 360]"},
      {"flat.tif", 10.0, 7.0, 0.0, 8, "its geotransform is degenerate (its pixels have no area)"},
  };
  for (const auto& c : cases) {
    test::write_geotiff(path(c.name), c.w, 8, std::vector<float>(size_t(c.w) * 8, 100.0f), c.north_deg, c.west_deg,
                        c.cell_deg);
    const std::string message = rejection(with_file(path(c.name)));
    EXPECT_EQ(message.rfind("terrain.file = \"", 0), 0u) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos) << c.expected << " in " << message;
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 0) << message;
  }
  // Pole to pole, and a grid across the antimeridian, are on it.
  test::write_geotiff(path("globe.tif"), 8, 8, h, 90.0, -180.0, 22.5);
  EXPECT_EQ(rejection(with_file(path("globe.tif"))), "");
  test::write_geotiff(path("dateline.tif"), 8, 8, h, 10.0, 179.98, 0.01);
  EXPECT_EQ(rejection(with_file(path("dateline.tif"))), "");
}

// A model far from the scene's location (or larger than terrain.extent_m allows) is refused
// when it is placed, in one line, rather than drawn wrapped about the planet.
TEST_F(TerrainFiles, GeoTiffsFarFromTheLocationAreRefusedWhenPlaced) {
  test::write_geotiff(path("far.tif"), 8, 8, std::vector<float>(64, 100.0f), 30.0, 7.0, 0.01);
  Scene s = with_file(path("far.tif"));
  s.location.lat_deg = 46.5f;
  s.location.lon_deg = 7.95f;
  ASSERT_EQ(rejection(s), "");
  try {
    terrain::load_heightfield(s);
    ADD_FAILURE() << "a model 1800 km away was placed";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("terrain.file '", 0), 0u) << message;
    EXPECT_NE(message.find("at most 1000 km a side, centred within 1000 km"), std::string::npos) << message;
  }
}

// Item 5: a GeoTIFF whose strip is corrupt is refused in nephele's one line, quoting GDAL's
// error, and GDAL prints nothing of its own.
TEST_F(TerrainFiles, CorruptGeoTiffStripsAreOneLineAndGdalStaysQuiet) {
  const int n = 64;
  std::vector<float> heights(size_t(n * n));
  for (size_t i = 0; i < heights.size(); ++i) heights[i] = 700.0f + float((i * 7919) % 1013);  // incompressible
  test::write_geotiff(path("dem.tif"), n, n, heights, 46.55, 7.93, 0.001, true, true);
  test::corrupt_first_strip(path("dem.tif"), 40);
  Scene s = with_file(path("dem.tif"));
  s.location.lat_deg = 46.5f;
  s.location.lon_deg = 7.95f;
  ::testing::internal::CaptureStderr();
  const std::string validation = rejection(s);
  std::string message;
  try {
    terrain::load_heightfield(s);
  } catch (const InputError& e) {
    message = e.what();
  }
  const std::string printed = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(validation, "");  // the header is whole
  EXPECT_EQ(printed, "");
  EXPECT_EQ(message.rfind("terrain.file '", 0), 0u) << message;
  EXPECT_NE(message.find("cannot read its heights; the file is corrupt (GDAL: "), std::string::npos) << message;
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 0) << message;
}

TEST_F(TerrainFiles, BadFilesAreRefusedNamingTheParameterAndWhatIsAllowed) {
  std::vector<unsigned short> v(16, 7);
  test::write_png16(path("rgb16.png"), 4, 4, 3, v);
  std::ofstream(path("grey8.png"), std::ios::binary);  // replaced just below
  {
    Image image(4, 4);
    write_image(image, path("grey8.png"));  // an 8-bit PNG (write_image writes 8 bits)
  }
  test::write_geotiff(path("plain.tif"), 8, 8, std::vector<float>(64, 10.0f), 0, 0, 0, false);
  test::write_png16(path("wide.png"), 8193, 2, 1, std::vector<unsigned short>(8193 * 2, 1));
  const struct {
    std::string file, expected;
  } cases[] = {
      {path("missing.png"), "cannot read the file"},
      {path("grey8.png"), "is an 8-bit PNG; heights need a 16-bit greyscale PNG"},
      {path("rgb16.png"), "has 3 channels; heights need a 16-bit greyscale PNG (1 channel)"},
      {path("plain.tif"), "has no georeferencing"},
      {path("wide.png"), "8193 x 2 points: at most 8192 a side"},
      {path("heights.jpg"), "must name a .png (16-bit grey), .exr, .tif/.tiff (GeoTIFF) or .obj file"},
  };
  for (const auto& c : cases) {
    const std::string message = rejection(with_file(c.file));
    EXPECT_EQ(message.rfind("terrain.file = \"", 0), 0u) << message;  // long paths are shortened
    EXPECT_NE(message.find(c.expected), std::string::npos) << message;
    EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 0) << message;
  }
  Scene s = load_preset("default");
  s.terrain.preset = "mountains";
  s.terrain.extent_m = glm::vec2(0.0f, 1000.0f);
  EXPECT_NE(rejection(s).find("terrain.extent_m = (0, 1000): each component must be in (0, 1e6]"),
            std::string::npos)
      << rejection(s);
  s.terrain.extent_m = glm::vec2(1000.0f);
  s.terrain.albedo_map = path("albedo.jpg");
  EXPECT_NE(rejection(s).find("terrain.albedo_map = \""), std::string::npos) << rejection(s);
  EXPECT_NE(rejection(s).find("must name a .png (sRGB) or .exr (linear) image"), std::string::npos) << rejection(s);
  s.terrain.albedo_map.clear();
  s.terrain.file = path("rgb16.png");
  EXPECT_NE(rejection(s).find("give at most one of file and preset"), std::string::npos) << rejection(s);
}

TEST_F(TerrainFiles, CommandLineRefusesBadTerrainWithOneLineAndWritesNothing) {
  std::vector<unsigned short> v(16, 7);
  test::write_png16(path("rgb16.png"), 4, 4, 3, v);
  const std::string out = path("out.png");
  for (const auto& [args, expected] : std::vector<std::pair<std::string, std::string>>{
           {"--terrain " + path("rgb16.png"), "has 3 channels; heights need a 16-bit greyscale PNG"},
           {"--terrain " + path("none.exr"), "cannot read the file"},
           {"--terrain mountains --terrain-extent-m 0,5", "--terrain-extent-m 0,5: each component must be in (0, 1e6]"},
           {"--terrain mountains --terrain-height-m -3", "--terrain-height-m -3: must be in [0, 10000]"}}) {
    const test::ProcessRun r = test::run_cli("render --width 8 --height 8 " + args + " --output " + out);
    EXPECT_EQ(r.status, 2) << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
    EXPECT_NE(r.output.find(expected), std::string::npos) << "'" << expected << "' in " << r.output;
    EXPECT_NE(r.output.find("error: --terrain"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(out)) << args;
  }
}

TEST(TerrainMountains, TheRangeReachesItsHeightAndStandsOnItsBase) {
  TerrainParams t;
  t.resolution = 128;
  t.base_m = 100.0f;
  t.height_m = 2500.0f;
  const terrain::Heightfield a = terrain::make_mountains(t), b = terrain::make_mountains(t);
  EXPECT_EQ(a.height_m, b.height_m);  // the same seed, the same range
  EXPECT_NEAR(a.max_height_m(), 2600.0f, 1e-2f);
  EXPECT_NEAR(a.min_height_m(), 100.0f, 1e-2f);
  for (int i = 0; i < 128; ++i) {  // the edges are at the base
    EXPECT_FLOAT_EQ(a.at(i, 0), 100.0f);
    EXPECT_FLOAT_EQ(a.at(0, i), 100.0f);
  }
  // A range, not a lone spike: a tenth of the land within the inner two thirds stands above
  // half the height.
  int high = 0, inner = 0;
  for (int y = 22; y < 106; ++y)
    for (int x = 22; x < 106; ++x, ++inner) high += a.at(x, y) > 1350.0f;
  EXPECT_GT(double(high) / inner, 0.1);
  t.seed = 2;
  EXPECT_NE(terrain::make_mountains(t).height_m, a.height_m);
}

TEST(TerrainPyramid, EachSquareBoundsEveryHeightInsideIt) {
  TerrainParams t;
  t.resolution = 38;  // 37 cells: odd, so the squares at the far edges are partial
  const terrain::Heightfield f = terrain::make_mountains(t);
  const terrain::MaxPyramid p = terrain::max_pyramid(f);
  ASSERT_EQ(p.levels, 6);  // 19, 10, 5, 3, 2, 1 squares a side
  EXPECT_EQ(p.size(1), glm::ivec2(19));
  EXPECT_EQ(p.size(6), glm::ivec2(1));
  EXPECT_FLOAT_EQ(p.at(6, 0, 0), f.max_height_m());
  for (int level = 1; level <= p.levels; ++level)
    for (int y = 0; y <= 37; ++y)
      for (int x = 0; x <= 37; ++x) {
        // Point (x, y) belongs to the cells x - 1 and x (and y - 1, y): both squares bound it.
        for (int cy = std::max(y - 1, 0); cy <= std::min(y, 36); ++cy)
          for (int cx = std::max(x - 1, 0); cx <= std::min(x, 36); ++cx)
            ASSERT_LE(f.at(x, y), p.at(level, cx >> level, cy >> level)) << level;
      }
  // ... and is tight: the top of level 1's first square is one of its points.
  float m = 0.0f;
  for (int y = 0; y <= 2; ++y)
    for (int x = 0; x <= 2; ++x) m = std::max(m, f.at(x, y));
  EXPECT_FLOAT_EQ(p.at(1, 0, 0), m);
}

}  // namespace
}  // namespace nephele

// A GRIB forecast's cloud cover (weather/grib.h): files written with ecCodes from its samples.
#include "weather/grib.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "nephele/sky.h"
#include "support/grib_files.h"

namespace nephele::weather {
namespace {

namespace fs = std::filesystem;
using test::GribField;
using test::write_grib;

class Grib : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("nephele_grib_" + std::to_string(::testing::UnitTest::GetInstance()->random_seed()) +
            "_" + ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

  // The observer of these tests: Frankfurt.
  static constexpr double kLat = 50.03, kLon = 8.57, kRadiusM = 6360e3;

  static std::string refusal(const std::string& file, double lat = kLat, double lon = kLon) {
    try {
      read_grib_cover(file, lat, lon, std::nullopt, kRadiusM);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }

  fs::path dir_;
};

// A field linear in latitude and longitude: bilinear resampling gives it back exactly.
double slope(double lat, double lon) {
  return std::clamp(0.3 + 0.02 * (lat - 50.0) + 0.01 * (lon - 8.0), 0.0, 1.0);
}

TEST_F(Grib, EcmwfFractionsAndWmoPercentAreReadAsCover) {
  const std::string file = path("cover.grib2");
  GribField low{.short_name = "lcc", .value = slope};
  GribField medium{.short_name = "mcc", .value = [](double, double) { return 0.25; }};
  // The WMO's high cloud cover (parameter 5), in percent.
  GribField high{.parameter_number = 5, .surface = 1, .scale = 100.0, .value = [](double, double) {
                   return 0.6;
                 }};
  GribField temperature{.short_name = "t", .value = [](double, double) { return 280.0; }};
  write_grib(file, {temperature, low, medium, high});
  const GribCover c = read_grib_cover(file, kLat, kLon, std::nullopt, kRadiusM);
  EXPECT_EQ(c.messages, 4);
  EXPECT_TRUE(c.has[kLowCover] && c.has[kMediumCover] && c.has[kHighCover]);
  EXPECT_FALSE(c.has[kTotalCover]);
  EXPECT_NEAR(c.at_observer[kLowCover], slope(kLat, kLon), 2e-3);
  EXPECT_NEAR(c.at_observer[kMediumCover], 0.25, 2e-3);
  EXPECT_NEAR(c.at_observer[kHighCover], 0.6, 2e-3);
  EXPECT_EQ(c.valid_time, "2026-12-03T12:00:00Z");
  // The box: 100 km north of the observer is 0.9 deg of latitude further, where the field is
  // 0.018 more; 100 km east, 1.40 deg of longitude, 0.014 more.
  const int n = kForecastMapSize;
  const auto texel = [&](double east_m, double north_m) {
    const int i = int(std::floor((east_m / (2.0 * kForecastHalfExtentM) + 0.5) * n));
    const int j = int(std::floor((north_m / (2.0 * kForecastHalfExtentM) + 0.5) * n));
    return c.map[size_t(j * n + i)][kLowCover];
  };
  const double texel_m = 2.0 * kForecastHalfExtentM / n;
  const double deg = 180.0 / 3.14159265358979;
  const auto expected = [&](double east_m, double north_m) {
    const double i = std::floor((east_m / (2.0 * kForecastHalfExtentM) + 0.5) * n);
    const double j = std::floor((north_m / (2.0 * kForecastHalfExtentM) + 0.5) * n);
    const double e = (i + 0.5) * texel_m - kForecastHalfExtentM;
    const double no = (j + 0.5) * texel_m - kForecastHalfExtentM;
    return slope(kLat + no / kRadiusM * deg, kLon + e / (kRadiusM * std::cos(kLat / deg)) * deg);
  };
  for (const auto& [e, no] : {std::pair{0.0, 0.0}, {100e3, 0.0}, {0.0, 100e3}, {-250e3, -200e3}})
    EXPECT_NEAR(texel(e, no), expected(e, no), 2e-3) << e << " " << no;
  EXPECT_NEAR(texel(0.0, 100e3) - texel(0.0, 0.0), 0.018, 2e-3);
  EXPECT_FLOAT_EQ(c.box_covered, 1.0f);
}

TEST_F(Grib, TotalCoverAloneIsTheLowLayers) {
  const std::string file = path("total.grib2");
  write_grib(file, {{.short_name = "tcc", .value = [](double, double) { return 0.8; }}});
  const GribCover c = read_grib_cover(file, kLat, kLon, std::nullopt, kRadiusM);
  EXPECT_TRUE(c.has[kTotalCover] && c.has[kLowCover]);
  EXPECT_NEAR(c.at_observer[kLowCover], 0.8, 2e-3);
  const WeatherState s = weather_from_grib(c, WeatherState{}, 100.0f);
  EXPECT_EQ(s.low.genus, Genus::Stratocumulus);  // 6.4 oktas: a deck
  EXPECT_NEAR(s.low.coverage_oktas, 6.4f, 0.02f);
  EXPECT_EQ(s.high.coverage_oktas, 0.0f);
}

// Without levels each genus takes its own altitudes; a deck's shell and an altocumulus' would
// overlap, and meet half way instead, so that the scene is valid.
TEST_F(Grib, LayersWithoutLevelsDoNotOverlap) {
  const std::string file = path("front.grib2");
  write_grib(file, {{.short_name = "lcc", .value = [](double, double) { return 0.95; }},
                    {.short_name = "mcc", .value = [](double, double) { return 0.6; }},
                    {.short_name = "hcc", .value = [](double, double) { return 0.7; }}});
  const GribCover c = read_grib_cover(file, kLat, kLon, std::nullopt, kRadiusM);
  const WeatherState s = weather_from_grib(c, WeatherState{}, 0.0f);
  EXPECT_EQ(s.low.genus, Genus::Stratocumulus);
  EXPECT_LE(s.low.top_m, s.high.base_m);
  EXPECT_GT(s.low.top_m, 1800.0f);    // the deck's clouds, to 1,800 m, stay in its shell
  EXPECT_LT(s.high.base_m, 3500.0f);  // and the altocumulus' from 3,500 m in its
  EXPECT_GE(s.sheet.base_m, s.high.top_m);
  Scene scene;
  EXPECT_NO_THROW(apply_weather(s, scene));
  EXPECT_NO_THROW(validate_scene(scene));
}

TEST_F(Grib, TheFieldsAtTheScenesTimeAreBlendedBetweenValidityTimes) {
  const std::string file = path("steps.grib2");
  std::vector<GribField> fields;
  for (long step : {0, 6, 12})
    fields.push_back({.short_name = "lcc",
                      .date = 20261203,
                      .time = 0,
                      .step_h = step,
                      .value = [step](double, double) { return 0.1 * double(step) / 6.0 + 0.1; }});
  write_grib(file, fields);
  const auto at = [&](std::optional<double> jd) {
    return read_grib_cover(file, kLat, kLon, jd, kRadiusM);
  };
  EXPECT_EQ(at(std::nullopt).valid_time, "2026-12-03T00:00:00Z");  // none: the earliest
  const double midnight = *julian_day_from_iso8601("2026-12-03T00:00:00Z");
  // 10:00: two thirds of the way from the 06:00 field (0.2) to the 12:00 one (0.3), over the
  // whole map as at the observer.
  const GribCover late = at(midnight + 10.0 / 24.0);
  EXPECT_EQ(late.valid_time, "2026-12-03T06:00:00Z");
  EXPECT_EQ(late.valid_time_next, "2026-12-03T12:00:00Z");
  EXPECT_NEAR(late.blend, 2.0f / 3.0f, 1e-4f);
  EXPECT_NEAR(late.at_observer[kLowCover], 0.2 + 0.1 * 2.0 / 3.0, 2e-3);
  EXPECT_NEAR(late.map[late.map.size() / 3][kLowCover], 0.2 + 0.1 * 2.0 / 3.0, 2e-3);
  EXPECT_EQ(late.valid_times, 3);
  // At a validity time, that field alone; after the last, the last.
  const GribCover six = at(midnight + 6.0 / 24.0);
  EXPECT_EQ(six.valid_time, "2026-12-03T06:00:00Z");
  EXPECT_EQ(six.blend, 0.0f);
  EXPECT_NEAR(six.at_observer[kLowCover], 0.2, 2e-3);
  EXPECT_EQ(at(midnight + 1.0).valid_time, "2026-12-03T12:00:00Z");
  EXPECT_EQ(at(midnight - 1.0).valid_time, "2026-12-03T00:00:00Z");
  // A sequence sees the cover change smoothly: a minute moves it by a 360th of the step.
  const float a = at(midnight + 9.0 / 24.0).at_observer[kLowCover];
  const float b = at(midnight + 9.0 / 24.0 + 1.0 / 1440.0).at_observer[kLowCover];
  EXPECT_NEAR(b - a, 0.1f / 360.0f, 2e-5f);
}

TEST_F(Grib, CoverOnPressureLevelsPlacesTheLayers) {
  const std::string file = path("levels.grib2");
  const auto cover_at = [](long hpa) {
    return [hpa](double, double) {
      return hpa == 850 || hpa == 900 ? 0.9 : hpa == 500 ? 0.4 : 0.0;
    };
  };
  std::vector<GribField> fields = {
      {.short_name = "lcc", .value = [](double, double) { return 0.9; }},
      {.short_name = "mcc", .value = [](double, double) { return 0.4; }}};
  for (long hpa : {1000, 950, 900, 850, 800, 700, 600, 500, 400, 300})
    fields.push_back({.short_name = "cc", .level_hpa = hpa, .value = cover_at(hpa)});
  write_grib(file, fields);
  const GribCover c = read_grib_cover(file, kLat, kLon, std::nullopt, kRadiusM);
  ASSERT_EQ(c.profile.size(), 10u);
  EXPECT_NEAR(c.profile.front().first, 111.0f, 2.0f);  // 1000 hPa in the standard atmosphere
  EXPECT_NEAR(c.profile[3].first, 1457.0f, 3.0f);      // 850 hPa
  const WeatherState s = weather_from_grib(c, WeatherState{}, 100.0f);
  // The deck spans 900-850 hPa (988-1457 m) and half-way to 950 and 800 (540, 1949 m): its
  // clouds, in the shell set for a stratocumulus, 440-1849 m above the 100 m ground.
  const glm::vec2 clouds_m(0.5f * (540.0f + 988.0f) - 100.0f, 0.5f * (1457.0f + 1949.0f) - 100.0f);
  const float sc = genus_type(Genus::Stratocumulus), ac = genus_type(Genus::Altocumulus);
  const glm::vec2 shell =
      cloud_shell_m(sc, coverage_for_oktas(s.low.coverage_oktas, sc), clouds_m.x, clouds_m.y);
  // The shells overlap (a stratocumulus deck fills the lowest third of its shell): they meet
  // half way between the deck's tops and the altocumulus' bases.
  const glm::vec2 high_clouds_m(0.5f * (4206 + 5574) - 100.0f, 0.5f * (5574 + 7185) - 100.0f);
  const float meet_m = 0.5f * (clouds_m.y + high_clouds_m.x);
  EXPECT_NEAR(s.low.base_m, shell.x, 40.0f);
  EXPECT_NEAR(s.low.top_m, std::min(shell.y, meet_m), 40.0f);
  // The altocumulus at 500 hPa (5574 m), half-way to 600 and 400 hPa.
  EXPECT_EQ(s.high.genus, Genus::Altocumulus);
  EXPECT_NEAR(s.high.coverage_oktas, 3.2f, 0.02f);
  const glm::vec2 high = cloud_shell_m(ac, coverage_for_oktas(s.high.coverage_oktas, ac),
                                       high_clouds_m.x, high_clouds_m.y);
  EXPECT_NEAR(s.high.base_m, std::max(high.x, meet_m), 60.0f);
  EXPECT_NEAR(s.high.top_m, high.y, 60.0f);
}

TEST_F(Grib, AGlobalGridGoesRoundTheEarth) {
  const std::string file = path("global.grib2");
  // 0 to 359 deg east: an observer at 359.8 (or -0.2) lies between the last column and the first.
  test::GribGrid global{
      .north_deg = 60, .south_deg = 40, .west_deg = 0, .east_deg = 359, .step_deg = 1};
  write_grib(file, {{.short_name = "lcc", .grid = global, .value = [](double, double lon) {
                       return lon < 0.5 ? 0.8 : lon > 358.5 ? 0.4 : 0.0;
                     }}});
  for (double lon : {359.8, -0.2}) {
    const GribCover c = read_grib_cover(file, 50.0, lon, std::nullopt, kRadiusM);
    EXPECT_NEAR(c.at_observer[kLowCover], 0.8 * 0.8 + 0.4 * 0.2, 2e-3) << lon;
  }
}

TEST_F(Grib, FilesThatCannotServeAreRefusedInOneLine) {
  // Not on the grid.
  const std::string file = path("europe.grib2");
  write_grib(file, {{.short_name = "lcc"}});
  const std::string away = refusal(file, 40.7, -74.0);
  EXPECT_NE(away.find("does not cover the observer at latitude 40.7000, longitude -74.0000"),
            std::string::npos)
      << away;
  EXPECT_NE(away.find("latitudes 30.00 to 60.00"), std::string::npos) << away;
  // No cloud cover.
  const std::string temperature = path("t.grib2");
  write_grib(temperature, {{.short_name = "t"}, {.short_name = "2t"}});
  const std::string none = refusal(temperature);
  EXPECT_NE(none.find("no cloud cover field"), std::string::npos) << none;
  EXPECT_NE(none.find("2 messages (they hold 2t, t)"), std::string::npos) << none;
  // Not GRIB, or not there.
  const std::string text = path("notes.grib2");
  std::ofstream(text) << "METAR EDDF 271150Z 24015KT 9999 FEW025 12/06 Q1008\n";
  EXPECT_NE(refusal(text).find("holds no GRIB message"), std::string::npos) << refusal(text);
  EXPECT_NE(refusal(path("missing.grib2")).find("cannot be read"), std::string::npos);
  // A device or a folder is not read (ecCodes would read /dev/zero for ever).
  EXPECT_NE(refusal("/dev/zero").find("is not a regular file"), std::string::npos)
      << refusal("/dev/zero");
  EXPECT_NE(refusal(dir_.string()).find("is not a regular file"), std::string::npos);
  // Each a single line naming the file's key.
  for (const std::string& why : {away, none, refusal(text)}) {
    EXPECT_EQ(why.find('\n'), std::string::npos) << why;
    EXPECT_EQ(why.rfind("weather.grib '", 0), 0u) << why;
  }
}

TEST_F(Grib, ASceneFileTakesItsLayersAndTimeFromTheForecast) {
  const std::string file = path("forecast.grib2");
  write_grib(file, {{.short_name = "lcc", .value = [](double, double) { return 0.5; }},
                    {.short_name = "hcc", .value = [](double, double) { return 0.9; }}});
  const std::string scene_path = path("scene.toml");
  std::ofstream(scene_path) << "[location]\nlat_deg = 50.03\nlon_deg = 8.57\n"
                               "[weather]\ngrib = \"forecast.grib2\"\n";
  const Scene scene = load_scene_file(scene_path);
  EXPECT_EQ(scene.weather.grib, file);  // relative to the scene's folder
  EXPECT_EQ(scene.time, "2026-12-03T12:00:00Z");
  EXPECT_NEAR(oktas_for_coverage(scene.clouds.coverage, scene.clouds.type), 4.0f, 0.05f);
  EXPECT_EQ(scene.cirrus.type, 0.5f);  // 7.2 oktas: a cirrostratus veil
  EXPECT_NEAR(oktas_for_sheet_coverage(scene.cirrus.coverage, scene.cirrus.type), 7.2f, 0.01f);
  // The texels scale each layer to the forecast's own: 1 where it is greatest.
  const auto texels = forecast_texels(*grib_cover(scene), scene);
  EXPECT_EQ(texels[texels.size() / 2][0], 255);
  EXPECT_EQ(texels[texels.size() / 2][2], 255);
  // Off the grid: refused naming the key, and where.
  std::ofstream(scene_path) << "[location]\nlat_deg = -33.9\nlon_deg = 151.2\n"
                               "[weather]\ngrib = \"forecast.grib2\"\n";
  try {
    load_scene_file(scene_path);
    ADD_FAILURE() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("weather.grib"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not cover the observer"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace nephele::weather

// A GRIB forecast's cover as the renderer draws it (weather/grib.h, the weather module's
// forecast_cover): the sky cover an observer measures follows the forecast where the observer
// stands, and the forecast's field stays on the ground while the wind moves the clouds.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include "nephele/renderer.h"
#include "render_fixture.h"
#include "support/grib_files.h"
#include "weather/grib.h"

namespace {

namespace fs = std::filesystem;
using nephele::Scene;
using nephele::test::GribField;
using nephele::test::GribGrid;

constexpr double kLat = 50.03, kLon = 8.57;
// 1 deg of longitude at kLat on the default planet (6360 km).
const double kLonDegM =
    6360e3 * std::cos(kLat * 3.14159265358979 / 180.0) * 3.14159265358979 / 180.0;

class GribRender : public RenderTest {
 protected:
  void SetUp() override {
    file_ = (fs::temp_directory_path() /
             ("nephele_grib_render_" +
              std::to_string(::testing::UnitTest::GetInstance()->random_seed()) + ".grib2"))
                .string();
  }
  void TearDown() override { fs::remove(file_); }

  // Low cover `value` around Frankfurt at noon.
  Scene forecast_scene(std::function<double(double, double)> value) {
    const GribGrid grid{
        .north_deg = 56, .south_deg = 44, .west_deg = 0, .east_deg = 18, .step_deg = 0.25};
    nephele::test::write_grib(file_,
                              {{.short_name = "lcc", .grid = grid, .value = std::move(value)}});
    Scene s;
    s.location.lat_deg = float(kLat);
    s.location.lon_deg = float(kLon);
    s.time = "2026-12-03T12:00:00Z";
    s.sun.from_time = true;
    s.weather.grib = file_;
    nephele::weather::apply_grib(s);
    s.output.width = 48;
    s.output.height = 32;
    return s;
  }

  static int oktas(const Scene& s) {
    const nephele::Frame f = render(s);
    EXPECT_TRUE(f.stats.sky_cover_fraction.has_value());
    return nephele::sky_cover_oktas(f.stats.sky_cover_fraction.value_or(-1.0));
  }

  std::string file_;
};

// A forecast of 4 oktas everywhere reads 3 to 5 (SCT); 8 oktas a closed deck.
TEST_F(GribRender, TheSkyCoverIsTheForecasts) {
  const int scattered = oktas(forecast_scene([](double, double) { return 0.5; }));
  EXPECT_GE(scattered, 3);
  EXPECT_LE(scattered, 5);
  EXPECT_EQ(oktas(forecast_scene([](double, double) { return 1.0; })), 8);
}

// Overcast east of a line 30 km east of the observer, clear west of it. The layer's coverage is
// the overcast's; the map takes it away where the forecast is clear. An hour of a 20 m/s wind
// (72 km) moves the clouds, not the line: 80 km west the sky stays clear, 100 km east overcast.
// There the camera, 2 m up in the observer's plane, is 790 m above the curved ground, under a
// deck whose clouds begin at 1 km: the clear sky 70 km west shows under the deck's edge in the
// lowest degree of the western sky (1-2% of the dome: 7 oktas, a gap left).
TEST_F(GribRender, TheForecastStaysOnTheGroundAsTheWindBlows) {
  const double line_lon = kLon + 30e3 / kLonDegM;
  Scene s = forecast_scene([line_lon](double, double lon) { return lon > line_lon ? 1.0 : 0.0; });
  EXPECT_FLOAT_EQ(s.clouds.coverage, 1.0f);
  s.clouds.wind_mps = {20.0f, 0.0f};
  for (float time_s : {0.0f, 3600.0f}) {
    s.time_s = time_s;
    s.camera.position_m = {-80e3f, 0.0f, 2.0f};
    EXPECT_LE(oktas(s), 1) << "west at " << time_s << " s";
    s.camera.position_m = {100e3f, 0.0f, 2.0f};
    EXPECT_GE(oktas(s), 7) << "east at " << time_s << " s";
  }
  // Without the forecast's map the same layer covers the west too.
  s.weather.grib.clear();
  s.camera.position_m = {-80e3f, 0.0f, 2.0f};
  EXPECT_EQ(oktas(s), 8);
}

}  // namespace

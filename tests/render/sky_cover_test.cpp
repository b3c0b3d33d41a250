// Cloud cover as an observer reports it: sky_cover_fraction over the whole dome above the
// observer, and the okta presets (apps/cli/gallery.h) landing in their ranges.
#include <gtest/gtest.h>

#include "gallery.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

using nephele::Scene;

namespace {

// A small image: the dome is measured at its own resolution whatever the image's.
double sky_cover(Scene s) {
  s.output.width = 48;
  s.output.height = 32;
  const nephele::Frame f = render(s);
  EXPECT_TRUE(f.stats.sky_cover_fraction.has_value());
  return f.stats.sky_cover_fraction.value_or(-1.0);
}

class SkyCoverTest : public RenderTest {};

}  // namespace

TEST(SkyCover, OktasFollowWmoCode2700) {
  EXPECT_EQ(nephele::sky_cover_oktas(0.0), 0);
  EXPECT_EQ(nephele::sky_cover_oktas(0.02), 1);  // a trace of cloud is 1 okta, not 0
  EXPECT_EQ(nephele::sky_cover_oktas(0.30), 2);
  EXPECT_EQ(nephele::sky_cover_oktas(0.50), 4);
  EXPECT_EQ(nephele::sky_cover_oktas(0.97), 7);  // a gap left is 7 oktas, not 8
  EXPECT_EQ(nephele::sky_cover_oktas(1.0), 8);
}

// The dome is the observer's, not the camera's: turning the camera changes nothing; more
// coverage covers more of it.
TEST_F(SkyCoverTest, TheDomeDoesNotDependOnTheView) {
  Scene s = nephele::load_preset("scattered");
  const double ahead = sky_cover(s);
  s.camera.view_dir = {-0.5f, -0.8f, 0.1f};
  EXPECT_DOUBLE_EQ(sky_cover(s), ahead);
  s.clouds.coverage += 0.1f;
  EXPECT_GT(sky_cover(s), ahead + 0.1);
}

// Above the cloud layer the sky above is clear, however cloudy below.
TEST_F(SkyCoverTest, AboveTheCloudsTheSkyIsClear) {
  Scene s = nephele::load_preset("overcast");
  s.camera.position_m.z = s.clouds.top_altitude_m + 500.0f;
  EXPECT_EQ(sky_cover(s), 0.0);
}

class PresetOktas : public RenderTest, public ::testing::WithParamInterface<std::string> {};

TEST_P(PresetOktas, SkyCoverLiesInThePresetsOktaRange) {
  const nephele::cli::OktaRange range = nephele::cli::gallery_okta_range(GetParam());
  const double cover = sky_cover(nephele::load_preset(GetParam()));
  const int oktas = nephele::sky_cover_oktas(cover);
  std::printf("%s: sky cover %.3f, %d oktas (range %d-%d)\n", GetParam().c_str(), cover, oktas,
              range.lo, range.hi);
  EXPECT_GE(oktas, range.lo) << "sky cover " << cover;
  EXPECT_LE(oktas, range.hi) << "sky cover " << cover;
}

INSTANTIATE_TEST_SUITE_P(Gallery, PresetOktas,
                         ::testing::ValuesIn(nephele::cli::gallery_presets()),
                         [](const auto& info) {
                           std::string name = info.param;
                           for (char& c : name)
                             if (c == '-') c = '_';
                           return name;
                         });

// The time-of-day keyframes (nephele/conditions.h) in scenes and in the renderer: their tables
// in TOML, the artist mode's sky, the weather blend and the stars' visibility.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nephele/exposure.h"
#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

using nephele::ConditionsMode;
using nephele::Scene;

namespace {

Scene parse(const std::string& text) { return nephele::parse_scene_toml(text, "test.toml"); }

// A cloudless view of the zenith in artist mode at `hour`.
Scene artist_zenith(float hour, float weather) {
  Scene s;
  s.clouds.coverage = 0.0f;
  s.output.width = s.output.height = 16;
  s.camera.view_dir = {0.0f, 0.01f, 1.0f};
  s.conditions.mode = ConditionsMode::Artist;
  s.conditions.hour = hour;
  s.conditions.weather = weather;
  return s;
}

}  // namespace

TEST(ConditionsScene, KeyframeTablesReadAndRoundTrip) {
  const Scene s = parse(
      "[conditions]\nmode = \"overlay\"\nweather = 0.25\nhour = 6.5\n"
      "[conditions.good.evening]\nhour = 19.5\nsky_zenith_rgb = [0.1, 0.2, 0.3]\n"
      "[conditions.bad.night]\nstar_visibility = 0.5\n");
  EXPECT_EQ(s.conditions.mode, ConditionsMode::Overlay);
  EXPECT_EQ(s.conditions.weather, 0.25f);
  EXPECT_EQ(s.conditions.good.keys[6].hour, 19.5f);
  EXPECT_EQ(s.conditions.good.keys[6].set.sky_zenith_rgb, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(s.conditions.bad.keys[0].set.star_visibility, 0.5f);
  // Untouched keys keep their defaults.
  EXPECT_EQ(s.conditions.good.keys[4].set.sky_zenith_rgb,
            nephele::default_good_weather().keys[4].set.sky_zenith_rgb);
  const Scene again = parse(nephele::scene_to_toml(s));
  EXPECT_EQ(again.conditions.good.keys[6].set.sky_zenith_rgb, glm::vec3(0.1f, 0.2f, 0.3f));
  EXPECT_EQ(again.conditions.bad.keys[0].set.star_visibility, 0.5f);
  EXPECT_EQ(again.conditions.hour, 6.5f);
}

TEST(ConditionsScene, BadKeyframesAreRejectedByName) {
  const auto message = [](const std::string& text) {
    try {
      nephele::validate_scene(parse(text));
    } catch (const nephele::InputError& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message("[conditions.good.evening]\nhour = 16\n").find("conditions.good.evening.hour"),
            std::string::npos);
  EXPECT_NE(message("[conditions.good.evenin]\nhour = 16\n").find("conditions.good.evenin"),
            std::string::npos);
  EXPECT_NE(message("[conditions]\nmode = \"artist\"\n").find("conditions.hour"), std::string::npos);
  EXPECT_NE(message("[conditions]\nweather = 2\n").find("conditions.weather"), std::string::npos);
  EXPECT_EQ(message("[conditions]\nmode = \"artist\"\nhour = 13\n"), "accepted");
}

class ConditionsRenderTest : public RenderTest {};

// Artist mode at a key hour: the zenith is that key's sky colour, in good and in bad weather.
TEST_F(ConditionsRenderTest, ArtistSkyIsTheKeyframesSky) {
  for (float weather : {1.0f, 0.0f}) {
    const Scene s = artist_zenith(13.0f, weather);  // the "day" key
    const glm::vec3 expected = (weather == 1.0f ? nephele::default_good_weather()
                                                : nephele::default_bad_weather())
                                   .keys[4]
                                   .set.sky_zenith_rgb *
                                   nephele::kLegacyLuxPerUnit;  // the old scale, in cd/m^2
    const glm::vec4 got = render(s).color.at(8, 8);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], 0.02f * expected[c]) << weather;
  }
  // Halfway between day (13 h) and early evening (17 h) the colour is halfway too.
  const glm::vec3 day =
      nephele::default_good_weather().keys[4].set.sky_zenith_rgb * nephele::kLegacyLuxPerUnit;
  const glm::vec3 early_evening =
      nephele::default_good_weather().keys[5].set.sky_zenith_rgb * nephele::kLegacyLuxPerUnit;
  const glm::vec4 got = render(artist_zenith(15.0f, 1.0f)).color.at(8, 8);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(got[c], 0.5f * (day[c] + early_evening[c]), 0.02f * day[c]);
}

// Overlay mode: the physical night sky with the keyframes' star visibility on the stars.
TEST_F(ConditionsRenderTest, StarVisibilityScalesTheStars) {
  const Scene s = starry_night(120, 80);
  const auto stars = [&](float visibility) {
    Scene v = s;
    v.conditions.good.keys[0].set.star_visibility = visibility;
    return render(v).color;
  };
  const nephele::Image none = stars(0.0f), half = stars(0.5f), all = stars(1.0f);
  const double excess_half = luminance_excess(half, none), excess_all = luminance_excess(all, none);
  ASSERT_GT(excess_all, 0.0) << "no stars in view";
  EXPECT_NEAR(excess_half / excess_all, 0.5, 0.02);
}

// A sequence through sunset and dusk at a real place has no jumps: frames 10 minutes apart
// (Paris, midsummer, 19:00 to 21:20 UTC; sunset about 19:58) darken smoothly, the step in log
// mean luminance never more than twice the largest of its neighbours' and under 1.75 (5.8x;
// measured at most 1.14, in nautical twilight). With only the key light lighting the sky, the
// sun-to-moon hand-over (21:10 -> 21:20) was 330x darker.
TEST_F(ConditionsRenderTest, SunsetSequenceHasNoJumps) {
  Scene s;
  s.output.width = 32;
  s.output.height = 20;
  s.time = "2026-06-21T19:00:00Z";
  s.sun.from_time = true;
  s.location = {48.85f, 2.35f, 0.0f};
  s.camera.view_dir = {-0.5f, 1.0f, 0.3f};
  // The clouds held still: only the light changes (a drifting, evolving sky changed which
  // clouds the small view holds, by up to 1.6x in 10 minutes).
  s.clouds.wind_mps = {0.0f, 0.0f};
  s.clouds.wind_shear_mps = {0.0f, 0.0f};
  s.clouds.detail_drift_mps = {0.0f, 0.0f, 0.0f};
  s.clouds.weather_evolution_s = 0.0f;
  // Light rays marched at each sample: the light volume (1.3 s a still on lavapipe, rebuilt
  // for every frame as the sun moves) costs far more than the march over 32 x 20 pixels.
  s.quality.light_volume_km = 0;
  std::vector<double> log_l;
  for (int i = 0; i < 15; ++i) {
    s.time_s = 600.0f * float(i);
    log_l.push_back(std::log(render(s).stats.mean_luminance));
    std::printf("%s +%4.0f min: mean luminance %.3g\n", s.time.c_str(), s.time_s / 60.0f,
                std::exp(log_l.back()));
  }
  for (size_t i = 1; i < log_l.size(); ++i) {
    const double step = std::abs(log_l[i] - log_l[i - 1]);
    EXPECT_LT(step, 1.75) << "frame " << i;
    double neighbours = 0.0;
    if (i >= 2) neighbours = std::max(neighbours, std::abs(log_l[i - 1] - log_l[i - 2]));
    if (i + 1 < log_l.size()) neighbours = std::max(neighbours, std::abs(log_l[i + 1] - log_l[i]));
    EXPECT_LT(step, 2.0 * neighbours + 0.05) << "frame " << i;
  }
}

// The ground fog module (render/modules/ground_fog) on the device: a medium in front of every
// layer of compose. Its physics (Koschmieder, the profile, the closed-form optical depths) is
// tested on the CPU in tests/unit/ground_fog_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "nephele/conditions.h"
#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele/image_compare.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render/render_module.h"
#include "render_fixture.h"

using nephele::Scene;

namespace {

Scene small_default() {
  Scene s = nephele::load_preset("default");
  s.output.width = 64;
  s.output.height = 48;
  return s;
}

class GroundFogTest : public RenderTest {};

// Above a fog sea: the sky above the horizon is untouched (the rays never enter the fog), the
// ground below is hidden under the fog's own light, brighter than the dark ground and even.
TEST_F(GroundFogTest, FromAboveItHidesTheGroundAndLeavesTheSky) {
  Scene clear = small_default();
  clear.camera.position_m.z = 800.0f;
  clear.camera.view_dir = glm::vec3(0.0f, 1.0f, -0.35f);
  Scene fog = clear;
  fog.ground_fog.visibility_m = 150.0f;
  fog.ground_fog.top_m = 400.0f;
  const nephele::Image a = render(clear).color;
  const nephele::Image b = render(fog).color;
  int sky = 0, ground = 0;
  double ground_clear = 0.0, ground_fog = 0.0, lo = 1e30, hi = 0.0, clear_lo = 1e30, clear_hi = 0.0;
  for (int y = 0; y < a.height; ++y)
    for (int x = 0; x < a.width; ++x) {
      const float la = nephele::luminance(a.at(x, y)), lb = nephele::luminance(b.at(x, y));
      ASSERT_TRUE(std::isfinite(lb));
      if (y < 4) {  // the top rows: sky
        EXPECT_NEAR(lb, la, 1e-5 * la) << x << ", " << y;
        ++sky;
      }
      if (y >= a.height - 12) {  // the bottom rows: the ground, 1 to 3 km away
        ground_clear += la;
        ground_fog += lb;
        lo = std::min(lo, double(lb));
        hi = std::max(hi, double(lb));
        clear_lo = std::min(clear_lo, double(la));
        clear_hi = std::max(clear_hi, double(la));
        ++ground;
      }
    }
  ASSERT_GT(sky, 0);
  EXPECT_GT(ground_fog, 1.5 * ground_clear) << "the fog's light over the dark ground";
  // Even: only the fog's own light varies (with the angle to the sun and the depth it is seen
  // to), where the clear ground shows the clouds' shadows.
  EXPECT_LT(hi / lo, 1.35);
  EXPECT_GT(clear_hi / clear_lo, 1.5 * (hi / lo)) << "the fog hides the clouds' shadows";
}

// A fog sea under broken clouds shows their shadows: where the clear ground is sunlit, the fog
// above it is brighter than where the ground is shadowed (the ground's shadow stands for the
// fog's). Lit only by the clouds' mean transmittance it was even (ratio 1.0).
TEST_F(GroundFogTest, AFogSeaShowsTheCloudsShadows) {
  Scene clear = nephele::load_preset("broken");
  clear.output.width = 64;
  clear.output.height = 48;
  clear.camera.position_m.z = 700.0f;
  clear.camera.view_dir = glm::vec3(0.0f, 1.0f, -0.25f);
  Scene fog = clear;
  fog.ground_fog.visibility_m = 200.0f;
  fog.ground_fog.top_m = 400.0f;
  const nephele::Image a = render(clear).color, b = render(fog).color;
  // Row by row (one distance each), each pixel against its row's mean: the clear ground sunlit
  // (above 1.2) or shadowed (below 0.8), and the fog above it. Nearer, under the clouds, the
  // ground is all in their shadow.
  double lit = 0.0, shaded = 0.0;
  int n_lit = 0, n_shaded = 0;
  for (int y = a.height * 35 / 100; y < a.height * 55 / 100; ++y) {  // the ground 3 to 8 km away
    double mean_a = 0.0, mean_b = 0.0;
    for (int x = 0; x < a.width; ++x) {
      mean_a += nephele::luminance(a.at(x, y)) / a.width;
      mean_b += nephele::luminance(b.at(x, y)) / a.width;
    }
    for (int x = 0; x < a.width; ++x) {
      const double ground = nephele::luminance(a.at(x, y)) / mean_a;
      const double over = nephele::luminance(b.at(x, y)) / mean_b;
      if (ground > 1.2) {
        lit += over;
        ++n_lit;
      } else if (ground < 0.8) {
        shaded += over;
        ++n_shaded;
      }
    }
  }
  ASSERT_GT(n_lit, 20) << "sunlit ground in view";
  ASSERT_GT(n_shaded, 20);
  EXPECT_GT((lit / n_lit) / (shaded / n_shaded), 1.2);
}

// Inside a dense fog the view above the horizon is nearly even (the sky and the clouds fade
// within a few hundred metres), lit: neither dark nor brighter than the sunlit clouds.
TEST_F(GroundFogTest, InsideADenseFogTheViewIsEvenAndLit) {
  Scene clear = small_default();
  Scene fog = clear;
  fog.ground_fog.visibility_m = 60.0f;
  fog.ground_fog.top_m = 300.0f;
  const nephele::Image a = render(clear).color;
  const nephele::Image b = render(fog).color;
  double lo = 1e30, hi = 0.0, clear_hi = 0.0, clear_lo = 1e30;
  for (size_t i = 0; i < b.pixels.size() / 3; ++i) {  // the top third: above the horizon
    const double l = nephele::luminance(b.pixels[i]), c = nephele::luminance(a.pixels[i]);
    lo = std::min(lo, l);
    hi = std::max(hi, l);
    clear_lo = std::min(clear_lo, c);
    clear_hi = std::max(clear_hi, c);
  }
  EXPECT_GT(clear_hi / clear_lo, 3.0);  // the clear view: blue sky, bright clouds
  EXPECT_LT(hi / lo, 1.3);
  EXPECT_GT(lo, 0.05 * clear_hi);
  EXPECT_LT(hi, clear_hi);
}

// Under a dense fog the ground gets the sun's and the sky's light through it: looking down from
// 1 m (through a metre of fog) the ground is about half as bright as in the clear, the fog above
// having scattered its direct light (diffusely, mostly on: a forward-scattering slab of optical
// depth 8 lets through about half).
TEST_F(GroundFogTest, UnderADenseFogTheGroundGetsLessLight) {
  Scene clear = small_default();
  clear.clouds.coverage = 0.0f;
  clear.camera.position_m.z = 1.0f;
  clear.camera.view_dir = glm::vec3(0.0f, 0.05f, -1.0f);
  clear.camera.fov_deg = 20.0f;
  Scene fog = clear;
  fog.ground_fog.visibility_m = 100.0f;  // sigma_t 0.039 / m: 0.04 between the eye and the ground
  fog.ground_fog.top_m = 200.0f;         // 7.8 above it
  const nephele::Image a = render(clear).color, b = render(fog).color;
  double lit_clear = 0.0, lit_fog = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    lit_clear += nephele::luminance(a.pixels[i]);
    lit_fog += nephele::luminance(b.pixels[i]);
  }
  EXPECT_GT(lit_fog / lit_clear, 0.3);
  EXPECT_LT(lit_fog / lit_clear, 0.75);
}

// The stars are behind the fog: inside a dense fog at night they are gone (stars.comp applies
// the media's transmittance towards the sky), while the same night without fog shows them.
TEST_F(GroundFogTest, InsideADenseFogTheStarsAreHidden) {
  const Scene s = starry_night(96, 64);
  // The stars' light: the image less the same image with the stars' visibility 0.
  const auto stars = [&](float visibility_m) {
    Scene with = s;
    with.ground_fog.visibility_m = visibility_m;
    Scene without = with;
    without.conditions.good.keys[0].set.star_visibility = 0.0f;
    return luminance_excess(render(with).color, render(without).color);
  };
  const double clear = stars(0.0f);
  ASSERT_GT(clear, 0.0) << "no stars in view";
  // 100 m visibility, 150 m of fog above the eye: an optical depth of 6 straight up.
  EXPECT_LT(stars(100.0f), 0.01 * clear);
}

// The time-of-day keyframes' fog by distance is the ground fog's medium: the ground beyond the
// keyframes' far distance is their fog colour; nearer, the colour is mixed in linearly with
// distance, as the seed does.
TEST_F(GroundFogTest, TheKeyframesFogIsAMedium) {
  Scene s;
  s.clouds.coverage = 0.0f;
  s.output.width = 32;
  s.output.height = 24;
  s.camera.position_m.z = 500.0f;
  s.camera.view_dir = {0.0f, 1.0f, -1.0f};  // the ground 700 m to 1.5 km away
  s.conditions.mode = nephele::ConditionsMode::Artist;
  s.conditions.hour = 13.0f;
  const glm::vec3 fog_rgb{0.2f, 0.3f, 0.4f};
  const auto with_fog = [&](float near_m, float far_m) {
    Scene v = s;
    for (auto* table : {&v.conditions.good, &v.conditions.bad})
      for (auto& key : table->keys) {
        key.set.fog_rgb = fog_rgb;
        key.set.fog_near_m = near_m;
        key.set.fog_far_m = far_m;
      }
    return render(v).color;
  };
  const nephele::Image whole = with_fog(0.0f, 1.0f), none = with_fog(1e6f, 2e6f);
  // Linear in distance: with the far distance at 4 and at 8 km (the ground nearer), the share of
  // fog mixed in halves, the same in every channel.
  const nephele::Image ramp4 = with_fog(0.0f, 4000.0f), ramp8 = with_fog(0.0f, 8000.0f);
  const glm::vec3 expected = fog_rgb * nephele::kLegacyLuxPerUnit;
  const glm::vec4 far = whole.at(16, 20), clear = none.at(16, 20);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(far[c], expected[c], 1e-3f * expected[c]) << c;
    ASSERT_GT(std::abs(clear[c] - expected[c]), 0.1f * expected[c]) << "the ground differs";
    const float share4 = (clear[c] - ramp4.at(16, 20)[c]) / (clear[c] - expected[c]);
    const float share8 = (clear[c] - ramp8.at(16, 20)[c]) / (clear[c] - expected[c]);
    EXPECT_GT(share4, 0.1f) << c;
    EXPECT_LT(share4, 0.5f) << c;
    EXPECT_NEAR(share4, 2.0f * share8, 0.01f * share4) << c;
  }
}

// The frame knows the fog only through the registry generated from the modules' folders
// (cmake/module_registry.cmake): src/render/modules/ground_fog/ground_fog.h is listed.
TEST(GroundFogScene, TheModuleIsRegisteredFromItsFolder) {
  const auto& modules = nephele::registered_modules();
  const auto it = std::find_if(modules.begin(), modules.end(),
                               [](const auto& m) { return std::string(m.name) == "ground_fog"; });
  ASSERT_NE(it, modules.end());
  EXPECT_NE(it->make, nullptr);
}

// The fog is reachable from its field table alone: the keys read from TOML.
TEST(GroundFogScene, TheKeysReadFromAScene) {
  const Scene s = nephele::parse_scene_toml(
      "[ground_fog]\nvisibility_m = 250.0\nbase_m = 20.0\ntop_m = 180.0\nsoftness_m = 30.0\n",
      "fog.toml");
  EXPECT_EQ(s.ground_fog.visibility_m, 250.0f);
  EXPECT_EQ(s.ground_fog.base_m, 20.0f);
  EXPECT_EQ(s.ground_fog.top_m, 180.0f);
  EXPECT_EQ(s.ground_fog.softness_m, 30.0f);
  // Ranges are validation's: a visibility under 1 m (other than 0, no fog) is refused.
  Scene bad = s;
  bad.ground_fog.visibility_m = 0.5f;
  EXPECT_THROW(nephele::validate_scene(bad), nephele::InputError);
}

}  // namespace

// The ground fog module (render/modules/ground_fog) on the device: a medium in front of every
// layer of compose. Its physics (Koschmieder, the profile, the closed-form optical depths) is
// tested on the CPU in tests/unit/ground_fog_test.cpp.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "nephele/error.h"
#include "nephele/image_compare.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
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

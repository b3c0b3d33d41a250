// Volumetric light shafts (shaders/light_shafts_inc.glsl): the air's single scattering lost to
// the clouds' shadows, as a share of the air's whole light. They never add light to the sky
// model's, change nothing under a clear sky, and draw beams (a loss that varies from one direction
// to the next by much of itself) below broken clouds; a closed deck darkens the air below it about
// evenly.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/glm.hpp>

#include "nephele/scene_io.h"
#include "render_fixture.h"

namespace nephele {
namespace {

class LightShaftsTest : public RenderTest {};

// From the ground towards a sun 12 deg high, in hazy air, the clouds' layer low.
Scene shaft_scene(float coverage) {
  Scene s = load_preset("default");
  s.output.width = 64;
  s.output.height = 40;
  s.output.auto_exposure = false;
  s.quality.cloud_downsample = 1;
  s.sun.direction = glm::normalize(glm::vec3(0.0f, 0.98f, 0.21f));
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, 0.12f);
  s.camera.fov_deg = 40.0f;
  s.atmosphere.mie_extinction_per_m *= 4.0f;
  s.atmosphere.mie_scattering_per_m *= 4.0f;
  s.clouds.bottom_altitude_m = 800.0f;
  s.clouds.top_altitude_m = 2000.0f;
  s.clouds.coverage = coverage;
  return s;
}

struct Loss {
  double mean = 0.0;        // the share of the light lost, over the lower half of the sky
  double beams = 0.0;       // its mean change from one pixel to the next along a row there
  double most_added = 0.0;  // the largest gain of any pixel, relative
};

// The light the shafts take from each pixel's luminance, relative to the pixel's.
Loss shaft_loss(float coverage) {
  Scene s = shaft_scene(coverage);
  s.quality.light_shafts = "off";
  const Frame off = render(s);
  s.quality.light_shafts = "volumetric";
  const Frame on = render(s);
  Loss loss;
  int n = 0, pairs = 0;
  const auto lost = [&](int x, int y) {
    const size_t i = size_t(y * s.output.width + x);
    const double a = luminance(off.color.pixels[i]), b = luminance(on.color.pixels[i]);
    return (a - b) / std::max(a, 1e-9);
  };
  for (size_t i = 0; i < on.color.pixels.size(); ++i) {
    const double a = luminance(off.color.pixels[i]), b = luminance(on.color.pixels[i]);
    loss.most_added = std::max(loss.most_added, (b - a) / std::max(a, 1e-9));
  }
  for (int y = s.output.height / 4; y < s.output.height / 2; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      loss.mean += lost(x, y);
      ++n;
      if (x == 0) continue;
      loss.beams += std::abs(lost(x, y) - lost(x - 1, y));
      ++pairs;
    }
  loss.mean /= double(n);
  loss.beams /= double(pairs);
  std::printf("coverage %.2f: the air's light lost %.4f on average, changing by %.4f from pixel "
              "to pixel along a row; most added %.2e\n", coverage, loss.mean, loss.beams, loss.most_added);
  return loss;
}

TEST_F(LightShaftsTest, BeamsOnlyBelowBrokenCloudsAndNeverAddedLight) {
  const Loss clear = shaft_loss(0.0f), broken = shaft_loss(0.5f), deck = shaft_loss(1.0f);
  for (const Loss& l : {clear, broken, deck}) EXPECT_LT(l.most_added, 1e-4);
  EXPECT_LT(clear.mean, 1e-5);
  EXPECT_LT(clear.beams, 1e-5);
  // Broken clouds: beams, the loss changing along a row by a larger share of itself than
  // under a deck (0.14 against 0.027 measured), which darkens the air below it about evenly.
  EXPECT_GT(broken.mean, 0.002);
  EXPECT_GT(broken.beams / broken.mean, 3.0 * deck.beams / deck.mean);
  // The deck shadows more of the air than broken clouds do, but only the sun's single
  // scattering: the air's multiple scattering stays (measured 0.48 of the lower sky's light
  // lost; 0.82 when the single scattering's share was taken from the whole light).
  EXPECT_GT(deck.mean, 10.0 * broken.mean);
  EXPECT_GT(deck.mean, 0.3);
  EXPECT_LT(deck.mean, 0.65);
}

}  // namespace
}  // namespace nephele

namespace nephele {
namespace {

// The seed's screen-space god rays: light added about the sun when it is in view (more near it
// than far from it), nothing when it is behind the camera; the image otherwise as without.
TEST_F(LightShaftsTest, ScreenSpaceRaysAddLightAboutTheSunInView) {
  Scene s = shaft_scene(0.4f);
  s.atmosphere = load_preset("default").atmosphere;
  s.quality.light_volume_km = 0;  // the rays read the cloud buffer only; no volume to build
  const auto gain = [&](const Scene& scene) {
    Scene off = scene, on = scene;
    off.quality.light_shafts = "off";
    on.quality.light_shafts = "screen";
    const Frame a = render(off), b = render(on);
    Image out = a.color;
    for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = b.color.pixels[i] - a.color.pixels[i];
    return out;
  };
  const Image in_view = gain(s);
  // The sun's pixel: straight ahead of the camera's direction, projected.
  double near = 0.0, far = 0.0, total = 0.0;
  const int cx = s.output.width / 2;
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      const double g = luminance(in_view.at(x, y));
      EXPECT_GE(g, -1e-3 * std::max(1.0, g));
      total += g;
      if (std::abs(x - cx) < 4 && y < s.output.height / 2) near += g / 4.0;
      if (x < 4) far += g / 4.0;
    }
  std::printf("screen rays: %.4g added in all, near the sun's column %.4g, at the edge %.4g\n", total,
              near, far);
  EXPECT_GT(total, 0.0);
  EXPECT_GT(near, 2.0 * far);
  Scene behind = s;
  behind.camera.view_dir = -s.camera.view_dir;
  behind.camera.view_dir.z = 0.1f;
  const Image none = gain(behind);
  for (const glm::vec4& p : none.pixels) EXPECT_NEAR(luminance(p), 0.0f, 1e-3f);
}

}  // namespace
}  // namespace nephele

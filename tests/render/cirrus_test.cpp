// The cirrus sheet (CirrusParams): behind the volumetric clouds from below, in front of them
// from above, moving with its own wind.
#include <gtest/gtest.h>

#include "nephele/image_compare.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"
#include "render/glsl.h"

using nephele::Frame;
using nephele::Scene;
namespace g = nephele::glsl;

namespace {

Scene cirrus_sky() {
  Scene s = nephele::load_preset("cirrus");
  s.output.width = 96;
  s.output.height = 64;
  return s;
}

double mean_abs_difference(const nephele::Image& a, const nephele::Image& b, bool where_opaque,
                           const Frame& clouds) {
  double sum = 0.0;
  int n = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const bool opaque = clouds.clouds.pixels[i].a < 0.02f;
    if (opaque != where_opaque) continue;
    sum += std::abs(double(nephele::luminance(a.pixels[i]) - nephele::luminance(b.pixels[i])));
    ++n;
  }
  return n ? sum / n : 0.0;
}

class CirrusTest : public RenderTest {};

}  // namespace

TEST(CirrusGenera, WeightsBlendNeighboursAndSumToOne) {
  EXPECT_EQ(g::cirrus_genus_weights(0.0f), glm::vec3(1, 0, 0));
  EXPECT_EQ(g::cirrus_genus_weights(0.5f), glm::vec3(0, 1, 0));
  EXPECT_EQ(g::cirrus_genus_weights(1.0f), glm::vec3(0, 0, 1));
  for (float t = 0.0f; t <= 1.0f; t += 0.05f) {
    const glm::vec3 w = g::cirrus_genus_weights(t);
    EXPECT_NEAR(w.x + w.y + w.z, 1.0f, 1e-6f) << t;
  }
  // Overhead a sheet of optical depth 0.3 lets 74% through; at 60 deg from the zenith, 55%.
  EXPECT_NEAR(g::cirrus_transmittance(0.3f, 1.0f), std::exp(-0.3f), 1e-6f);
  EXPECT_NEAR(g::cirrus_transmittance(0.3f, -0.5f), std::exp(-0.6f), 1e-6f);
}

// From the ground the sheet shows in the clear sky and not through thick cloud.
TEST_F(CirrusTest, FromBelowItIsBehindTheClouds) {
  Scene s = cirrus_sky();
  s.clouds.coverage = 0.5f;
  Scene bare = s;
  bare.cirrus.coverage = 0.0f;
  const Frame with = render(s), without = render(bare);
  const double in_clear_sky = mean_abs_difference(with.color, without.color, false, without);
  const double through_cloud = mean_abs_difference(with.color, without.color, true, without);
  EXPECT_GT(in_clear_sky, 0.01 * nephele::luminance(without.color.pixels[0]) + 1e-4);
  EXPECT_LT(through_cloud, 0.05 * in_clear_sky);
}

// From above (an airliner at 11 km) it lies over everything below, thick cloud included.
TEST_F(CirrusTest, FromAboveItIsInFront) {
  Scene s = cirrus_sky();
  s.clouds.coverage = 0.6f;
  s.cirrus.altitude_m = 7000.0f;
  s.cirrus.coverage = 0.8f;
  s.camera.position_m.z = 11000.0f;
  s.camera.view_dir = {0.17f, 0.96f, -0.5f};
  Scene bare = s;
  bare.cirrus.coverage = 0.0f;
  const Frame with = render(s), without = render(bare);
  EXPECT_GT(mean_abs_difference(with.color, without.color, true, without), 0.005);
}

// The sheet drifts with its own wind: with the clouds' wind still, only the cirrus moves.
TEST_F(CirrusTest, ItMovesWithItsOwnWind) {
  Scene s = cirrus_sky();
  s.clouds.coverage = 0.0f;
  s.clouds.wind_mps = {0.0f, 0.0f};
  s.clouds.weather_evolution_s = 0.0f;
  const Frame start = render(s);
  s.time_s = 120.0f;
  const Frame later = render(s);
  EXPECT_GT(nephele::luminance_error(later.color, start.color), 0.01);
  // Without the sheet nothing else moved.
  s.cirrus.coverage = 0.0f;
  const Frame bare_later = render(s);
  s.time_s = 0.0f;
  EXPECT_EQ(render(s).color.pixels, bare_later.color.pixels);
}

// Particle clouds drawn (seed 003, 3.3.4; issue 22): the raster pass's layer over the sky, in
// the film layers, and in depth order with the volumetric clouds.
#include <gtest/gtest.h>

#include <cmath>

#include "nephele/scene_io.h"
#include "render_fixture.h"

namespace {

nephele::Scene particle_scene() {
  nephele::Scene s = nephele::load_preset("default");
  s.output.width = 96;
  s.output.height = 64;
  s.clouds.coverage = 0.0f;
  s.particle_clouds.coverage = 0.35f;
  s.particle_clouds.field_radius_m = 6000.0f;
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, 0.6f);
  s.output.auto_exposure = false;
  return s;
}

class ParticleRenderTest : public RenderTest {};

TEST_F(ParticleRenderTest, CloudsOverTheSkyAtTheirDistanceInTheFilmLayers) {
  nephele::Scene s = particle_scene();
  const nephele::FilmLayers layers = shared_renderer().render_layers(s);
  size_t cloudy = 0, clear = 0;
  double worst = 0.0, cloud_blue = 0.0, sky_blue = 0.0;
  for (size_t i = 0; i < layers.clouds.pixels.size(); ++i) {
    const glm::vec4 c = layers.clouds.pixels[i];
    const float a = c.a;
    ASSERT_GE(a, 0.0f);
    ASSERT_LE(a, 1.0f);
    const glm::vec4 image = layers.frame.color.pixels[i];
    for (int k = 0; k < 3; ++k)
      worst = std::max(worst, double(std::abs(image[k] - (c[k] + (1.0f - a) * layers.sky.pixels[i][k]))) /
                                  (std::abs(image[k]) + 1e-3));
    const float depth_m = layers.clouds_depth_m.pixels[i].r;
    if (a > 0.5f) {
      ++cloudy;
      EXPECT_GT(c.g, 0.0f);
      cloud_blue += c.b / std::max(c.r, 1e-9f);
      // From the ground, at least as far as the layer's base (1500 m less a cell) straight up,
      // and within the field (6 km radius, 2.7 km high).
      EXPECT_GT(depth_m, 1350.0f);
      EXPECT_LT(depth_m, 7500.0f);
    }
    if (a < 1e-3f) ++clear, sky_blue += image.b / std::max(image.r, 1e-9f);
  }
  // Whiter than the blue sky between them (lit by the sun as much as by the sky).
  EXPECT_LT(cloud_blue / cloudy, 0.75 * sky_blue / clear);
  std::printf("blue / red: clouds %.2f, sky %.2f\n", cloud_blue / cloudy, sky_blue / clear);
  std::printf("%zu cloudy, %zu clear of %zu pixels; worst over error %.3g\n", cloudy, clear,
              layers.clouds.pixels.size(), worst);
  EXPECT_GT(cloudy, layers.clouds.pixels.size() / 5);  // broken clouds: both, plenty of each
  EXPECT_GT(clear, layers.clouds.pixels.size() / 20);
  EXPECT_LT(worst, 1e-5);
  // Without particle clouds the same sky has no clouds at all.
  s.particle_clouds.coverage = 0.0f;
  const nephele::FilmLayers none = shared_renderer().render_layers(s);
  for (const glm::vec4& c : none.clouds.pixels) ASSERT_LT(c.a, 1e-4f);
}

// The mean relative difference of two images' luminance over the pixels where `mask` holds.
template <typename Mask>
double masked_difference(const nephele::Image& a, const nephele::Image& b, Mask mask, size_t& n) {
  double sum = 0.0;
  n = 0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    if (!mask(i)) continue;
    const double la = nephele::luminance(a.pixels[i]), lb = nephele::luminance(b.pixels[i]);
    sum += std::abs(la - lb) / std::max(lb, 1e-9);
    ++n;
  }
  return n ? sum / double(n) : 0.0;
}

TEST_F(ParticleRenderTest, TheNearerOfParticleAndVolumetricCloudsHidesTheOther) {
  // An overcast volumetric deck at 1500-2500 m, seen from below, with dense particle clouds
  // under it (400-900 m) or above it (4000-4600 m).
  nephele::Scene deck = particle_scene();
  deck.clouds.coverage = 1.0f;
  deck.clouds.type = 0.0f;
  deck.clouds.density = 0.8f;
  deck.clouds.bottom_altitude_m = 1500.0f;
  deck.clouds.top_altitude_m = 2500.0f;
  deck.particle_clouds.coverage = 0.7f;
  deck.particle_clouds.opacity = 0.9f;
  deck.particle_clouds.field_radius_m = 3000.0f;
  deck.camera.view_dir = glm::vec3(0.0f, 0.4f, 1.0f);

  nephele::Scene below = deck;  // particles in front of the deck
  below.particle_clouds.bottom_altitude_m = 400.0f;
  below.particle_clouds.top_altitude_m = 900.0f;
  nephele::Scene below_alone = below;
  below_alone.clouds.coverage = 0.0f;
  const nephele::FilmLayers alone = shared_renderer().render_layers(below_alone);
  const nephele::Frame both = render(below);
  size_t n = 0;
  const double in_front = masked_difference(
      both.color, alone.frame.color, [&](size_t i) { return alone.clouds.pixels[i].a > 0.995f; }, n);
  std::printf("particles in front of the deck: %zu opaque pixels differ by %.2f%%\n", n, 100 * in_front);
  EXPECT_GT(n, 200u);
  EXPECT_LT(in_front, 0.03);
  // ... and where they are thin, the deck shows through them.
  const double see_through = masked_difference(
      both.color, alone.frame.color, [&](size_t i) { return alone.clouds.pixels[i].a < 0.3f; }, n);
  EXPECT_GT(see_through, 0.1);

  nephele::Scene above = deck;  // particles behind the deck
  above.particle_clouds.bottom_altitude_m = 4000.0f;
  above.particle_clouds.top_altitude_m = 4600.0f;
  nephele::Scene deck_alone = above;
  deck_alone.particle_clouds.coverage = 0.0f;
  const nephele::FilmLayers deck_layers = shared_renderer().render_layers(deck_alone);
  const nephele::Frame hidden = render(above);
  const double behind = masked_difference(
      hidden.color, deck_layers.frame.color,
      [&](size_t i) { return deck_layers.clouds.pixels[i].a > 0.995f; }, n);
  std::printf("particles behind the deck: %zu opaque pixels differ by %.2f%%\n", n, 100 * behind);
  EXPECT_GT(n, 200u);
  EXPECT_LT(behind, 0.03);
}

// Drawn off-screen at half or a quarter of the output's resolution and filtered up: a quarter
// or a sixteenth of the fragments, the same clouds, softer (at 160 x 96 the particles are a few
// pixels across, so the blur is large; a misplaced or shifted layer would move the clouds).
TEST_F(ParticleRenderTest, ALowerResolutionLayerShowsTheSameClouds) {
  nephele::Scene s = particle_scene();
  s.output.width = 160;
  s.output.height = 96;
  s.particle_clouds.layer_resolution = 1.0f;
  const nephele::Frame full = render(s);
  ASSERT_TRUE(full.stats.particle_clouds);
  EXPECT_EQ(full.stats.particle_clouds->layer_width, 160);
  EXPECT_EQ(full.stats.particle_clouds->layer_height, 96);
  double previous = 0.0;
  for (const float scale : {0.5f, 0.25f}) {
    s.particle_clouds.layer_resolution = scale;
    const nephele::Frame low = render(s);
    EXPECT_EQ(low.stats.particle_clouds->layer_width, int(std::lround(160 * scale)));
    EXPECT_EQ(low.stats.particle_clouds->layer_height, int(std::lround(96 * scale)));
    size_t n = 0;
    const double difference = masked_difference(low.color, full.color, [](size_t) { return true; }, n);
    const double luminance = low.stats.mean_luminance / full.stats.mean_luminance - 1.0;
    std::printf("layer at %.2f: mean luminance %+.2f%%, mean pixel difference %.2f%%\n", scale,
                100.0 * luminance, 100.0 * difference);
    EXPECT_NEAR(luminance, 0.0, 0.01) << scale;  // filtering moves light, it neither adds nor loses it
    EXPECT_LT(difference, scale > 0.4f ? 0.22 : 0.35) << scale;
    EXPECT_GT(difference, previous) << scale;  // the coarser, the softer
    previous = difference;
  }
}

}  // namespace

namespace {

// From a cockpit at 3.2 km over a particle field 20 km across, far clouds as impostors.
nephele::Scene cockpit_scene(const std::string& impostors) {
  nephele::Scene s = nephele::load_preset("default");
  s.output.width = 120;
  s.output.height = 72;
  s.output.auto_exposure = false;
  s.clouds.coverage = 0.0f;
  s.camera.position_m = glm::vec3(0.0f, 0.0f, 3200.0f);
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, -0.08f);
  s.particle_clouds.coverage = 0.3f;
  s.particle_clouds.field_radius_m = 20000.0f;
  s.particle_clouds.cell_m = 200.0f;
  s.particle_clouds.particle_radius_m = 260.0f;
  s.particle_clouds.impostor_distance_m = 5000.0f;
  s.particle_clouds.impostors = impostors;
  return s;
}

TEST_F(ParticleRenderTest, ImpostorsLookLikeTheParticlesTheyReplace) {
  const nephele::Frame all = render(cockpit_scene("off"));
  ASSERT_TRUE(all.stats.particle_clouds);
  EXPECT_EQ(all.stats.particle_clouds->impostors, 0);
  EXPECT_EQ(all.stats.particle_clouds->drawn, all.stats.particle_clouds->particles);
  for (const std::string method : {"direct", "tiles"}) {
    const nephele::Frame frame = render(cockpit_scene(method));
    const nephele::ParticleCloudStats& p = *frame.stats.particle_clouds;
    std::printf("%s: %d impostors of %d clouds, %zu of %zu particles drawn one by one; "
                "atlas occupancy %.3f, wasted %.3f\n",
                method.c_str(), p.impostors, p.clouds, p.drawn, p.particles, p.atlas_occupancy,
                p.atlas_wasted);
    EXPECT_GT(p.impostors, p.clouds / 2) << method;  // most of the field is far
    EXPECT_LT(p.drawn, p.particles / 2) << method;
    EXPECT_GT(p.atlas_occupancy, 0.0) << method;
    // The same image: mean luminance within 3% (the benchmark's target), and pixel by pixel
    // close on average.
    EXPECT_NEAR(frame.stats.mean_luminance / all.stats.mean_luminance, 1.0, 0.03) << method;
    size_t n = 0;
    const double difference =
        masked_difference(frame.color, all.color, [](size_t) { return true; }, n);
    std::printf("%s: mean luminance %+.2f%%, mean pixel difference %.2f%%\n", method.c_str(),
                100.0 * (frame.stats.mean_luminance / all.stats.mean_luminance - 1.0),
                100.0 * difference);
    EXPECT_LT(difference, 0.06) << method;
  }
}

// An atlas too small for every image at the asked resolution: the images are drawn smaller
// until they fit, so that no far cloud falls back to its particles, in a still and in a
// flight; with room, they stay at the asked resolution.
TEST_F(ParticleRenderTest, ImpostorsShrinkToFitASmallAtlas) {
  nephele::Scene s = cockpit_scene("off");
  s.output.width = 240;
  s.output.height = 144;
  const nephele::Frame all = render(s);
  for (const std::string method : {"direct", "tiles"}) {
    s.particle_clouds.impostors = method;
    s.particle_clouds.atlas_size = 2048;
    const nephele::ParticleCloudStats roomy = *render(s).stats.particle_clouds;
    EXPECT_EQ(roomy.impostor_resolution_scale, 1.0) << method;
    EXPECT_EQ(roomy.impostors_waiting, 0) << method;
    // Room for fewer texels than the images take, but for every image at the smallest size
    // (8 texels a side): direct granules of 8, tiles of 16.
    s.particle_clouds.atlas_size = method == "direct" ? 320 : 384;
    s.particle_clouds.atlas_granule = 8;
    s.particle_clouds.atlas_tile = 16;
    const nephele::Frame still = render(s);
    const nephele::ParticleCloudStats& p = *still.stats.particle_clouds;
    std::printf("%s in a small atlas: %d impostors, %d waiting, images at %.2f of the "
                "resolution asked, occupancy %.3f, mean luminance %+.2f%%\n",
                method.c_str(), p.impostors, p.impostors_waiting, p.impostor_resolution_scale,
                p.atlas_occupancy, 100.0 * (still.stats.mean_luminance / all.stats.mean_luminance - 1.0));
    EXPECT_LT(p.impostor_resolution_scale, 0.9) << method;
    EXPECT_EQ(p.impostors_waiting, 0) << method;
    EXPECT_EQ(p.impostors, roomy.impostors) << method;
    EXPECT_NEAR(still.stats.mean_luminance / all.stats.mean_luminance, 1.0, 0.03) << method;
    // A flight: the turn redraws images, which must keep finding room.
    nephele::Renderer& r = shared_renderer();
    for (int f = 1; f <= 6; ++f) {
      nephele::Scene next = s;
      const float yaw = 0.1f * float(f);  // rad
      next.camera.view_dir = glm::vec3(std::sin(yaw), std::cos(yaw), -0.08f);
      const nephele::ParticleCloudStats q = *r.render_next(next, false).stats.particle_clouds;
      EXPECT_EQ(q.impostors_waiting, 0) << method << " frame " << f;
      EXPECT_GE(q.impostor_resolution_scale, 0.25) << method;
    }
  }
  // Room for fewer images than far clouds (64 tiles): the clouds left over are drawn particle
  // by particle, and the image is still the same, also in a second still, turned, that
  // replaces the first's images.
  s.particle_clouds.atlas_size = 256;
  s.particle_clouds.atlas_tile = 32;
  s.camera.view_dir = glm::vec3(std::sin(0.05f), std::cos(0.05f), -0.08f);
  render(s);
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, -0.08f);  // the view of `all`
  const nephele::Frame full = render(s);
  const nephele::ParticleCloudStats& p = *full.stats.particle_clouds;
  std::printf("tiles in a 64-tile atlas: %d impostors, %d far clouds waiting\n", p.impostors,
              p.impostors_waiting);
  EXPECT_GT(p.impostors_waiting, 0);
  EXPECT_LE(p.impostors, 64);
  EXPECT_NEAR(full.stats.mean_luminance / all.stats.mean_luminance, 1.0, 0.03);
}

}  // namespace

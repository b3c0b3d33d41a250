// Bloom and glare (render/modules/post/post.h, bloom.comp): the lens's spread keeps the image's
// light, brightens the sun's surroundings, and leaves alone what lies beyond its reach.
#include <gtest/gtest.h>

#include <cmath>

#include "nephele/scene_io.h"
#include "render/modules/post/post.h"
#include "render_fixture.h"

namespace nephele {
namespace {

class BloomTest : public RenderTest {};

// Looking at the sun, 30 deg high, a few small clouds about it; a 10 deg field, so that the
// sun's disk (0.53 deg) covers a few pixels.
Scene sun_scene() {
  Scene s = load_preset("default");
  s.output.width = 96;
  s.output.height = 64;
  s.output.auto_exposure = false;
  s.sun.direction = glm::normalize(glm::vec3(0.0f, 0.87f, 0.5f));
  s.camera.view_dir = s.sun.direction;
  s.camera.fov_deg = 10.0f;
  s.clouds.coverage = 0.2f;
  return s;
}

glm::dvec3 total(const Image& image) {
  glm::dvec3 sum(0.0);
  for (const glm::vec4& p : image.pixels) sum += glm::dvec3(p);
  return sum;
}

// The sum of the image (per channel) is kept within 0.5%, whether all the light is spread or
// only the sun's; the spread takes light from the sun's pixels into their neighbours.
TEST_F(BloomTest, KeepsTheImagesLight) {
  Scene s = sun_scene();
  const Frame plain = render(s);
  s.output.bloom_strength = 0.3f;
  s.output.bloom_radius_deg = 0.5f;
  for (const float threshold : {0.0f, 1.0e5f}) {
    s.output.bloom_threshold_cd_m2 = threshold;
    const Frame bloomed = render(s);
    const glm::dvec3 a = total(plain.color), b = total(bloomed.color);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(b[c] / a[c], 1.0, 0.005) << "threshold " << threshold;
    // The brightest pixel (the sun) gives light away; its surroundings gain it.
    size_t brightest = 0;
    for (size_t i = 0; i < plain.color.pixels.size(); ++i)
      if (plain.color.pixels[i].g > plain.color.pixels[brightest].g) brightest = i;
    EXPECT_LT(bloomed.color.pixels[brightest].g, plain.color.pixels[brightest].g);
    const int x = int(brightest % size_t(s.output.width)), y = int(brightest / size_t(s.output.width));
    std::printf("threshold %g: the sun's pixel %g -> %g cd/m^2\n", threshold,
                plain.color.pixels[brightest].g, bloomed.color.pixels[brightest].g);
    const int nx = std::min(x + 3, s.output.width - 1);
    EXPECT_GT(bloomed.color.at(nx, y).g, plain.color.at(nx, y).g * 1.01f);
  }
}

// With a threshold above all but the sun, pixels further from the sun than the kernel reaches
// (in x or y) are the same as without bloom; strength 0 changes nothing.
TEST_F(BloomTest, LeavesAloneWhatItDoesNotReach) {
  Scene s = sun_scene();
  const Frame plain = render(s);
  size_t brightest = 0;
  for (size_t i = 0; i < plain.color.pixels.size(); ++i)
    if (plain.color.pixels[i].g > plain.color.pixels[brightest].g) brightest = i;
  const int sx = int(brightest % size_t(s.output.width)), sy = int(brightest / size_t(s.output.width));
  s.output.bloom_strength = 0.2f;
  s.output.bloom_radius_deg = 0.1f;
  s.output.bloom_threshold_cd_m2 = 0.5f * plain.color.pixels[brightest].g;
  const glm::vec2 kernel = bloom_kernel(0.1f, vertical_fov_deg(s), s.output.width, s.output.height);
  const int reach = int(kernel.y);
  const Frame bloomed = render(s);
  int far = 0;
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      if (std::abs(x - sx) <= 2 * reach + 2 || std::abs(y - sy) <= 2 * reach + 2) continue;
      ++far;
      // Renders agree to a few units in the last place (lavapipe's threads).
      for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(bloomed.color.at(x, y)[c], plain.color.at(x, y)[c], 1e-5f * plain.color.at(x, y)[c])
            << x << ", " << y;
    }
  EXPECT_GT(far, 500);
  s.output.bloom_strength = 0.0f;
  const Frame none = render(s);
  for (size_t i = 0; i < none.color.pixels.size(); ++i)
    EXPECT_NEAR(none.color.pixels[i].g, plain.color.pixels[i].g, 1e-5f * plain.color.pixels[i].g);
}

// The Gaussian's sigma is the radius in pixels of view: 1 deg of a 70 deg field 320 pixels high
// is 4.0 pixels, 12 taps each side; a tiny image narrows it to fit.
TEST(BloomKernel, SigmaFromTheAngleAndTheImage) {
  const glm::vec2 k = bloom_kernel(1.0f, 70.0f, 480, 320);
  EXPECT_NEAR(k.x, 160.0f / std::tan(glm::radians(35.0f)) * std::tan(glm::radians(1.0f)), 1e-3f);
  EXPECT_EQ(k.y, 12.0f);
  const glm::vec2 tiny = bloom_kernel(30.0f, 70.0f, 8, 6);
  EXPECT_EQ(tiny.y, 5.0f);
  EXPECT_NEAR(tiny.x, 5.0f / 3.0f, 1e-6f);
}

}  // namespace
}  // namespace nephele

// The lightning module (render/modules/lightning) on the device: flashes in the storm cells of
// the thunderstorm preset at night, seen by their light. Its laws and block are tested on the
// CPU in tests/unit/lightning_test.cpp; here, what the image shows: flashes that come and go and
// are the same on a re-render, a stroke's bolt under the cloud base, and a flash that lights
// its own frame of a sequence, whose clouds are marched over several frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include "nephele/image_compare.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

using nephele::Scene;

namespace {

class LightningTest : public RenderTest {};

// The storm 70 km away at night (the sun 20 degrees down, no moon), flashing 30 times a minute
// a cell, at a fixed exposure.
Scene storm_night(float time_s) {
  Scene s = nephele::load_preset("thunderstorm-dusk");
  s.sun.direction = nephele::sun_direction_from_angles(-20.0, 250.0);
  s.lightning.flashes_per_min = 30.0f;
  s.camera.position_m = {-100.0f, -71200.0f, 2.0f};
  s.camera.view_dir = {0.0f, 1.0f, 0.22f};
  s.camera.fov_deg = 65.0f;
  s.output.width = 96;
  s.output.height = 64;
  s.output.auto_exposure = false;
  s.output.ev100 = -2.0f;
  s.time_s = time_s;
  return s;
}

double total_luminance(const nephele::Image& image) {
  double sum = 0.0;
  for (const glm::vec4& p : image.pixels) sum += nephele::luminance(p);
  return sum;
}

// Over four seconds the view is lit by flashes in some frames and dark in others; without
// lightning it is as dark as the darkest; the brightest frame re-rendered is the same.
TEST_F(LightningTest, FlashesComeAndGoAndAreTheSameOnARerender) {
  std::vector<double> sums;
  double brightest = 0.0;
  float brightest_s = 0.0f;
  for (const float t : {0.3f, 1.3f, 2.3f, 3.3f}) {
    sums.push_back(total_luminance(render(storm_night(t)).color));
    if (sums.back() > brightest) brightest = sums.back(), brightest_s = t;
  }
  const double darkest = *std::min_element(sums.begin(), sums.end());
  EXPECT_GT(brightest, 10.0 * darkest) << "no flash lit the view";
  Scene calm = storm_night(brightest_s);
  calm.lightning.flashes_per_min = 0.0f;
  const double unlit = total_luminance(render(calm).color);
  EXPECT_LE(unlit, darkest * 1.0001);
  const nephele::Image a = render(storm_night(brightest_s)).color;
  const nephele::Image b = render(storm_night(brightest_s)).color;
  for (size_t i = 0; i < a.pixels.size(); ++i) ASSERT_EQ(a.pixels[i], b.pixels[i]) << i;
}

// A stroke to the ground 24 km ahead (seed 1, 2.3 s), seen through a 10-degree lens: its bolt
// is a thin bright line standing under the cloud base, which the same flash kept in the cloud
// (ground_share 0) does not draw.
TEST_F(LightningTest, AStrokeDrawsItsBoltUnderTheBase) {
  Scene stroke = storm_night(2.3f);
  stroke.camera.view_dir = {-0.1537f, 1.0f, 0.02f};
  stroke.camera.fov_deg = 10.0f;
  stroke.lightning.ground_share = 1.0f;
  Scene in_cloud = stroke;
  in_cloud.lightning.ground_share = 0.0f;
  const nephele::Image a = render(stroke).color, b = render(in_cloud).color;
  // The bolt's pixels stand out of their row, five times its median: the most of them in one
  // column (a standing line) against none such without the stroke.
  const auto tallest_column = [](const nephele::Image& image) {
    std::vector<int> count(size_t(image.width), 0);
    for (int y = 0; y < image.height; ++y) {
      std::vector<double> row;
      for (int x = 0; x < image.width; ++x) row.push_back(nephele::luminance(image.at(x, y)));
      std::vector<double> sorted = row;
      std::nth_element(sorted.begin(), sorted.begin() + image.width / 2, sorted.end());
      const double median = sorted[size_t(image.width / 2)];
      for (int x = 0; x < image.width; ++x)
        count[size_t(x)] += row[size_t(x)] > 5.0 * median + 1e-6;
    }
    return *std::max_element(count.begin(), count.end());
  };
  EXPECT_GE(tallest_column(a), 8) << "no bolt standing under the base";
  EXPECT_LE(tallest_column(b), 3) << "a bolt without a stroke";
}

// In a sequence the clouds are marched a pixel in 16 a frame and reprojected; a flash lights
// its own frame all the same, as much as a still at that time.
TEST_F(LightningTest, AFlashLightsItsOwnFrameInASequence) {
  const auto sequence_end = [](Scene first) {
    nephele::Renderer r(validated());
    first.quality.mode = nephele::MarchMode::Default;
    r.render(first);
    Scene s = first;
    s.time_s = 2.3f;
    return total_luminance(r.render_next(s).color);
  };
  Scene first = storm_night(2.2f);
  Scene calm = first;
  calm.lightning.flashes_per_min = 0.0f;
  const double lit = sequence_end(first), dark = sequence_end(calm);
  const double still = total_luminance(render(storm_night(2.3f)).color);
  EXPECT_GT(lit, 3.0 * dark);
  EXPECT_GT(lit - dark, 0.5 * (still - dark));
}

}  // namespace

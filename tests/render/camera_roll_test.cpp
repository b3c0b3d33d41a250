// camera.roll_deg on the device: a rolled camera sees the unrolled image turned, and the
// horizon tilts the way scene.h says (positive roll: the horizon rises to the right).
#include <gtest/gtest.h>

#include <cmath>

#include "nephele/image.h"
#include "nephele/image_compare.h"
#include "nephele/scene.h"
#include "render/frame_params.h"
#include "render_fixture.h"

namespace {

using nephele::Image;
using nephele::Scene;

class CameraRollTest : public RenderTest {};

// A small square view north and a little up, with clouds over the sky and ground below. (At
// 32 pixels a side the per-pixel jitter at the cumulus' edges alone made the turned images
// differ by 5%, whatever the lighting; at 64, 0.7%.)
Scene square_view() {
  Scene s;
  s.output.width = s.output.height = 64;
  s.camera.view_dir = {0.2f, 1.0f, 0.05f};
  s.camera.fov_deg = 60.0f;
  s.clouds.coverage = 0.6f;
  return s;
}

// The row (continuous, from the top) where the column's luminance drops most from one pixel to
// the next: the horizon, where the bright sky meets the dark ground.
double horizon_row(const Image& image, int x) {
  double best_drop = -1.0, row = -1.0;
  for (int y = 0; y + 1 < image.height; ++y) {
    const double drop = nephele::luminance(image.at(x, y)) - nephele::luminance(image.at(x, y + 1));
    if (drop > best_drop) {
      best_drop = drop;
      row = y + 0.5;
    }
  }
  return row;
}

}  // namespace

// The basis: roll 0 is the unrolled basis bit for bit, roll 90 turns right into down.
TEST(CameraBasis, RollTurnsRightAndUpAboutForward) {
  nephele::CameraParams camera;
  camera.view_dir = {0.3f, 1.0f, 0.2f};
  const nephele::CameraBasis plain = nephele::camera_basis(camera.view_dir);
  const nephele::CameraBasis zero = nephele::camera_basis(camera);
  EXPECT_EQ(zero.forward, plain.forward);
  EXPECT_EQ(zero.right, plain.right);
  EXPECT_EQ(zero.up, plain.up);
  camera.roll_deg = 90.0f;
  const nephele::CameraBasis rolled = nephele::camera_basis(camera);
  EXPECT_EQ(rolled.forward, plain.forward);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(rolled.right[i], -plain.up[i], 1e-6f);  // the right wing goes down
    EXPECT_NEAR(rolled.up[i], plain.right[i], 1e-6f);
  }
}

// Roll 90 is the roll-0 image turned 90 degrees counter-clockwise: pixel (x, y) of the rolled
// image is pixel (w - 1 - y, x) of the plain one. The clouds' per-pixel jitter differs between
// the two, so the match is statistical.
TEST_F(CameraRollTest, Roll90IsTheImageTurnedCounterClockwise) {
  Scene s = square_view();
  const Image plain = render(s).color;
  s.camera.roll_deg = 90.0f;
  const Image rolled = render(s).color;
  const int n = s.output.width;
  double diff = 0.0, sum = 0.0, diff_unturned = 0.0;
  for (int y = 0; y < n; ++y)
    for (int x = 0; x < n; ++x) {
      const double a = nephele::luminance(rolled.at(x, y));
      diff += std::abs(a - nephele::luminance(plain.at(n - 1 - y, x)));
      diff_unturned += std::abs(a - nephele::luminance(plain.at(x, y)));
      sum += a;
    }
  std::printf("rolled against the turned image: %.4f (before turning %.4f)\n", diff / sum,
              diff_unturned / sum);
  EXPECT_LT(diff / sum, 0.03) << "relative mean difference to the turned image";
  EXPECT_GT(diff_unturned / sum, 0.2) << "the images differ before turning";
}

// Positive roll: the horizon is lower on the left than on the right; negative: the reverse.
TEST_F(CameraRollTest, HorizonRisesToTheRightWithPositiveRoll) {
  Scene s = square_view();
  s.clouds.coverage = 0.0f;
  s.camera.view_dir = {0.0f, 1.0f, 0.0f};
  const int last = s.output.width - 1;
  const Image level = render(s).color;
  EXPECT_NEAR(horizon_row(level, 2), horizon_row(level, last - 2), 1.0);
  s.camera.roll_deg = 20.0f;
  const Image right_up = render(s).color;
  // tan 20 deg of the 28 columns between: about 10 rows.
  EXPECT_GT(horizon_row(right_up, 2) - horizon_row(right_up, last - 2), 6.0);
  s.camera.roll_deg = -20.0f;
  const Image left_up = render(s).color;
  EXPECT_LT(horizon_row(left_up, 2) - horizon_row(left_up, last - 2), -6.0);
}

// Rolling during an animation: the previous frame's basis carries its roll, so the history is
// found where the roll moved it and the frames match a still image of the final view.
TEST_F(CameraRollTest, RollingAnimationReprojectsItsHistory) {
  Scene s = square_view();
  s.output.width = 64;
  s.output.height = 40;
  s.quality.cloud_downsample = 1;
  s.clouds.wind_mps = {0.0f, 0.0f};
  s.clouds.weather_evolution_s = 0.0f;
  s.sun.direction = {0.3f, -0.7f, 0.4f};  // behind: one pixel of the disk would swamp the rest
  render(s);
  nephele::Frame frame;
  for (int i = 1; i <= 24; ++i) {
    s.camera.roll_deg = 1.5f * float(i);
    frame = shared_renderer().render_next(s);
  }
  const Image still = render(s).color;
  Scene unrolled = s;
  unrolled.camera.roll_deg = 0.0f;
  // How far the roll moved the image: history taken at the same pixel would be this far off.
  const double moved = nephele::luminance_error(render(unrolled).color, still);
  EXPECT_GT(moved, 0.5);  // measured 0.94
  // Measured 0.18; 0.49 when the previous frame's basis leaves out its roll.
  const double error = nephele::luminance_error(frame.color, still);
  EXPECT_LT(error, 0.25);
  EXPECT_LT(error, 0.3 * moved);
}

// Pure functions behind temporal reprojection and the light volume (shaders/common/*_inc.glsl).
#include <gtest/gtest.h>

#include <cmath>

#include "render/glsl.h"
#include "render/modules/clouds/clouds.h"

namespace g = nephele::glsl;
using glm::vec2;
using glm::vec3;

TEST(CameraPixel, InvertsCameraRayOverTheImageAndBeyond) {
  // An oblique camera; pixels inside and outside a 90 x 60 image (reprojection looks there too).
  const vec3 forward = glm::normalize(vec3(0.3f, 1.0f, 0.4f));
  const vec3 right = glm::normalize(glm::cross(forward, vec3(0, 0, 1)));
  const vec3 up = glm::cross(right, forward);
  const float tan_half = std::tan(glm::radians(30.0f)), aspect = 1.5f;
  for (float y = -10.0f; y <= 70.0f; y += 7.3f)
    for (float x = -10.0f; x <= 100.0f; x += 9.1f) {
      const vec3 dir = g::camera_ray(forward, right, up, tan_half, aspect, x, y, 90.0f, 60.0f);
      const vec2 p = g::camera_pixel(forward, right, up, tan_half, aspect, dir, 90.0f, 60.0f);
      EXPECT_NEAR(p.x, x, 1e-3f);
      EXPECT_NEAR(p.y, y, 1e-3f);
    }
}

TEST(CameraPixel, DirectionsBehindTheCameraAreOffImage) {
  const vec2 p = g::camera_pixel(vec3(0, 1, 0), vec3(1, 0, 0), vec3(0, 0, 1), 0.5f, 1.5f,
                                 vec3(0.1f, -1.0f, 0.0f), 90.0f, 60.0f);
  EXPECT_LT(p.x, -1e6f);
  EXPECT_LT(p.y, -1e6f);
}

TEST(LightVolume, CoordinateMapRoundTripsAndIsFineNearTheCentre) {
  const float half_m = 150000.0f;
  EXPECT_EQ(g::light_volume_coord(vec2(0.0f), half_m), vec2(0.5f));
  EXPECT_FLOAT_EQ(g::light_volume_coord(vec2(half_m, 0.0f), half_m).x, 1.0f);
  EXPECT_FLOAT_EQ(g::light_volume_coord(vec2(0.0f, -half_m), half_m).y, 0.0f);
  // Clamped to the disk outside it, in the same direction.
  const vec2 outside = g::light_volume_coord(vec2(3.0f * half_m, 3.0f * half_m), half_m);
  EXPECT_NEAR(glm::length(outside - 0.5f), 0.5f, 1e-6f);
  EXPECT_NEAR(outside.x, outside.y, 1e-6f);
  for (float x = -half_m; x <= half_m; x += 13731.0f)
    for (float y = -half_m; y <= half_m; y += 17113.0f) {
      const vec2 off(x, y);
      if (glm::length(off) > half_m) continue;
      const vec2 back = g::light_volume_offset_m(g::light_volume_coord(off, half_m), half_m);
      EXPECT_NEAR(back.x, x, 1e-3f * half_m);
      EXPECT_NEAR(back.y, y, 1e-3f * half_m);
    }
  // Voxel size = the map's radial derivative / cells: compare with a finite difference, along
  // an axis and along a diagonal alike (no direction is favoured).
  const int cells = 160;
  for (const vec2 dir : {vec2(1.0f, 0.0f), glm::normalize(vec2(1.0f, 1.0f)), vec2(0.0f, -1.0f)})
    for (float r : {1000.0f, 5000.0f, 20000.0f, 100000.0f}) {
      const vec2 c = g::light_volume_coord(dir * r, half_m);
      const vec2 dc = dir * (0.5f / float(cells));
      const float numeric = glm::length(g::light_volume_offset_m(c + dc, half_m) -
                                        g::light_volume_offset_m(c - dc, half_m));
      EXPECT_NEAR(g::light_volume_voxel_m(r, half_m, cells), numeric, 0.01f * numeric) << r;
    }
  // Fine near the camera, coarse far away: about 0.3 km at 1 km, 3 km at 100 km.
  EXPECT_NEAR(g::light_volume_voxel_m(1000.0f, half_m, cells), 306.0f, 1.0f);
  EXPECT_NEAR(g::light_volume_voxel_m(100000.0f, half_m, cells), 3062.0f, 5.0f);
}

namespace {

// A frame's parameters for a camera looking along `heading_deg` (about the vertical, 0 north,
// 90 east) and `pitch_deg` up, 60 deg vertically over a 160 x 100 cloud buffer with history,
// whose previous frame looked along `previous_deg` and `previous_pitch_deg`.
nephele::gpu::FrameParams turning(float heading_deg, float previous_deg, float pitch_deg = 8.0f,
                                  float previous_pitch_deg = 8.0f) {
  nephele::gpu::FrameParams f{};
  const auto basis = [](float deg, float pitch_deg, glm::vec4& forward, glm::vec4& right,
                        glm::vec4& up, glm::vec4& pos) {
    const float a = glm::radians(deg), p = glm::radians(pitch_deg);
    const vec3 fw(std::sin(a) * std::cos(p), std::cos(a) * std::cos(p), std::sin(p));
    const vec3 r = glm::normalize(glm::cross(fw, vec3(0, 0, 1)));
    forward = glm::vec4(fw, 1.6f);  // w the aspect
    right = glm::vec4(r, 0.0f);     // w the lens shift
    up = glm::vec4(glm::cross(r, fw), 0.0f);
    pos = glm::vec4(0.0f, 0.0f, 0.0f, std::tan(glm::radians(30.0f)));  // w tan(half fov)
  };
  basis(heading_deg, pitch_deg, f.camera_forward, f.camera_right, f.camera_up, f.camera_pos_m);
  basis(previous_deg, previous_pitch_deg, f.prev_camera_forward, f.prev_camera_right,
        f.prev_camera_up, f.prev_camera_pos_m);
  f.cloud_grid = glm::ivec4(160, 100, 4, 1);
  return f;
}

}  // namespace

// What a turning or pitching camera brings in, which the frame marches itself: the columns at
// the side it turns to, as many as the turn, or the rows at the top or bottom it pitches to;
// nothing without a move, without history, or for a move of more than a quarter of the image.
TEST(EnteringRegion, IsWhatATurnOrAPitchBringsIn) {
  // 2 deg of a 60 x 96 deg view (aspect 1.6: tan 48 deg = 1.6 tan 30 deg): about 3.5 columns
  // of 160 at the centre, more at the sides.
  const glm::ivec4 right = nephele::entering_region(turning(12.0f, 10.0f));
  EXPECT_EQ(right.x + right.y, 160);
  EXPECT_GE(right.y, 4);
  EXPECT_LE(right.y, 8);
  EXPECT_LE(right.w, 4);  // the turn about the vertical tilts the top and bottom a little
  const glm::ivec4 left = nephele::entering_region(turning(8.0f, 10.0f));
  EXPECT_EQ(left.x, 0);
  EXPECT_NEAR(left.y, right.y, 1);  // sampled every 2 columns
  // Pitching up 2 deg: about 3.5 rows of 100 at the top, no columns.
  const glm::ivec4 up = nephele::entering_region(turning(10.0f, 10.0f, 10.0f, 8.0f));
  EXPECT_EQ(up.y, 0);
  EXPECT_EQ(up.z, 0);
  EXPECT_GE(up.w, 3);
  EXPECT_LE(up.w, 7);
  const glm::ivec4 down = nephele::entering_region(turning(10.0f, 10.0f, 6.0f, 8.0f));
  EXPECT_EQ(down.z + down.w, 100);
  EXPECT_EQ(nephele::entering_region(turning(10.0f, 10.0f)), glm::ivec4(0));
  EXPECT_EQ(nephele::entering_region(turning(40.0f, 10.0f)).y, 0);  // over a quarter
  nephele::gpu::FrameParams no_history = turning(12.0f, 10.0f);
  no_history.cloud_grid.w = 0;
  EXPECT_EQ(nephele::entering_region(no_history), glm::ivec4(0));
}

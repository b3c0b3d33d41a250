// Pure functions behind temporal reprojection and the light volume (shaders/common/*_inc.glsl).
#include <gtest/gtest.h>

#include <cmath>

#include "render/glsl.h"

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

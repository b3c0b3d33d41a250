// The sky-view LUT mapping (shaders/common/sky_view_inc.glsl compiled as C++): directions and
// LUT coordinates round-trip, the horizon is the row boundary v = 0.5, and the LUT's texels on
// either side of it see sky and ground as sky_single_scattering does.
#include "render/modules/sky_view/sky_view.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/glsl.h"

namespace g = nephele::glsl;
using glm::vec2;
using glm::vec3;

namespace {

// The scene's default atmosphere.
const g::Atmosphere kEarth{.planet_radius_m = 6360e3f,
                           .top_radius_m = 6460e3f,
                           .rayleigh_sigma_s = vec3(5.802e-6f, 13.558e-6f, 33.1e-6f),
                           .rayleigh_height_m = 8000.0f,
                           .mie_sigma_s = 3.996e-6f,
                           .mie_sigma_t = 4.44e-6f,
                           .mie_height_m = 1200.0f,
                           .mie_g = 0.8f};

// Camera altitudes (m): the ground to above the top of the atmosphere.
const float kAltitudesM[] = {0.5f, 2.0f, 100.0f, 1500.0f, 10000.0f, 60000.0f, 200000.0f};

// Suns: ordinary, low, set, and straight up or down at the camera `eye` (no azimuth).
std::vector<vec3> suns(vec3 eye) {
  return {glm::normalize(vec3(0.3f, 0.7f, 0.35f)), glm::normalize(vec3(-1.0f, 0.2f, 0.03f)),
          glm::normalize(vec3(0.0f, 1.0f, -0.2f)), glm::normalize(eye), -glm::normalize(eye)};
}

// n directions evenly spread over the sphere (Fibonacci).
std::vector<vec3> sphere_directions(int n) {
  std::vector<vec3> dirs;
  const float golden = g::PI * (3.0f - std::sqrt(5.0f));
  for (int i = 0; i < n; ++i) {
    const float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(n);
    const float r = std::sqrt(1.0f - z * z);
    dirs.emplace_back(r * std::cos(golden * float(i)), r * std::sin(golden * float(i)), z);
  }
  return dirs;
}

// Angle (rad) between unit vectors, accurate for small angles.
double angle(vec3 a, vec3 b) {
  return 2.0 * std::asin(std::min(1.0, double(glm::length(a - b)) / 2.0));
}

// The camera `altitude_m` above the ground, near the planet frame's +z axis as the renderer
// puts it (planet_from_enu), where float positions are exact to the metre...
vec3 eye_at(float altitude_m) {
  return vec3(300.0f, -200.0f, kEarth.planet_radius_m + altitude_m);
}

// ... or far from it, where positions round to about half a metre.
vec3 eye_far_at(float altitude_m) {
  return glm::normalize(vec3(0.2f, -0.3f, 1.0f)) * (kEarth.planet_radius_m + altitude_m);
}

}  // namespace

TEST(SkyView, FrameIsOrthonormalWithTheSunAtTheMiddleColumn) {
  for (float altitude : kAltitudesM)
    for (vec3 sun : suns(eye_at(altitude))) {
      const g::SkyViewFrame f = g::sky_view_frame(eye_at(altitude), sun, kEarth.planet_radius_m);
      EXPECT_NEAR(glm::length(f.up), 1.0f, 1e-6f);
      EXPECT_NEAR(glm::length(f.forward), 1.0f, 1e-6f);
      EXPECT_NEAR(glm::dot(f.up, f.forward), 0.0f, 1e-6f);
      EXPECT_NEAR(glm::length(f.side), 1.0f, 1e-6f);
      EXPECT_LE(f.horizon_elevation_rad, 0.0f);
      EXPECT_NEAR(glm::dot(f.up, f.side), 0.0f, 1e-6f);
      EXPECT_GE(glm::dot(sun, f.forward), -1e-6f);
      if (std::abs(glm::dot(sun, f.up)) < 0.999f)
        EXPECT_NEAR(g::sky_view_uv(f, sun).x, 0.5f, 1e-3f) << "altitude " << altitude;
    }
}

TEST(SkyView, DirectionsRoundTripThroughLutCoordinates) {
  const std::vector<vec3> dirs = sphere_directions(20000);
  for (float altitude : kAltitudesM)
    for (vec3 sun : suns(eye_far_at(altitude))) {
      const g::SkyViewFrame f =
          g::sky_view_frame(eye_far_at(altitude), sun, kEarth.planet_radius_m);
      double worst = 0.0;
      for (vec3 d : dirs) {
        const vec2 uv = g::sky_view_uv(f, d);
        ASSERT_GE(uv.x, 0.0f);
        ASSERT_LE(uv.x, 1.0f);
        ASSERT_GE(uv.y, 0.0f);
        ASSERT_LE(uv.y, 1.0f);
        worst = std::max(worst, angle(g::sky_view_dir(f, uv), d));
      }
      // asin in float next to the zenith: 2.3e-4 rad measured, a thirtieth of a texel (half a
      // texel would be 8e-3; the azimuth's sign lost, as in a mirrored table, up to pi).
      EXPECT_LT(worst, 5e-4) << "altitude " << altitude << " m: worst angle (rad)";
    }
}

TEST(SkyView, TexelCentresRoundTrip) {
  const int w = int(nephele::kSkyViewWidth), h = int(nephele::kSkyViewHeight);
  for (float altitude : kAltitudesM) {
    const vec3 eye = eye_at(altitude);
    const g::SkyViewFrame f = g::sky_view_frame(eye, suns(eye)[0], kEarth.planet_radius_m);
    for (int j = 0; j < h; ++j)
      for (int i = 0; i < w; ++i) {
        const vec2 uv((float(i) + 0.5f) / float(w), (float(j) + 0.5f) / float(h));
        const vec2 back = g::sky_view_uv(f, g::sky_view_dir(f, uv));
        // A hundredth of a texel.
        ASSERT_NEAR(back.x, uv.x, 0.01f / float(w)) << "texel " << i << ", " << j;
        ASSERT_NEAR(back.y, uv.y, 0.01f / float(h)) << "texel " << i << ", " << j;
      }
  }
}

TEST(SkyView, HorizonMapsToTheRowBoundary) {
  for (float altitude : kAltitudesM) {
    const vec3 eye = eye_at(altitude);
    const g::SkyViewFrame f = g::sky_view_frame(eye, suns(eye)[0], kEarth.planet_radius_m);
    // The horizon's elevation is the tangent to the planet: cos(dip) = R / r (in double).
    const double r = double(kEarth.planet_radius_m) + double(altitude);
    const double dip = std::acos(double(kEarth.planet_radius_m) / r);
    EXPECT_NEAR(f.horizon_elevation_rad, -dip, 1e-6) << "altitude " << altitude;
    for (float azimuth : {0.0f, 1.0f, 2.5f}) {
      const vec3 horizontal = std::cos(azimuth) * f.forward + std::sin(azimuth) * f.side;
      const vec3 tangent = float(std::cos(dip)) * horizontal - float(std::sin(dip)) * f.up;
      // v - 0.5 grows as the square root of the angle from the horizon: 1e-3 in v is 6e-6 rad
      // (ignoring the horizon's dip would be 0.01 at 2 m).
      EXPECT_NEAR(g::sky_view_uv(f, tangent).y, 0.5f, 1e-3f) << "altitude " << altitude;
      // 2e-5 rad above and below the horizon.
      const vec3 tilt = float(std::sin(dip)) * horizontal + float(std::cos(dip)) * f.up;
      const vec3 above = tangent + 2e-5f * tilt, below = tangent - 2e-5f * tilt;
      EXPECT_GE(g::sky_view_uv(f, above).y, 0.5f) << "altitude " << altitude;
      EXPECT_LT(g::sky_view_uv(f, below).y, 0.5f) << "altitude " << altitude;
      const float u = 0.5f + azimuth / (2.0f * g::PI);
      EXPECT_LT(angle(g::sky_view_dir(f, vec2(u, 0.5f)), tangent), 1e-6);
    }
    // Zenith, nadir (asin in float: within a twentieth of a row); towards the sun, to its left
    // and right (the azimuth's sign is kept), away from it (the seam, u = 0 or 1).
    EXPECT_NEAR(g::sky_view_uv(f, f.up).y, 1.0f, 5e-4f);
    EXPECT_NEAR(g::sky_view_uv(f, -f.up).y, 0.0f, 5e-4f);
    EXPECT_NEAR(g::sky_view_uv(f, f.forward).x, 0.5f, 1e-6f);
    EXPECT_NEAR(g::sky_view_uv(f, f.side).x, 0.75f, 1e-6f);
    EXPECT_NEAR(g::sky_view_uv(f, -f.side).x, 0.25f, 1e-6f);
    const float away = g::sky_view_uv(f, -f.forward).x;
    EXPECT_NEAR(std::min(away, 1.0f - away), 0.0f, 1e-6f);
  }
}

// The texels next to the horizon lie a small fraction of a degree from it; the LUT is only
// right if sky_single_scattering sees the ground from every texel below the horizon and from
// none above it, wherever the camera is.
TEST(SkyView, TexelsBelowTheHorizonAndOnlyThoseSeeTheGround) {
  const int w = int(nephele::kSkyViewWidth), h = int(nephele::kSkyViewHeight);
  for (float altitude : kAltitudesM)
    for (vec3 eye : {eye_at(altitude), eye_far_at(altitude)}) {
      const vec3 sun = suns(eye)[0];
      const g::SkyViewFrame f = g::sky_view_frame(eye, sun, kEarth.planet_radius_m);
      int wrong = 0, moved = 0;
      for (int j = 0; j < h; ++j)
        for (int i = 0; i < w; i += 5) {
          const vec2 uv((float(i) + 0.5f) / float(w), g::sky_view_row_v(j, h));
          const vec3 d = g::sky_view_texel_dir(f, uv, eye, kEarth.planet_radius_m);
          if (angle(d, g::sky_view_dir(f, uv)) > 0.0) ++moved;
          const g::SkySample sky =
              g::sky_single_scattering(kEarth, eye, d, sun, 4, 2, 0.1f, vec3(0));
          if ((sky.transmittance.x == 0.0f) != (j < h / 2)) ++wrong;
        }
      EXPECT_EQ(wrong, 0) << "altitude " << altitude << " m, eye.x " << eye.x;
      // Only texels of the two rows next to the horizon ever move.
      EXPECT_LE(moved, 2 * (w / 5 + 1)) << "altitude " << altitude << " m, eye.x " << eye.x;
    }
}

// The LUT's rows: a lookup at a row's own v reads that row's centre, and the last row on
// each side is the zenith (nadir) at every azimuth, so the sky is continuous across it.
TEST(SkyView, RowsRoundTripAndTheLastRowIsTheZenith) {
  const int h = int(nephele::kSkyViewHeight);
  for (int j = 0; j < h; ++j)
    EXPECT_NEAR(g::sky_view_row_coordinate(g::sky_view_row_v(j, h), float(h)),
                (float(j) + 0.5f) / float(h), 1e-6f) << "row " << j;
  const vec3 eye = eye_at(2.0f);
  const g::SkyViewFrame f = g::sky_view_frame(eye, suns(eye)[0], kEarth.planet_radius_m);
  for (float u : {0.0f, 0.3f, 0.5f, 0.9f}) {
    EXPECT_LT(angle(g::sky_view_dir(f, vec2(u, g::sky_view_row_v(h - 1, h))), f.up), 1e-3);
    EXPECT_LT(angle(g::sky_view_dir(f, vec2(u, g::sky_view_row_v(0, h))), -f.up), 1e-3);
  }
  // The first row above the horizon stays off it: half a row in v.
  EXPECT_GT(g::sky_view_row_v(h / 2, h), 0.5f + 0.4f / float(h));
  EXPECT_LT(g::sky_view_row_v(h / 2 - 1, h), 0.5f - 0.4f / float(h));
}

TEST(SkyView, TexcoordsStayOnTheirSideOfTheHorizonAndInTheirTable) {
  const float rows = float(nephele::kSkyViewHeight);
  for (float table : {0.0f, 1.0f})
    for (float v : {0.0f, 0.001f, 0.3f, 0.4999f, 0.5f, 0.5001f, 0.8f, 1.0f}) {
      const vec2 tc = g::sky_view_texcoord(vec2(0.3f, v), rows, table);
      EXPECT_EQ(tc.x, 0.3f);
      // Texel rows of the whole image (2 rows high): the bilinear footprint's rows.
      const float row = tc.y * 2.0f * rows - 0.5f;
      const float lo = table * rows + (v < 0.5f ? 0.0f : 0.5f * rows);
      const float hi = lo + 0.5f * rows - 1.0f;
      EXPECT_GE(row, lo - 1e-3f) << "v " << v << " table " << table;
      EXPECT_LE(row, hi + 1e-3f) << "v " << v << " table " << table;
    }
}

namespace {

// The CPU's table lookups are safe for any float: a NaN coordinate (from a NaN position or
// direction) read past the table and crashed (issue 18); it reads the first texel instead, and
// coordinates beyond the table the edge texels.
TEST(TableLookup, AnyFloatCoordinateReadsATexelOfTheTable) {
  const std::vector<glm::vec4> texels = {glm::vec4(1.0f), glm::vec4(2.0f), glm::vec4(3.0f),
                                         glm::vec4(4.0f)};
  const g::sampler2D table{texels.data(), 2, 2};
  const float nan = std::nanf(""), inf = INFINITY;
  EXPECT_EQ(g::textureLod(table, vec2(nan, nan), 0.0f), glm::vec4(1.0f));
  EXPECT_EQ(g::textureLod(table, vec2(inf, -inf), 0.0f), glm::vec4(2.0f));
  EXPECT_EQ(g::textureLod(table, vec2(-1e30f, 1e30f), 0.0f), glm::vec4(3.0f));
  EXPECT_EQ(g::textureLod(table, vec2(0.75f, 0.75f), 0.0f), glm::vec4(4.0f));
  // Through the atmosphere's lookups: a camera 1e30 m away gives NaN coordinates.
  std::vector<glm::vec4> lut(size_t(g::TRANSMITTANCE_LUT_W) * g::TRANSMITTANCE_LUT_H, glm::vec4(0.5f));
  const g::sampler2D t_lut{lut.data(), g::TRANSMITTANCE_LUT_W, g::TRANSMITTANCE_LUT_H};
  const vec3 t = g::transmittance_to_light(kEarth, t_lut, false, vec3(1e30f, 0.0f, 6.36e6f),
                                           vec3(0.0f, 0.0f, 1.0f));
  for (int c = 0; c < 3; ++c) EXPECT_TRUE(t[c] == 0.5f || t[c] == 1.0f || t[c] == 0.0f) << t[c];
  EXPECT_EQ(g::saturate(nan), 0.0f);
}

}  // namespace

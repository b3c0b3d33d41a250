// Hillaire's LUT sky (the default) against the brute-force reference rendered by the same
// renderer (atmosphere.model = reference: every pixel integrated with no table, the sun's
// transmittance integrated in place and Psi_ms evaluated at every step), and the sky from the
// ground to space.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "nephele/image_compare.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "frame_atmosphere.h"
#include "render_fixture.h"

using nephele::Scene;
using nephele::SkyModel;

namespace {

// A cloudless sky with the sun at `elevation_deg` in the north, small enough for the reference.
Scene clear_sky(float sun_elevation_deg) {
  Scene s = nephele::load_preset("default");
  s.clouds.coverage = 0.0f;
  s.quality.light_volume_km = 0;  // no clouds to light: no light volume to build
  s.output.width = 48;
  s.output.height = 32;
  const float e = glm::radians(sun_elevation_deg);
  s.sun.direction = {0.0f, std::cos(e), std::sin(e)};
  return s;
}

// Mean over pixels of |L - L_ref| / L_ref (luminance), between the LUT sky and the reference.
double lut_error(Scene s) {
  s.atmosphere.model = SkyModel::Hillaire;
  const nephele::Frame lut = render(s);
  s.atmosphere.model = SkyModel::Reference;
  const nephele::Frame ref = render(s);
  double sum = 0.0;
  for (size_t i = 0; i < ref.color.pixels.size(); ++i) {
    const double l_ref = nephele::luminance(ref.color.pixels[i]);
    sum += std::abs(nephele::luminance(lut.color.pixels[i]) - l_ref) / std::max(l_ref, 1e-12);
  }
  return sum / double(ref.color.pixels.size());
}

struct View {
  const char* name;
  float sun_elevation_deg;
  glm::vec3 camera_m, view_dir;
};

class LutAgainstReference : public RenderTest, public ::testing::WithParamInterface<View> {};

}  // namespace

// Measured at 48 x 32: noon 0.28%, sunset 0.35%, twilight 0.64%, 30 km 0.22% (the limit is the
// issue's 2%). A multiple-scattering LUT interpolated linearly instead of in log, 32 texels
// wide, was 13% off at twilight. The brute force evaluates Hillaire's Psi_ms in place, so both
// use the isotropic model: the tables are what is checked here. (The angular field differs
// from Psi_ms by design, 3% here; it is checked against the path tracer instead, in
// validate_cli_test.cpp.)
TEST_P(LutAgainstReference, MeanRelativeErrorBelowTwoPercent) {
  const View& v = GetParam();
  Scene s = clear_sky(v.sun_elevation_deg);
  s.atmosphere.angular_multiple_scattering = false;
  s.camera.position_m = v.camera_m;
  s.camera.view_dir = v.view_dir;
  s.camera.fov_deg = 90.0f;
  s.output.width = 32;  // the reference is brute force per pixel
  s.output.height = 24;
  const double error = lut_error(s);
  std::printf("%s: LUT sky vs brute-force reference: mean relative error %.2f%%\n", v.name,
              100.0 * error);
  EXPECT_LT(error, 0.02);
}

INSTANTIATE_TEST_SUITE_P(
    Views, LutAgainstReference,
    ::testing::Values(View{"noon", 60.0f, {0, 0, 2}, {0.3f, 1.0f, 0.4f}},
                      View{"sunset", 2.0f, {0, 0, 2}, {0.2f, 1.0f, 0.15f}},
                      View{"twilight", -4.0f, {0, 0, 2}, {0.0f, 1.0f, 0.3f}},
                      View{"from30km", 30.0f, {0, 0, 30000}, {0.5f, 1.0f, -0.05f}}),
    [](const ::testing::TestParamInfo<View>& info) { return std::string(info.param.name); });

class AtmosphereTest : public RenderTest {};

// Multiple scattering brightens the clear zenith sky (measured: by 30% with the sun at 45
// degrees, 22% at -3 degrees); single scattering alone is the seed's sky, a little too dark.
TEST_F(AtmosphereTest, MultipleScatteringBrightensTheSky) {
  for (float elevation : {45.0f, -3.0f}) {
    Scene s = clear_sky(elevation);
    s.camera.view_dir = {0.0f, 0.0f, 1.0f};
    const nephele::AtmosphereTables t = nephele::compute_atmosphere_tables(s);
    const nephele::gpu::FrameParams f = nephele::make_frame_params(s, 0, nephele::sky_lights(s), t);
    const nephele::glsl::Atmosphere a = frame_atmosphere(f);
    const glm::vec3 eye(f.camera_pos_m), up(0, 0, 1), sun(f.sun_dir);
    const glm::vec3 total = nephele::glsl::sky_hillaire(a, t.transmittance_lut(), t.ms_lut(),
                                                        t.ms_field_lut(), nephele::glsl::MS_ANGULAR,
                                                        false, eye, up, sun, 64, 0.1f, glm::vec3(0))
                                .radiance;
    const glm::vec3 single =
        nephele::glsl::sky_single_scattering(a, eye, up, sun, 64, 64, 0.1f, glm::vec3(0)).radiance;
    const float gain = nephele::luminance(glm::vec4(total, 1)) / nephele::luminance(glm::vec4(single, 1));
    std::printf("sun %.0f deg: zenith (single + multiple) / single = %.2f\n", elevation, gain);
    EXPECT_GT(gain, 1.1f);
    EXPECT_LT(gain, 1.6f);
  }
}

// Ozone absorbs orange light (the Chappuis band): it keeps the twilight zenith blue.
// What the angular field changes (docs/validation.md): the light scattered more than once
// comes mostly from near the horizon, and Rayleigh's phase sends horizontal light on
// horizontally, so against Hillaire's isotropic Psi_ms the horizon brightens relative to the
// zenith (the path tracer: 1 deg up, 4-8% brighter relative to the zenith than the isotropic
// model has it), and the field's mean radiance at the ground exceeds Psi_ms (the sky light on
// the ground, which Psi_ms leaves out, reflects).
TEST_F(AtmosphereTest, TheAngularFieldBrightensTheHorizonAgainstTheZenith) {
  Scene s = clear_sky(30.0f);
  const nephele::AtmosphereTables t = nephele::compute_atmosphere_tables(s);
  const nephele::gpu::FrameParams f = nephele::make_frame_params(s, 0, nephele::sky_lights(s), t);
  const nephele::glsl::Atmosphere a = frame_atmosphere(f);
  const glm::vec3 eye(f.camera_pos_m), sun(f.sun_dir);
  const glm::vec3 horizon = glm::normalize(glm::vec3(0.0f, -1.0f, 0.0175f));  // 1 deg, away
  const auto sky = [&](int mode, glm::vec3 dir) {
    return nephele::glsl::sky_hillaire(a, t.transmittance_lut(), t.ms_lut(), t.ms_field_lut(), mode,
                                       false, eye, dir, sun, 64, 0.1f, glm::vec3(0))
        .radiance;
  };
  const glm::vec3 up(0, 0, 1);
  for (int c = 0; c < 3; ++c) {
    const double iso = sky(nephele::glsl::MS_ISOTROPIC, horizon)[c] / sky(nephele::glsl::MS_ISOTROPIC, up)[c];
    const double ang = sky(nephele::glsl::MS_ANGULAR, horizon)[c] / sky(nephele::glsl::MS_ANGULAR, up)[c];
    EXPECT_GT(ang / iso, 1.02) << c;
    EXPECT_LT(ang / iso, 1.15) << c;
  }
  const glm::vec3 ground(0.0f, 0.0f, a.planet_radius_m + 10.0f);
  const glm::vec3 psi = nephele::glsl::multiple_scattering_at(a, t.transmittance_lut(), t.ms_lut(),
                                                              false, ground, sun, 0.1f);
  const float r = glm::length(ground);
  const nephele::glsl::MsFieldCoefficients field = nephele::glsl::ms_field_read(
      t.ms_field_lut(), nephele::glsl::ms_field_unit(a, 10.0f, glm::dot(ground, sun) / r), 0);
  for (int c = 0; c < 3; ++c) EXPECT_GT(0.2820948f * field.c[0][c], psi[c]) << c;
}

TEST_F(AtmosphereTest, OzoneKeepsTheTwilightZenithBlue) {
  Scene s = clear_sky(-4.0f);
  s.camera.view_dir = {0.0f, 0.01f, 1.0f};
  s.output.width = s.output.height = 8;
  const auto blue_over_red = [&](const Scene& scene) {
    const glm::vec4 c = render(scene).color.at(4, 4);
    return c.b / c.r;
  };
  Scene no_ozone = s;
  no_ozone.atmosphere.ozone_absorption_per_m = glm::vec3(0.0f);
  const float with = blue_over_red(s), without = blue_over_red(no_ozone);
  std::printf("twilight zenith b/r: with ozone %.2f, without %.2f\n", with, without);
  EXPECT_GT(with, 1.15f * without);
}

// From the ground to space: at 100 km and 400 km, looking at the limb, the planet below is lit,
// a bright band of air lies along the limb and space above it is dark.
TEST_F(AtmosphereTest, LimbFromSpace) {
  for (float altitude_m : {100e3f, 400e3f}) {
    Scene s = clear_sky(30.0f);
    s.output.width = 64;
    s.output.height = 96;
    s.camera.position_m = {0.0f, 0.0f, altitude_m};
    const float dip = std::acos(6360e3f / (6360e3f + altitude_m));  // the limb's depression
    s.camera.view_dir = {0.0f, std::cos(dip), -std::sin(dip)};
    s.camera.fov_deg = 20.0f;
    const nephele::Frame frame = render(s);
    // The middle column: space at the top, the limb in the middle, the ground at the bottom.
    float space = 0.0f, band = 0.0f, ground = 0.0f;
    for (int y = 0; y < s.output.height; ++y) {
      const float l = float(nephele::luminance(frame.color.at(32, y)));
      ASSERT_TRUE(std::isfinite(l)) << "row " << y;
      if (y < 8) space = std::max(space, l);
      if (y > 30 && y < 66) band = std::max(band, l);
      if (y > 88) ground = std::max(ground, l);
    }
    std::printf("%.0f km: space %.3g, limb %.3g, ground %.3g\n", altitude_m / 1000.0f, space,
                band, ground);
    EXPECT_LT(space, 0.05f * band);
    EXPECT_GT(ground, 0.0f);
    EXPECT_GT(band, ground);
  }
}

// atmosphere.model = preetham: the sky above the horizon is Preetham's analytic sky (the
// function of preetham_inc.glsl compiled as C++, times the sun's illuminance).
TEST_F(AtmosphereTest, PreethamModelDrawsPreethamsSky) {
  Scene s = clear_sky(40.0f);
  s.atmosphere.model = SkyModel::Preetham;
  s.atmosphere.turbidity = 3.0f;
  s.camera.view_dir = {0.6f, 0.3f, 0.5f};
  s.output.width = 40;
  s.output.height = 30;
  const nephele::Frame frame = render(s);
  const nephele::gpu::FrameParams f = nephele::make_frame_params(s, 0);
  const nephele::CameraBasis basis = nephele::camera_basis(s.camera.view_dir);
  double error = 0.0;
  int n = 0;
  for (int y = 0; y < s.output.height; y += 3)
    for (int x = 0; x < s.output.width; x += 3) {
      const glm::vec3 dir = nephele::glsl::camera_ray(basis.forward, basis.right, basis.up,
                                                      f.camera_pos_m.w, f.camera_forward.w, float(x),
                                                      float(y), 40.0f, 30.0f);
      const glm::vec3 expected = nephele::glsl::preetham_sky_radiance(
                                     3.0f, dir, glm::vec3(f.sun_dir), glm::vec3(0, 0, 1)) *
                                 s.sun.illuminance_lux;
      const float got = nephele::luminance(frame.color.at(x, y));
      error += std::abs(got - nephele::luminance(glm::vec4(expected, 1))) /
               nephele::luminance(glm::vec4(expected, 1));
      ++n;
    }
  std::printf("Preetham sky as drawn vs the function: mean error %.2f%%\n", 100.0 * error / n);
  EXPECT_LT(error / n, 0.02);
  // And it is not the Hillaire sky: the two models differ by more than that here.
  s.atmosphere.model = SkyModel::Hillaire;
  EXPECT_GT(nephele::luminance_error(render(s).color, frame.color), 0.05);
}

// In twilight (sun 12 degrees down) the ground is lit by the sky alone: darker than the sky just
// above the horizon. (Points at the end of ground rays, a rounding below the surface, once saw
// the sun through the planet and glowed orange.)
TEST_F(AtmosphereTest, TwilightGroundIsDarkerThanTheSkyAboveIt) {
  Scene s = clear_sky(-12.0f);
  s.camera.view_dir = {0.0f, 1.0f, 0.0f};
  s.camera.fov_deg = 20.0f;
  const nephele::Frame frame = render(s);
  double above = 0.0, below = 0.0;
  for (int x = 0; x < s.output.width; ++x) {
    above += nephele::luminance(frame.color.at(x, s.output.height / 2 - 3));
    below += nephele::luminance(frame.color.at(x, s.output.height / 2 + 3));
  }
  EXPECT_LT(below, 0.2 * above);
}

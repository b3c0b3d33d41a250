// The reference path tracer on the planet (path_trace.comp with PLANET 1) against closed forms:
// the sun seen straight up through a clear sky, dimmed by the transmittance of the
// atmosphere's exponential and tent profiles integrated exactly; and the clear sky's single
// scattering against the numerical integral of the sky model (glsl::sky_single_scattering),
// looking up, towards the sun and away from it near the horizon.
#include <gtest/gtest.h>

#include <cmath>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "frame_atmosphere.h"
#include "render/glsl.h"
#include "render_fixture.h"

namespace {

using nephele::Scene;

// A clear sky over a black ground, the camera 2 m up, 8 x 8 pixels.
Scene clear_sky(glm::vec3 view_dir, float fov_deg, glm::vec3 sun) {
  Scene s;
  s.clouds.coverage = 0.0f;
  s.high_clouds.coverage = 0.0f;
  s.cirrus.coverage = 0.0f;
  s.atmosphere.ground_albedo = 0.0f;
  s.sun.direction = sun;
  s.camera.position_m = {0.0f, 0.0f, 2.0f};
  s.camera.view_dir = view_dir;
  s.camera.fov_deg = fov_deg;
  s.output.width = 8;
  s.output.height = 8;
  return s;
}

// The image's mean per channel, and its standard error (from the pixels' variances).
struct Mean {
  glm::dvec3 value{0.0}, sigma{0.0};
};
Mean image_mean(const nephele::ReferenceImage& image) {
  Mean m;
  const double n = double(image.mean.pixels.size());
  for (size_t i = 0; i < image.mean.pixels.size(); ++i) {
    m.value += glm::dvec3(image.mean.pixels[i]) / n;
    m.sigma += glm::dvec3(image.variance.pixels[i]) / (n * n);
  }
  m.sigma = glm::sqrt(m.sigma);
  return m;
}

// The directions through the pixels' centres.
template <class F>
glm::dvec3 mean_over_pixels(const Scene& s, F f) {
  const nephele::CameraBasis basis = nephele::camera_basis(s.camera.view_dir);
  const float tan_half = std::tan(glm::radians(0.5f * s.camera.fov_deg));
  glm::dvec3 sum(0.0);
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x)
      sum += f(nephele::glsl::camera_ray(basis.forward, basis.right, basis.up, tan_half, 1.0f,
                                         float(x), float(y), float(s.output.width),
                                         float(s.output.height)));
  return sum / double(s.output.width * s.output.height);
}

class PlanetReferenceTest : public RenderTest {};

// Straight up at a sun in the zenith (a field of view inside its disk): what reaches the
// camera is the disk's radiance times exp(-tau), tau = sigma_R H_R (e^(-z/H_R) - e^(-Z/H_R))
// + sigma_M H_M (e^(-z/H_M) - e^(-Z/H_M)) + sigma_O w (the ozone tent's area; camera at z,
// top of the atmosphere at Z). The sky's own light there is a millionth of the disk's.
TEST_F(PlanetReferenceTest, TheSunStraightUpIsDimmedByTheClosedFormTransmittance) {
  Scene s = clear_sky({0.0f, 0.0f, 1.0f}, 0.05f, {0.0f, 0.0f, 1.0f});
  s.output.width = 32;
  s.output.height = 32;
  nephele::ReferenceOptions options;
  options.spp = 1500;
  options.max_bounces = 0;
  const nephele::ReferenceImage image = shared_renderer().render_reference(s, options);
  ASSERT_EQ(image.cut_loops, 0);
  const Mean got = image_mean(image);

  const nephele::AtmosphereParams& a = s.atmosphere;
  const double z = s.camera.position_m.z, top = a.atmosphere_height_km * 1000.0;
  const auto layer = [&](double h) { return h * (std::exp(-z / h) - std::exp(-top / h)); };
  const glm::dvec3 tau = glm::dvec3(a.rayleigh_scattering_per_m) * layer(a.rayleigh_scale_height_m) +
                         double(a.mie_extinction_per_m) * layer(a.mie_scale_height_m) +
                         glm::dvec3(a.ozone_absorption_per_m) * double(a.ozone_half_width_m);
  const double e = nephele::key_light(s).illuminance;
  const double cos_radius = std::cos(glm::radians(double(s.sun.disk_angular_radius_deg)));
  const glm::dvec3 disk = mean_over_pixels(s, [&](glm::vec3 dir) {
    return glm::dvec3(nephele::glsl::sun_disk(dir, glm::vec3(0.0f, 0.0f, 1.0f), float(cos_radius)));
  });
  for (int c = 0; c < 3; ++c) {
    const double expected = e * disk[c] * std::exp(-tau[c]);
    std::printf("channel %d: path traced %.6g +- %.2g, closed form %.6g (tau %.4f)\n", c,
                got.value[c], got.sigma[c], expected, tau[c]);
    EXPECT_NEAR(got.value[c], expected, 3.0 * got.sigma[c] + 0.001 * expected) << "channel " << c;
    EXPECT_LT(got.sigma[c], 0.0015 * expected) << "channel " << c;
  }
}

// Single scattering (max_bounces 0) of a clear sky with the sun 30 deg up in the south, looking
// up, 10 deg up towards the sun and 5 deg up away from it, against the sky model's integral of
// the same medium and phase functions (256 steps along the view, 64 towards the sun).
TEST_F(PlanetReferenceTest, ClearSkySingleScatteringMatchesTheIntegral) {
  const glm::vec3 sun = nephele::sun_direction_from_angles(30.0f, 180.0f);
  for (auto [elevation_deg, azimuth_deg] : {std::pair{90.0f, 0.0f}, {10.0f, 180.0f}, {5.0f, 0.0f}}) {
    const glm::vec3 view = nephele::sun_direction_from_angles(elevation_deg, azimuth_deg);
    const Scene s = clear_sky(view, 1.0f, sun);
    nephele::ReferenceOptions options;
    options.spp = 1500;
    options.max_bounces = 0;
    const nephele::ReferenceImage image = shared_renderer().render_reference(s, options);
    ASSERT_EQ(image.cut_loops, 0);
    const Mean got = image_mean(image);
    const nephele::gpu::FrameParams f = nephele::make_frame_params(s, 0);
    const nephele::glsl::Atmosphere atmosphere = frame_atmosphere(f);
    const glm::vec3 eye(f.camera_pos_m);
    const double e = nephele::key_light(s).illuminance;
    const glm::dvec3 exact = mean_over_pixels(s, [&](glm::vec3 dir) {
      return glm::dvec3(nephele::glsl::sky_single_scattering(atmosphere, eye, dir, sun, 256, 64,
                                                             0.0f, glm::vec3(0.0f))
                            .radiance) * e;
    });
    for (int c = 0; c < 3; ++c) {
      std::printf("elevation %.0f azimuth %.0f channel %d: path traced %.5g +- %.2g, integral %.5g\n",
                  elevation_deg, azimuth_deg, c, got.value[c], got.sigma[c], exact[c]);
      EXPECT_NEAR(got.value[c], exact[c], 3.0 * got.sigma[c] + 0.01 * exact[c])
          << "elevation " << elevation_deg << " channel " << c;
      EXPECT_LT(got.sigma[c], 0.03 * exact[c]) << "elevation " << elevation_deg << " channel " << c;
    }
  }
}

// The majorant grid's image and one majorant per shell's (another seed) agree: their means per
// channel within 3 standard errors and 1%.
void expect_same_mean(const nephele::ReferenceImage& grid, const nephele::ReferenceImage& flat) {
  const Mean a = image_mean(grid), b = image_mean(flat);
  for (int c = 0; c < 3; ++c) {
    std::printf("channel %d: grid %.5g +- %.2g, flat %.5g +- %.2g\n", c, a.value[c], a.sigma[c],
                b.value[c], b.sigma[c]);
    EXPECT_NEAR(a.value[c], b.value[c],
                3.0 * std::hypot(a.sigma[c], b.sigma[c]) + 0.01 * b.value[c])
        << "channel " << c;
  }
}

// Thin cumulus: with the noise clouds' majorant grid and without it the same image within the
// noise, and no tentative collision ever finds the extinction above the grid's bound. (Thin,
// because on lavapipe a path's null collisions must stay few: with thicker clouds the flat
// majorant's image came out darker the more null collisions it made, lavapipe's loop limit
// cutting the tracking short, until the paths carried over between passes; docs/path-tracer.md,
// "Paths that carry over between passes", and the thick clouds' test below.)
TEST_F(PlanetReferenceTest, TheNoiseCloudsMajorantGridIsNeverExceededAndChangesNothing) {
  Scene s = nephele::load_preset("default");
  s.output.width = 16;
  s.output.height = 12;
  s.camera.view_dir = {0.2f, 1.0f, 0.5f};
  s.clouds.optics = "seed";
  s.clouds.density = 0.05f;
  s.clouds.extinction_per_m = 0.05f;
  nephele::ReferenceOptions options;
  options.spp = 150;
  const nephele::ReferenceImage grid = shared_renderer().render_reference(s, options);
  options.majorant_grid = nephele::MajorantGrid::kNone;
  options.seed = 2;
  const nephele::ReferenceImage flat = shared_renderer().render_reference(s, options);
  std::printf("with the grid %.1f s, without %.1f s\n", grid.seconds, flat.seconds);
  for (const nephele::ReferenceImage* image : {&grid, &flat}) {
    EXPECT_EQ(image->cut_loops, 0);
    EXPECT_EQ(image->majorant_violations, 0);
  }
  expect_same_mean(grid, flat);
}

// Thick clouds of droplets (the default view, bounces to 6): the paths carry over from pass to
// pass, so lavapipe's loop limit cuts nothing, the image does not depend on where the passes
// cut the paths, and it does not depend on the majorant. With nested loops in one pass, 2.3%
// of the samples had their tracking cut and the grid's image came out 5% darker than one
// majorant per shell's, 5 standard errors apart. At 12 samples a pixel the means' standard
// errors are 6% (droplets at their real depths since stop 58): the pixels' equality across
// pass lengths and the counters are the strict checks, the means' agreement a loose one.
TEST_F(PlanetReferenceTest, ThickCloudsAreTracedWhereverThePassesEndAndWhateverTheMajorant) {
  Scene s = nephele::load_preset("default");
  s.output.width = 16;
  s.output.height = 12;
  s.clouds.optics = "droplets";
  nephele::ReferenceOptions options;
  options.spp = 12;
  options.max_bounces = 6;
  const nephele::ReferenceImage grid = shared_renderer().render_reference(s, options);
  options.iterations_per_pass = 77;
  const nephele::ReferenceImage short_passes = shared_renderer().render_reference(s, options);
  options.iterations_per_pass = 0;
  options.majorant_grid = nephele::MajorantGrid::kNone;
  options.seed = 2;
  const nephele::ReferenceImage flat = shared_renderer().render_reference(s, options);
  for (const nephele::ReferenceImage* image : {&grid, &short_passes, &flat}) {
    EXPECT_EQ(image->cut_loops, 0);
    EXPECT_EQ(image->majorant_violations, 0);
  }
  for (size_t i = 0; i < grid.mean.pixels.size(); ++i)
    ASSERT_EQ(short_passes.mean.pixels[i], grid.mean.pixels[i]) << "pixel " << i;
  expect_same_mean(grid, flat);
}

// The default scene at 8 x 6 looking up into its clouds, of droplets: the seed's clouds (tau in
// the hundreds) have paths of tens of thousands of steps, which make a test slow without
// making it stricter.
Scene small_droplet_view() {
  Scene s = nephele::load_preset("default");
  s.output.width = 8;
  s.output.height = 6;
  s.clouds.optics = "droplets";
  s.camera.view_dir = {0.2f, 1.0f, 0.5f};
  return s;
}

// On the planet the samples take the colour channels in turn: spread over invocations they are
// the same samples, and a pass that is not a multiple of three runs on until every channel has
// as many.
TEST_F(PlanetReferenceTest, SpreadingSamplesOverInvocationsKeepsTheChannelsEven) {
  const Scene s = small_droplet_view();
  nephele::ReferenceOptions options;
  options.spp = 6;
  options.invocations_per_pixel = 1;
  const nephele::ReferenceImage one = shared_renderer().render_reference(s, options);
  options.invocations_per_pixel = 3;
  const nephele::ReferenceImage three = shared_renderer().render_reference(s, options);
  EXPECT_EQ(three.spp, 6);
  for (size_t i = 0; i < one.mean.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(three.mean.pixels[i][c], one.mean.pixels[i][c],
                  1e-5 * std::abs(one.mean.pixels[i][c]) + 1e-7)
          << "pixel " << i;
  options.invocations_per_pixel = 4;  // 4, 8, 12: the first multiple of 3 at or past 6
  EXPECT_EQ(shared_renderer().render_reference(s, options).spp, 12);
}

// A GPU's shader (path_trace_gpu.comp, without the undo of an iteration the loop limit cut
// short, which NVIDIA's driver 580 cannot compile) traces the same samples as a CPU device's
// where no pass is cut: passes of 64 iterations stay far under lavapipe's 65535.
TEST_F(PlanetReferenceTest, TheGpusShaderTracesTheSameSamples) {
  const Scene s = small_droplet_view();
  nephele::ReferenceOptions options;
  options.spp = 6;
  options.iterations_per_pass = 64;
  options.undo_cut_iteration = 1;
  const nephele::ReferenceImage cpu = shared_renderer().render_reference(s, options);
  options.undo_cut_iteration = 0;
  const nephele::ReferenceImage gpu = shared_renderer().render_reference(s, options);
  double lit = 0.0;
  for (size_t i = 0; i < cpu.mean.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      lit += cpu.mean.pixels[i][c];
      EXPECT_EQ(gpu.mean.pixels[i][c], cpu.mean.pixels[i][c]) << "pixel " << i;
    }
  EXPECT_GT(lit, 0.0);
  options.undo_cut_iteration = 2;
  EXPECT_THROW(shared_renderer().render_reference(s, options), nephele::InputError);
}

// Clouds of droplets (clouds.optics = "droplets"): the genera's shares of cloud_shape.z and the
// voxel clouds' keep every majorant a bound, and no path is lost on the way.
TEST_F(PlanetReferenceTest, DropletCloudsStayUnderTheirMajorants) {
  for (const char* preset : {"default", "voxel-cumulus"}) {
    Scene s = nephele::load_preset(preset);
    s.clouds.optics = "droplets";
    s.clouds.phase_g_forward = Scene().clouds.phase_g_forward;
    s.clouds.phase_g_backward = Scene().clouds.phase_g_backward;
    s.clouds.phase_lobe_weight = Scene().clouds.phase_lobe_weight;
    s.output.width = 16;
    s.output.height = 12;
    s.camera.view_dir = {0.2f, 1.0f, 0.5f};
    nephele::ReferenceOptions options;
    options.spp = 9;
    const nephele::ReferenceImage image = shared_renderer().render_reference(s, options);
    EXPECT_EQ(image.majorant_violations, 0) << preset;
    EXPECT_EQ(image.cut_loops, 0) << preset;
    double sum = 0.0;
    for (const glm::vec4& p : image.mean.pixels) sum += p.g;
    EXPECT_GT(sum, 0.0) << preset;
  }
}

// What the tracer cannot render is refused with one line naming the parameter.
TEST_F(PlanetReferenceTest, ScenesItCannotTraceAreRefused) {
  Scene s = clear_sky({0.0f, 1.0f, 0.2f}, 60.0f, {0.0f, 0.6f, 0.8f});
  s.cirrus.coverage = 0.3f;
  try {
    shared_renderer().render_reference(s);
    ADD_FAILURE() << "cirrus accepted";
  } catch (const nephele::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cirrus.coverage"), std::string::npos) << e.what();
  }
  s.cirrus.coverage = 0.0f;
  s.conditions.mode = nephele::ConditionsMode::Artist;
  EXPECT_THROW(shared_renderer().render_reference(s), nephele::InputError);
}

}  // namespace

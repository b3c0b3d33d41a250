// The classical cloud models drawn (classic_clouds.comp, seed 004, issue 23): each pixel of
// the cloud buffer against the model's closed form for that pixel's ray.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "render/glsl.h"
#include "render/modules/classic_clouds/classic_clouds.h"
#include "render/modules/metaball_clouds/metaball_clouds.h"
#include "render_fixture.h"

namespace nephele {
namespace {

// From the ground looking up into the [clouds] layer, 1.5-4 km, the sun high in the south-east;
// the cloud buffer at the image's resolution.
Scene blinn_scene() {
  Scene s = load_preset("default");
  s.output.width = 32;
  s.output.height = 24;
  s.output.auto_exposure = false;
  s.quality.cloud_downsample = 1;
  s.camera.view_dir = glm::vec3(0.0f, 0.5f, 1.0f);
  s.camera.fov_deg = 60.0f;
  s.sun.direction = glm::normalize(glm::vec3(0.5f, -0.4f, 0.75f));
  s.clouds.model = CloudModel::Blinn;
  s.classic.blinn_particles_per_m3 = 3.0e5f;  // tau = 0.236
  return s;
}

struct Ray {
  glm::vec3 dir;
  double path_m;   // through the layer
  glm::vec3 up;    // at the path's middle
};

Ray ray_of(const Scene& s, int x, int y) {
  const CameraBasis b = camera_basis(s.camera);
  const float tan_half = std::tan(glm::radians(s.camera.fov_deg) * 0.5f);
  const float aspect = float(s.output.width) / float(s.output.height);
  Ray r;
  r.dir = glsl::camera_ray(b.forward, b.right, b.up, tan_half, aspect, float(x), float(y),
                           float(s.output.width), float(s.output.height));
  const double planet_m = s.atmosphere.planet_radius_km * 1000.0;
  const glm::dvec3 eye(s.camera.position_m.x, s.camera.position_m.y, planet_m + s.camera.position_m.z);
  const glm::dvec3 d(r.dir);
  const auto exit_at = [&](double radius_m) {  // from inside the sphere
    const double b2 = glm::dot(eye, d), c = glm::dot(eye, eye) - radius_m * radius_m;
    return -b2 + std::sqrt(b2 * b2 - c);
  };
  const double t0 = exit_at(planet_m + s.clouds.bottom_altitude_m);
  const double t1 = exit_at(planet_m + s.clouds.top_altitude_m);
  r.path_m = t1 - t0;
  r.up = glm::vec3(glm::normalize(eye + d * (0.5 * (t0 + t1))));
  return r;
}

class ClassicRenderTest : public RenderTest {};

// Blinn's slab from below, the sun above it: the transmittance along each ray is e^(-tau/mu),
// mu = thickness / path; the light is Blinn's transmitted single scattering omega phi(alpha)
// mu0/(mu - mu0)(e^(-tau/mu) - e^(-tau/mu0)) times the sunlight / 4 pi, dimmed by the air in
// front: radiance over the closed form is nearly the same for every pixel (the air's
// transmittance differs by a few percent over these rays), and exactly the same ratio between
// two renders, where the air cancels: each phase function against Henyey-Greenstein's, and
// the seed's printing of B and Tr against the original.
TEST_F(ClassicRenderTest, BlinnsLayerIsItsClosedFormPixelByPixel) {
  Scene s = blinn_scene();
  const float thickness_m = s.clouds.top_altitude_m - s.clouds.bottom_altitude_m;
  const float tau = glsl::blinn_optical_depth(s.classic.blinn_particles_per_m3,
                                              s.classic.blinn_particle_radius_m, thickness_m);
  // The closed form for each pixel, with the scene's phase and printing.
  const auto closed_form = [&](const Scene& scene) {
    std::vector<glm::vec2> out;
    const int kind = blinn_phase_kind(scene.classic.blinn_phase);
    const bool seed = scene.classic.seed_formulas;
    for (int y = 0; y < scene.output.height; ++y)
      for (int x = 0; x < scene.output.width; ++x) {
        const Ray r = ray_of(scene, x, y);
        const float mu = float(thickness_m / r.path_m);
        const float mu0 = glm::dot(r.up, scene.sun.direction);
        const float cos_alpha = -glm::dot(r.dir, scene.sun.direction);
        const float x_param = scene.classic.blinn_phase_x;
        out.push_back(glsl::blinn_layer(tau, mu, mu0, false, scene.classic.blinn_albedo,
                                        glsl::blinn_phase(kind, x_param, cos_alpha, seed),
                                        glsl::blinn_phase(kind, x_param, -1.0f, seed), seed));
      }
    return out;
  };
  const Frame reference = render(s);
  const std::vector<glm::vec2> reference_expected = closed_form(s);
  double lo = 1e30, hi = 0.0;
  for (size_t i = 0; i < reference_expected.size(); ++i) {
    const double ratio = reference.clouds.pixels[i].g / reference_expected[i].x;
    lo = std::min(lo, ratio);
    hi = std::max(hi, ratio);
  }
  std::printf("hg: radiance / closed form in [%.4g, %.4g]\n", lo, hi);
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi / lo, 1.06);
  const std::vector<std::pair<std::string, bool>> cases = {
      {"anisotropic", false}, {"lambert", false}, {"rayleigh", false}, {"hg", true}};
  for (const auto& [phase, seed] : cases) {
    {
      s.classic.blinn_phase = phase;
      s.classic.blinn_phase_x = phase == "anisotropic" ? 0.8f : -0.6f;
      s.classic.seed_formulas = seed;
      const Frame f = render(s);
      ASSERT_EQ(f.clouds.width, s.output.width);
      const std::vector<glm::vec2> expected = closed_form(s);
      double worst_tr = 0.0, worst_ratio = 0.0;
      for (size_t i = 0; i < expected.size(); ++i) {
        const glm::vec4 c = f.clouds.pixels[i];
        worst_tr = std::max(worst_tr, double(std::abs(c.a - std::min(expected[i].y, 1.0f))));
        const double measured = c.g / reference.clouds.pixels[i].g;
        const double predicted = expected[i].x / reference_expected[i].x;
        worst_ratio = std::max(worst_ratio, std::abs(measured / predicted - 1.0));
      }
      std::printf("%s%s: worst transmittance error %.2e, worst ratio to hg's error %.2e\n",
                  phase.c_str(), seed ? " (seed's form)" : "", worst_tr, worst_ratio);
      EXPECT_LT(worst_tr, 2e-3) << phase << seed;
      EXPECT_LT(worst_ratio, 2e-3) << phase << seed;
    }
  }
  // No particles: a clear sky, the same as nephele's with no clouds.
  s.classic.blinn_particles_per_m3 = 0.0f;
  const Frame none = render(s);
  for (const glm::vec4& c : none.clouds.pixels) ASSERT_EQ(c, glm::vec4(0.0f, 0.0f, 0.0f, 1.0f));
}

}  // namespace
}  // namespace nephele

namespace nephele {
namespace {

class GardnerRenderTest : public RenderTest {};

// Gardner's stratus from below: every pixel's opacity is his translucency of his texture T at
// the point where the ray meets the sky plane (evaluated here by the same functions on the
// CPU, whose spectrum classic_test.cpp checks), and with the texture alone shading it (f = s
// = 0, t = 1, the plane opaque) the light is T times the same sunlight everywhere.
TEST_F(GardnerRenderTest, TheSkyPlaneShowsHisTexturePixelByPixel) {
  Scene s = blinn_scene();
  s.clouds.model = CloudModel::Gardner;
  s.classic.gardner_clouds = "stratus";
  s.classic.gardner_range = 0.3f;
  const Frame f = render(s);
  const float bottom_m = s.clouds.bottom_altitude_m;
  const CameraBasis b = camera_basis(s.camera);
  const float tan_half = std::tan(glm::radians(s.camera.fov_deg) * 0.5f);
  const float aspect = float(s.output.width) / float(s.output.height);
  float sum_c = 1.0f, c = 1.0f;
  for (int i = 1; i < s.classic.gardner_terms; ++i) sum_c += (c *= 0.707f);
  const float f1 = 2.0f * glsl::PI / s.classic.gardner_period_m;
  const auto texture_at = [&](int x, int y) {
    const glm::vec3 dir = glsl::camera_ray(b.forward, b.right, b.up, tan_half, aspect, float(x),
                                           float(y), float(s.output.width), float(s.output.height));
    const glm::vec3 p = s.camera.position_m + dir * ((bottom_m - s.camera.position_m.z) / dir.z);
    return glsl::gardner_texture(p, glm::vec2(f1), sum_c, 1.0f / (4.0f * sum_c * sum_c),
                                 s.classic.gardner_terms, false);
  };
  double worst = 0.0;
  int clear = 0, opaque = 0;
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      const float tr = glsl::gardner_translucency(texture_at(x, y), s.classic.gardner_t1,
                                                  s.classic.gardner_t2, s.classic.gardner_range, 1.0f);
      const float a = f.clouds.at(x, y).a;
      worst = std::max(worst, double(std::abs(a - (1.0f - tr))));
      clear += a > 0.99f;
      opaque += a < 0.01f;
    }
  std::printf("stratus: worst opacity error %.2e, %d clear and %d opaque of %d pixels\n", worst,
              clear, opaque, s.output.width * s.output.height);
  EXPECT_LT(worst, 5e-3);
  EXPECT_GT(clear, 20);  // a broken deck: both
  EXPECT_GT(opaque, 20);
  // The texture alone: light over T the same for every pixel (the air's few percent aside).
  s.classic.gardner_t1 = 0.0f;
  s.classic.gardner_range = 1e-6f;
  s.classic.gardner_ambient = s.classic.gardner_specular = 0.0f;
  s.classic.gardner_texture = 1.0f;
  const Frame lit = render(s);
  double lo = 1e30, hi = 0.0;
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      const float t = texture_at(x, y);
      if (t < 0.05f) continue;
      const double ratio = lit.clouds.at(x, y).g / t;
      lo = std::min(lo, ratio);
      hi = std::max(hi, ratio);
    }
  EXPECT_GT(lo, 0.0);
  EXPECT_LT(hi / lo, 1.06);
}

double mean_opacity(const Frame& f) {
  double opacity = 0.0;
  for (const glm::vec4& p : f.clouds.pixels) opacity += 1.0 - p.a;
  return opacity / double(f.clouds.pixels.size());
}

// Cumulus, his ellipsoids and his impressionistic objects: no cloud at coverage 0, more cloud
// with more coverage.
TEST_F(GardnerRenderTest, CumulusCoverFollowsTheCoverage) {
  Scene s = blinn_scene();
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, 0.25f);
  for (const CloudModel model : {CloudModel::Gardner, CloudModel::GardnerQuadrics}) {
    s.clouds.model = model;
    double previous = -1.0;
    for (const float coverage : {0.0f, 0.3f, 0.8f}) {
      s.clouds.coverage = coverage;
      const double opacity = mean_opacity(render(s));
      std::printf("%s, coverage %.1f: mean opacity %.3f\n", to_string(model), coverage, opacity);
      if (coverage == 0.0f) EXPECT_EQ(opacity, 0.0);
      EXPECT_GT(opacity, previous + (coverage > 0.0f ? 0.02 : -1.0));
      previous = opacity;
    }
  }
}

// Cirrus: his plane at the cirrus's altitude, thin (never more than 0.6 opaque) and streaked:
// the texture varies far more across the streaks (north-south) than along them.
TEST_F(GardnerRenderTest, CirrusIsAThinStreakedPlaneAtItsAltitude) {
  Scene s = blinn_scene();
  s.clouds.model = CloudModel::Gardner;
  s.classic.gardner_clouds = "cirrus";
  s.camera.view_dir = glm::vec3(0.0f, 0.0f, 1.0f);  // straight up: x east, y north in the image
  s.camera.fov_deg = 90.0f;
  const Frame f = render(s);
  double along = 0.0, across = 0.0, max_opacity = 0.0;
  for (int y = 1; y < s.output.height; ++y)
    for (int x = 1; x < s.output.width; ++x) {
      const auto at = [&](int i, int j) { return f.clouds.pixels[size_t(j * s.output.width + i)].a; };
      max_opacity = std::max(max_opacity, 1.0 - at(x, y));
      along += std::abs(at(x, y) - at(x - 1, y));
      across += std::abs(at(x, y) - at(x, y - 1));
    }
  std::printf("cirrus: opacity up to %.3f, change along the streaks %.3f, across %.3f\n", max_opacity,
              along, across);
  EXPECT_GT(max_opacity, 0.2);
  EXPECT_LE(max_opacity, 0.6 + 1e-4);
  EXPECT_GT(across, 2.0 * along);
}

}  // namespace
}  // namespace nephele

namespace nephele {
namespace {

class KajiyaRenderTest : public RenderTest {};

// Kajiya and Von Herzen's two passes (the light array, Romberg along the eye ray) against a
// brute-force march of the same density and single scattering (1024 samples, the light marched
// at each), looking straight up so that every sample lies within a light array of 3 km about
// the camera (37.5 m cells across, 78 m through the layer), the sun 49 deg high: at 10 levels
// (1025 samples) the light within 4% (2.75% measured; 3.1% at 7 levels) and the transmittance
// within 0.001; closer with more levels. The array's cells set the floor: a lower sun crosses
// more of them (20 deg: 4.6%), the default 150 km array (1.9 km cells) leaves 14%.
TEST_F(KajiyaRenderTest, RombergOnTheLightArrayMatchesTheBruteForceMarch) {
  Scene s = blinn_scene();
  s.camera.view_dir = glm::vec3(0.0f, 0.0f, 1.0f);
  s.camera.fov_deg = 40.0f;
  s.clouds.model = CloudModel::Kajiya;
  s.classic.kajiya_reference = true;
  const Frame reference = render(s);
  s.classic.kajiya_reference = false;
  s.quality.light_volume_km = 3;
  double previous = 1e30;
  for (const int levels : {2, 7, 10}) {
    s.classic.kajiya_levels = levels;
    const Frame f = render(s);
    double radiance_error = 0.0, radiance_sum = 0.0, transmittance_error = 0.0;
    int cloudy = 0;
    for (size_t i = 0; i < f.clouds.pixels.size(); ++i) {
      const glm::vec4 a = f.clouds.pixels[i], b = reference.clouds.pixels[i];
      transmittance_error += std::abs(a.a - b.a);
      if (b.a > 0.9f) continue;
      ++cloudy;
      radiance_error += std::abs(a.g - b.g);
      radiance_sum += b.g;
    }
    const double relative = radiance_error / std::max(radiance_sum, 1e-30);
    transmittance_error /= double(f.clouds.pixels.size());
    std::printf("levels %d: %d cloudy pixels, radiance off by %.2f%%, transmittance by %.4f\n",
                levels, cloudy, 100.0 * relative, transmittance_error);
    EXPECT_GT(cloudy, int(f.clouds.pixels.size()) / 10);
    if (levels == 10) {
      EXPECT_LT(relative, 0.04);
      EXPECT_LT(transmittance_error, 0.001);
    }
    EXPECT_LT(relative, previous);
    previous = relative;
  }
}

}  // namespace
}  // namespace nephele

namespace nephele {
namespace {

class NishitaRenderTest : public RenderTest {};

// One cumulus of 60 metaballs 6 km north of a camera on the ground looking at it, the sun high
// in the south-east behind the camera; a 32-voxel grid.
Scene nishita_scene() {
  Scene s = load_preset("default");
  s.output.width = 32;
  s.output.height = 24;
  s.output.auto_exposure = false;
  s.quality.cloud_downsample = 1;
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, 0.3f);
  s.camera.fov_deg = 40.0f;
  s.sun.direction = glm::normalize(glm::vec3(0.4f, -0.6f, 0.7f));
  s.clouds.model = CloudModel::Nishita;
  s.classic.nishita_metaballs = 60;
  s.classic.nishita_clouds = 1;
  s.classic.nishita_extent_m = 3000.0f;
  s.classic.nishita_center_m = glm::vec2(0.0f, 6000.0f);
  s.classic.nishita_voxels = 32;
  return s;
}

// The cloud is where its balls are: opaque where a pixel's ray passes near a ball's centre
// (within 0.4 of its radius), clear where it passes every ball by more than two voxels.
TEST_F(NishitaRenderTest, TheCloudStandsWhereItsMetaballsAre) {
  const Scene s = nishita_scene();
  const std::vector<Metaball> balls = make_cumulus_metaballs(s, s.noise_seed);
  const MetaballGrid grid = voxelize_metaballs(balls, s.classic.nishita_voxels);
  const Frame f = render(s);
  const CameraBasis b = camera_basis(s.camera);
  const float tan_half = std::tan(glm::radians(s.camera.fov_deg) * 0.5f);
  int cores = 0, clear = 0;
  for (int y = 0; y < s.output.height; ++y)
    for (int x = 0; x < s.output.width; ++x) {
      const glm::vec3 d = glsl::camera_ray(b.forward, b.right, b.up, tan_half, 32.0f / 24.0f,
                                           float(x), float(y), 32.0f, 24.0f);
      float nearest = 1e30f, margin = 1e30f;  // in radii; beyond the surface (m)
      for (const Metaball& ball : balls) {
        const glm::vec3 to = ball.centre_m - s.camera.position_m;
        const float miss_m = glm::length(to - d * glm::dot(to, d));
        nearest = std::min(nearest, miss_m / ball.radius_m);
        margin = std::min(margin, miss_m - ball.radius_m);
      }
      const float transmittance = f.clouds.pixels[size_t(y * s.output.width + x)].a;
      if (nearest < 0.4f) {
        ++cores;
        EXPECT_LT(transmittance, 0.3f) << "pixel " << x << ", " << y;
      } else if (margin > 2.0f * grid.voxel_m) {
        ++clear;
        EXPECT_GT(transmittance, 0.999f) << "pixel " << x << ", " << y;
      }
    }
  std::printf("%d pixels through balls' cores, %d clear\n", cores, clear);
  EXPECT_GT(cores, 20);
  EXPECT_GT(clear, 200);
}

// Each of the paper's lights adds to the cloud: the second order to the first, the sky's light
// to both; the second order adds a share of the first that the physics bounds (more than a
// tenth, less than double: higher orders are left out).
TEST_F(NishitaRenderTest, TheSecondOrderAndTheSkyAddLight) {
  Scene s = nishita_scene();
  const auto cloud_light = [&](int order, bool sky) {
    s.classic.nishita_order = order;
    s.classic.nishita_sky_light = sky;
    const Frame f = render(s);
    double sum = 0.0;
    for (const glm::vec4& p : f.clouds.pixels) sum += p.r + p.g + p.b;
    return sum;
  };
  const double first = cloud_light(1, false), second = cloud_light(2, false), sky = cloud_light(2, true);
  std::printf("cloud light: first order %.4g, + second %.4g (x%.3f), + sky %.4g (x%.3f)\n", first,
              second, second / first, sky, sky / second);
  EXPECT_GT(second / first, 1.1);
  EXPECT_LT(second / first, 2.0);
  EXPECT_GT(sky / second, 1.02);
}

// The light passes run when the balls or the light change, not every frame of a flight: a
// sun that moved 0.1 deg keeps the light, one that moved 1 deg relights; a camera that moved
// keeps it.
TEST_F(NishitaRenderTest, RelitOnlyWhenTheLightMoves) {
  Scene s = nishita_scene();
  s.classic.nishita_metaballs = 59;  // balls no other test lit
  const auto relit = [&](const Scene& scene) {
    const Frame f = shared_renderer().render_next(scene, false);
    for (const PassTiming& p : f.stats.passes)
      if (p.name == "nishita_light") return true;
    return false;
  };
  EXPECT_TRUE(relit(s));
  s.camera.position_m.x += 200.0f;
  EXPECT_FALSE(relit(s));
  const auto turned = [](glm::vec3 d, float deg) {
    const float a = glm::radians(deg);
    return glm::vec3(d.x * std::cos(a) - d.y * std::sin(a), d.x * std::sin(a) + d.y * std::cos(a), d.z);
  };
  s.sun.direction = turned(s.sun.direction, 0.1f);
  EXPECT_FALSE(relit(s));
  s.sun.direction = turned(s.sun.direction, 1.0f);
  EXPECT_TRUE(relit(s));
  s.classic.nishita_metaballs = 61;
  EXPECT_TRUE(relit(s));
}

}  // namespace
}  // namespace nephele

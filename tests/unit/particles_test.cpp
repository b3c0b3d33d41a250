// Particle clouds (seed 003, 3.3.2-3.3.3; issue 22): Perlin noise, the field's shapes and
// coverage, and the CPU lighting's recurrence.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <set>

#include <glm/geometric.hpp>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "particles/particle_field.h"
#include "particles/particle_lighting.h"
#include "particles/perlin.h"

namespace nephele::particles {
namespace {

TEST(Perlin, ZeroOnTheLatticeBoundedContinuousAndSeeded) {
  const PerlinNoise a(1), b(2);
  float lo = 1e9f, hi = -1e9f, worst_step = 0.0f;
  int differ = 0;
  for (int i = 0; i < 2000; ++i) {
    const float x = 0.37f * i, y = 0.11f * i + 3.0f, z = 0.07f * i - 5.0f, w = 0.013f * i;
    EXPECT_EQ(a.noise3(float(i % 17), float(i % 5), float(-i % 9)), 0.0f);
    EXPECT_EQ(a.noise4(float(i % 17), float(i % 5), float(-i % 9), float(i % 3)), 0.0f);
    for (float v : {a.noise3(x, y, z), a.noise4(x, y, z, w)}) lo = std::min(lo, v), hi = std::max(hi, v);
    worst_step = std::max(worst_step, std::abs(a.noise4(x + 1e-3f, y, z, w) - a.noise4(x, y, z, w)));
    differ += std::abs(a.noise3(x, y, z) - b.noise3(x, y, z)) > 0.05f;
  }
  EXPECT_GT(hi, 0.5f);
  EXPECT_LT(lo, -0.5f);
  EXPECT_LE(hi, 1.5f);
  EXPECT_GE(lo, -1.5f);
  EXPECT_LT(worst_step, 0.01f);  // gradient bounded: no jumps
  EXPECT_GT(differ, 1000);       // another seed, another pattern
  EXPECT_EQ(a.noise3(1.3f, 2.7f, -0.4f), PerlinNoise(1).noise3(1.3f, 2.7f, -0.4f));
}

ParticleCloudParams small_field(float coverage) {
  ParticleCloudParams p;
  p.coverage = coverage;
  p.field_radius_m = 6000.0f;
  p.cell_m = 125.0f;
  return p;
}

double spawned_share(const ParticleField& f) { return double(f.particles()) / double(f.cells); }

TEST(ParticleField, CoverageIsTheShareOfCellsAtEveryMomentOfAnEvolvingSky) {
  for (float coverage : {0.15f, 0.35f, 0.6f}) {
    ParticleCloudParams p = small_field(coverage);
    p.field_radius_m = 12000.0f;  // many noise periods: the share is close to its expectation
    p.cell_m = 200.0f;
    p.evolution_s = 600.0f;
    const ParticleField first = generate_field(p, 0.0f);
    EXPECT_NEAR(spawned_share(first), coverage, 0.05) << "coverage " << coverage;
    for (float t : {900.0f, 4000.0f}) {
      const ParticleField later = generate_field(p, t);
      EXPECT_NEAR(spawned_share(later), coverage, 0.05) << "coverage " << coverage << " t " << t;
      // ... while the sky itself changed: most particles are not where they were.
      std::set<std::tuple<int, int, int>> before;
      for (const ParticleCloud& c : first.clouds)
        for (const Particle& q : c.particles)
          before.insert({int(std::floor(q.position_m.x / p.cell_m)),
                         int(std::floor(q.position_m.y / p.cell_m)),
                         int(std::floor(q.position_m.z / p.cell_m))});
      size_t kept = 0;
      for (const ParticleCloud& c : later.clouds)
        for (const Particle& q : c.particles)
          kept += before.count({int(std::floor(q.position_m.x / p.cell_m)),
                                int(std::floor(q.position_m.y / p.cell_m)),
                                int(std::floor(q.position_m.z / p.cell_m))});
      EXPECT_LT(double(kept) / double(later.particles()), 0.75) << "t " << t;
    }
  }
  EXPECT_EQ(generate_field(small_field(0.0f), 0.0f).particles(), 0u);
  const ParticleField full = generate_field(small_field(1.0f), 0.0f);
  EXPECT_EQ(full.particles(), full.cells);
}

TEST(ParticleField, ParticlesSitRandomlyInTheirCellsSizedAndTexturedByTheNoise) {
  const ParticleCloudParams p = small_field(0.3f);
  const ParticleField f = generate_field(p, 0.0f);
  ASSERT_GT(f.particles(), 1000u);
  EXPECT_EQ(f.particles(), generate_field(p, 0.0f).particles());  // deterministic
  double sum = 0.0, sum2 = 0.0;
  size_t n = 0;
  int textures[kTextureCount] = {};
  double radius_by_texture[kTextureCount] = {};
  for (const ParticleCloud& c : f.clouds) {
    // Each cloud keeps to its square and the layer.
    EXPECT_LE(std::abs(c.center_m.x / p.cloud_spacing_m - std::round(c.center_m.x / p.cloud_spacing_m)), 1e-4);
    for (const Particle& q : c.particles) {
      EXPECT_LE(std::abs(q.position_m.x - c.center_m.x), 0.5f * p.cloud_spacing_m + p.cell_m);
      EXPECT_GE(q.position_m.z, p.bottom_altitude_m - p.cell_m);
      EXPECT_LE(q.position_m.z, p.top_altitude_m + p.cell_m);
      EXPECT_LE(glm::length(q.position_m - c.center_m) + q.radius_m, c.bound_radius_m + 1e-2f);
      EXPECT_GE(q.radius_m, 0.45f * p.particle_radius_m - 1e-3f);
      EXPECT_LE(q.radius_m, p.particle_radius_m + 1e-3f);
      const double frac = q.position_m.x / p.cell_m - std::floor(q.position_m.x / p.cell_m);
      sum += frac, sum2 += frac * frac, ++n;
      ++textures[q.texture];
      radius_by_texture[q.texture] += q.radius_m;
    }
  }
  // Offsets uniform in the cell: mean 1/2, standard deviation 1/sqrt(12) = 0.289.
  EXPECT_NEAR(sum / n, 0.5, 0.03);
  EXPECT_NEAR(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 0.289, 0.02);
  for (int t = 0; t < kTextureCount; ++t) {
    EXPECT_GT(textures[t], 0) << "texture " << t;
    if (t > 0)  // the noise picks both: denser spots, bigger particles, later textures
      EXPECT_GT(radius_by_texture[t] / textures[t], radius_by_texture[t - 1] / textures[t - 1]);
  }
}

ParticleCloud column(int count, float spacing_m, float radius_m) {
  ParticleCloud c;
  for (int i = 0; i < count; ++i) {
    Particle p;
    p.position_m = glm::vec3(0.0f, 0.0f, float(i) * spacing_m);
    p.radius_m = radius_m;
    c.particles.push_back(p);
  }
  c.center_m = glm::vec3(0.0f, 0.0f, 0.5f * float(count - 1) * spacing_m);
  return c;
}

TEST(ParticleLighting, AColumnTowardsTheLightFollowsHarrisAndLastrasRecurrence) {
  // Particles stacked under the sun: at each centre, I_{k+1} = I_k (1 - a (1 - f)).
  for (float forward : {0.0f, 0.4f}) {
    for (int buffer : {32, 64}) {
      ParticleCloud c = column(8, 50.0f, 100.0f);
      const float opacity = 0.3f;
      light_cloud(c, glm::vec3(0, 0, 1), forward, opacity, buffer);
      double expected = 1.0;
      for (int k = 7; k >= 0; --k) {  // the highest is nearest the sun
        EXPECT_NEAR(c.particles[k].light, expected, 0.02) << "k " << k << " f " << forward;
        expected *= 1.0 - opacity * (1.0 - forward);
      }
      EXPECT_EQ(c.lit_towards, glm::vec3(0, 0, 1));
    }
  }
  // Lit from below, the order reverses.
  ParticleCloud c = column(4, 50.0f, 100.0f);
  light_cloud(c, glm::vec3(0, 0, -1), 0.0f, 0.5f, 32);
  EXPECT_NEAR(c.particles[0].light, 1.0f, 1e-6f);
  EXPECT_NEAR(c.particles[3].light, 0.125f, 0.02f);
}

TEST(ParticleLighting, TheVectorSplatIsTheScalarOneByteForByte) {
  ParticleField f = generate_field(small_field(0.4f), 0.0f);
  ParticleField g = f;
  const glm::vec3 sun = glm::normalize(glm::vec3(0.3f, -0.5f, 0.8f));
  size_t compared = 0;
  for (size_t i = 0; i < f.clouds.size(); ++i) {
    light_cloud(f.clouds[i], sun, 0.35f, 0.5f, 64);
    light_cloud_scalar(g.clouds[i], sun, 0.35f, 0.5f, 64);
    for (size_t k = 0; k < f.clouds[i].particles.size(); ++k, ++compared)
      ASSERT_EQ(f.clouds[i].particles[k].light, g.clouds[i].particles[k].light);
  }
  EXPECT_GT(compared, 1000u);
}

TEST(ParticleLighting, SunlitSidesAreBrighterAndTheForwardShareFollowsThePhase) {
  ParticleCloudParams p = small_field(0.4f);
  ParticleField f = generate_field(p, 0.0f);
  const glm::vec3 sun(0.0f, 0.0f, 1.0f);
  double top = 0.0, bottom = 0.0;
  int n_top = 0, n_bottom = 0;
  for (ParticleCloud& c : f.clouds) {
    light_cloud(c, sun, forward_share(p), p.opacity, p.light_buffer);
    for (const Particle& q : c.particles) {
      if (q.position_m.z > p.top_altitude_m - 400.0f) top += q.light, ++n_top;
      if (q.position_m.z < p.bottom_altitude_m + 300.0f) bottom += q.light, ++n_bottom;
    }
  }
  EXPECT_GT(top / n_top, 0.9);  // the sunlit tops barely shaded
  EXPECT_LT(bottom / n_bottom, 0.7);  // the bases under about 3 particles' shade
  // f = albedo p(0) gamma: HG(0.6, 1) = (1 + g) / (4 pi (1 - g)^2) = 0.7958 / sr.
  EXPECT_NEAR(forward_share(p), 0.9 * 0.7958 * 0.5, 1e-3);
  p.rayleigh_phase = true;  // 3 / (16 pi) x 2
  EXPECT_NEAR(forward_share(p), 0.9 * 0.11937 * 0.5, 1e-4);
  p.rayleigh_phase = false;
  p.forward_solid_angle_sr = 12.0f;
  EXPECT_EQ(forward_share(p), 1.0f);  // never more than it intercepts
}

TEST(ParticleLighting, RelightingKeepsToItsBudgetAndOnlyRedoesStaleClouds) {
  const ParticleCloudParams p = small_field(0.3f);
  ParticleField f = generate_field(p, 0.0f);
  ASSERT_GT(f.clouds.size(), 10u);
  const glm::vec3 sun = glm::normalize(glm::vec3(0.2f, 0.1f, 1.0f));
  const size_t budget = f.particles() / 5;
  int calls = 0;
  RelightReport r;
  do {
    r = relight(f, sun, p, budget);
    EXPECT_TRUE(r.particles <= budget || r.clouds == 1);
    ++calls;
  } while (r.stale_left > 0 && calls < 100);
  EXPECT_GE(calls, 5);
  EXPECT_LE(calls, 8);
  EXPECT_EQ(relight(f, sun, p, budget).clouds, 0);  // nothing changed, nothing redone
  // A light moved by less than the threshold keeps the lighting; by more, redoes it.
  const glm::vec3 near = glm::normalize(sun + glm::vec3(0.002f, 0.0f, 0.0f));
  EXPECT_EQ(relight(f, near, p, f.particles()).clouds, 0);
  const glm::vec3 far = glm::normalize(sun + glm::vec3(0.05f, 0.0f, 0.0f));
  EXPECT_EQ(relight(f, far, p, f.particles()).clouds, int(f.clouds.size()));
  // Every parameter of the lighting redoes it (a viewer's slider), and each lighting counts.
  const uint32_t lightings = f.clouds[0].lightings;
  for (const auto& change : std::vector<std::function<void(ParticleCloudParams&)>>{
           [](ParticleCloudParams& q) { q.albedo = 0.5f; },
           [](ParticleCloudParams& q) { q.phase_g = 0.2f; },
           [](ParticleCloudParams& q) { q.rayleigh_phase = true; },
           [](ParticleCloudParams& q) { q.forward_solid_angle_sr = 0.1f; },
           [](ParticleCloudParams& q) { q.opacity = 0.7f; },
           [](ParticleCloudParams& q) { q.light_buffer = 64; }}) {
    ParticleCloudParams q = p;
    change(q);
    EXPECT_EQ(relight(f, far, q, f.particles()).clouds, int(f.clouds.size()));
    EXPECT_EQ(relight(f, far, q, f.particles()).clouds, 0);
  }
  EXPECT_EQ(f.clouds[0].lightings, lightings + 6);
  // What only the drawing uses does not (the last lighting was p's with a 64-texel buffer).
  ParticleCloudParams drawing = p;
  drawing.light_buffer = 64;
  drawing.diffuse_strength = 3.0f;
  drawing.impostors = "tiles";
  EXPECT_EQ(relight(f, far, drawing, f.particles()).clouds, 0);
}

TEST(ParticleField, ItsShapeNamesWhatTheFieldDependsOn) {
  const ParticleCloudParams p = small_field(0.3f);
  ParticleCloudParams q = p;
  q.albedo = 0.1f;
  q.impostors = "off";
  q.wind_mps = glm::vec2(10.0f, 0.0f);
  q.layer_resolution = 0.5f;
  EXPECT_EQ(field_shape(q, 1.0f), field_shape(p, 1.0f));  // drawing and lighting only
  EXPECT_FALSE(field_shape(p, 2.0f) == field_shape(p, 1.0f));
  for (const auto& change : std::vector<std::function<void(ParticleCloudParams&)>>{
           [](ParticleCloudParams& r) { r.coverage = 0.4f; },
           [](ParticleCloudParams& r) { r.cell_m *= 2.0f; },
           [](ParticleCloudParams& r) { r.seed = 7; },
           [](ParticleCloudParams& r) { r.noise_period_m *= 2.0f; }}) {
    ParticleCloudParams r = p;
    change(r);
    EXPECT_FALSE(field_shape(r, 1.0f) == field_shape(p, 1.0f));
    EXPECT_NE(generate_field(r, 1.0f).particles(), generate_field(p, 1.0f).particles());
  }
}

TEST(ParticleScene, BadParametersGetOneLineNamingThem) {
  const auto message = [](const std::string& toml) {
    try {
      validate_scene(parse_scene_toml(toml, ""));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message("[particle_clouds]\nlight_buffer = 48\n"),
            "particle_clouds.light_buffer = 48: must be 32 or 64");
  const std::string cells = message("[particle_clouds]\ncoverage = 0.5\ncell_m = 2\n");
  EXPECT_NE(cells.find("particle_clouds.cell_m = 2: the field would hold"), std::string::npos) << cells;
  EXPECT_NE(message("[particle_clouds]\ncoverage = 1.5\n").find("particle_clouds.coverage = 1.5"),
            std::string::npos);
  const std::string layer = message("[particle_clouds]\nlayer_resolution = 0.1\n");
  EXPECT_NE(layer.find("particle_clouds.layer_resolution = 0.1"), std::string::npos) << layer;
  EXPECT_NE(layer.find("[0.25, 1]"), std::string::npos) << layer;
  EXPECT_NE(message("[particle_clouds]\nbottom_altitude_m = 3000\n").find("top_altitude_m"),
            std::string::npos);
  // A scene's particle clouds survive writing and reading.
  Scene s;
  s.particle_clouds.coverage = 0.25f;
  s.particle_clouds.rayleigh_phase = true;
  s.particle_clouds.light_buffer = 64;
  s.particle_clouds.layer_resolution = 0.75f;
  const Scene back = parse_scene_toml(scene_to_toml(s), "");
  EXPECT_EQ(back.particle_clouds.coverage, 0.25f);
  EXPECT_TRUE(back.particle_clouds.rayleigh_phase);
  EXPECT_EQ(back.particle_clouds.light_buffer, 64);
  EXPECT_EQ(back.particle_clouds.layer_resolution, 0.75f);
}

}  // namespace
}  // namespace nephele::particles

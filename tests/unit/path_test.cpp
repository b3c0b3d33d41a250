// The reference path tracer's functions (shaders/common/path_inc.glsl) against known answers:
// transmittance through a heterogeneous slab, a furnace, single scattering in a homogeneous
// sphere against a numerical integral, and the error falling as 1/sqrt(samples).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "render/glsl.h"

namespace {

using namespace nephele::glsl;

// A slab 0 <= z <= 100 m whose extinction varies along z: 0.02 (1 + 0.8 sin(z / 7 m)) per m.
// Its optical depth along z over [0, 100] has a closed form.
namespace slab {
using namespace nephele::glsl;
constexpr float kThickness = 100.0f;
float pt_sigma_t(vec3 p) { return 0.02f * (1.0f + 0.8f * std::sin(p.z / 7.0f)); }
vec2 pt_bounds(vec3 o, vec3 d) {
  // Only rays along +z are used.
  (void)d;
  return vec2(std::max(-o.z, 0.0f), kThickness - o.z);
}
vec2 pt_majorant_segment(vec3, vec3, float) { return vec2(0.05f, 1e30f); }
#include "common/path_inc.glsl"
double optical_depth() {  // integral of 0.02 (1 + 0.8 sin(z/7)) over [0, 100]
  return 0.02 * (kThickness + 0.8 * 7.0 * (1.0 - std::cos(kThickness / 7.0)));
}
}  // namespace slab

// A homogeneous sphere of radius 50 m at the origin, sigma_t 0.03 per m.
namespace sphere {
using namespace nephele::glsl;
constexpr float kRadius = 50.0f;
constexpr float kSigma = 0.03f;
float pt_sigma_t(vec3 p) { return dot(p, p) <= kRadius * kRadius ? kSigma : 0.0f; }
vec2 pt_bounds(vec3 o, vec3 d) {
  vec2 t = ray_sphere(o, d, kRadius);
  return vec2(std::max(t.x, 0.0f), t.y);
}
vec2 pt_majorant_segment(vec3, vec3, float) { return vec2(0.04f, 1e30f); }
#include "common/path_inc.glsl"
}  // namespace sphere

// Two layers of a slab, 0.03 per m over 0 <= z < 20 and 50 <= z < 70 m, nothing between, with
// a majorant grid of 10 m cells along z: 0.03 over the layers' cells, 0 over the empty ones.
namespace gaps {
using namespace nephele::glsl;
bool dense(float z) { return (z >= 0.0f && z < 20.0f) || (z >= 50.0f && z < 70.0f); }
float pt_sigma_t(vec3 p) { return dense(p.z) ? 0.03f : 0.0f; }
vec2 pt_bounds(vec3 o, vec3) { return vec2(std::max(-o.z, 0.0f), 100.0f - o.z); }
int segments_seen = 0;  // cells entered, counted by the tests
vec2 pt_majorant_segment(vec3 o, vec3 d, float t) {
  ++segments_seen;
  const float z = o.z + d.z * t;
  const float cell_end = (std::floor(z / 10.0f + 1e-4f) + 1.0f) * 10.0f;
  return vec2(dense(z + 1e-3f) ? 0.03f : 0.0f, t + (cell_end - z) / d.z);
}
#include "common/path_inc.glsl"
}  // namespace gaps

// A slab 0 <= z <= 100 m of three colour channels (path_spectral_inc.glsl): the first slab's
// extinction times 0.5, 1 and 2, under one majorant that bounds them all.
namespace colours {
using namespace nephele::glsl;
constexpr float kThickness = 100.0f;
const vec3 kScale(0.5f, 1.0f, 2.0f);
vec3 pt_sigma_t3(vec3 p) {
  return kScale * (0.02f * (1.0f + 0.8f * std::sin(p.z / 7.0f)));
}
float pt_sigma_t(vec3 p) {
  return pt_sigma_t3(p).y;
}
vec2 pt_bounds(vec3 o, vec3) {
  return vec2(std::max(-o.z, 0.0f), kThickness - o.z);
}
vec2 pt_majorant_segment(vec3, vec3, float) {
  return vec2(0.08f, 1e30f);
}
#include "common/path_inc.glsl"
#include "common/path_spectral_inc.glsl"
}  // namespace colours

// Three channels on shared tentative collisions: each channel's ratio-tracked transmittance
// is its own, and the hero's delta tracking, weighted by the balance heuristic over the three
// heroes, lets each channel through with its own transmittance (no channel's estimate borrows
// another's).
TEST(PathTracer, ThreeChannelsOnOnePathKeepTheirOwnTransmittance) {
  const vec3 d(0.0f, 0.0f, 1.0f);
  const int n = 60000;
  glm::dvec3 ratio_sum(0.0), escape_sum(0.0);
  for (int i = 0; i < n; ++i) {
    const uint stream = colours::pt_stream(3u, uint(i), 0u);
    ratio_sum +=
        glm::dvec3(colours::pt_ratio_tracking3(vec3(0.0f), d, colours::kThickness, stream));
    const vec4 flight = colours::pt_hero_delta_tracking(vec3(0.0f), d, colours::kThickness,
                                                        colours::pt_hash(stream), i % 3);
    if (flight.x > colours::kThickness)
      escape_sum += glm::dvec3(colours::pt_hero_weights(vec3(flight.y, flight.z, flight.w)));
  }
  for (int c = 0; c < 3; ++c) {
    const double exact = std::exp(-slab::optical_depth() * double(colours::kScale[c]));
    EXPECT_NEAR(ratio_sum[c] / n, exact, 0.02 * exact + 0.002) << "channel " << c;
    EXPECT_NEAR(escape_sum[c] / n, exact, 0.03 * exact + 0.003) << "channel " << c;
  }
}

// The hero channels: every three samples 3j..3j+2 of a pixel take the three, and so do any
// three consecutive samples of one slot when the slots are a power of three (a pass stopped
// early leaves each slot a multiple of three).
TEST(PathTracer, HeroChannelsComeInThreesInEverySlot) {
  for (uint first = 0; first < 3000; first += 3) {
    int seen[3] = {};
    for (uint k = 0; k < 3; ++k) ++seen[colours::path_hero(first + k)];
    ASSERT_TRUE(seen[0] == 1 && seen[1] == 1 && seen[2] == 1) << first;
  }
  for (uint slots : {1u, 3u, 9u, 27u})
    for (uint slot = 0; slot < slots; ++slot)
      for (uint m = 0; m < 300; m += 3) {
        int seen[3] = {};
        for (uint k = 0; k < 3; ++k) ++seen[colours::path_hero(slot + (m + k) * slots)];
        ASSERT_TRUE(seen[0] == 1 && seen[1] == 1 && seen[2] == 1)
            << "slots " << slots << " slot " << slot << " m " << m;
      }
}

TEST(PathTracer, RatioTrackingMatchesTheSlabsTransmittance) {
  const double exact = std::exp(-slab::optical_depth());  // about 0.13
  double sum = 0.0;
  const int n = 20000;
  for (int i = 0; i < n; ++i)
    sum += slab::pt_ratio_tracking(vec3(0.0f), vec3(0.0f, 0.0f, 1.0f), slab::kThickness,
                                   slab::pt_stream(1u, uint(i), 0u));
  EXPECT_NEAR(sum / n, exact, 0.01 * exact + 0.003) << "exact " << exact;
}

TEST(PathTracer, DeltaTrackingLetsThroughTheSlabsTransmittance) {
  const double exact = std::exp(-slab::optical_depth());
  int through = 0;
  double first_half = 0.0;  // collisions in z < 50, against 1 - T(50)
  const int n = 40000;
  for (int i = 0; i < n; ++i) {
    float t = slab::pt_delta_tracking(vec3(0.0f), vec3(0.0f, 0.0f, 1.0f), slab::kThickness,
                                      slab::pt_stream(2u, uint(i), 0u));
    through += t > slab::kThickness;
    first_half += t < 50.0f;
  }
  const double half_depth = 0.02 * (50.0 + 0.8 * 7.0 * (1.0 - std::cos(50.0 / 7.0)));
  // Binomial standard error at n = 40000: under 0.0025; 4 sigma.
  EXPECT_NEAR(double(through) / n, exact, 0.01);
  EXPECT_NEAR(first_half / n, 1.0 - std::exp(-half_depth), 0.01);
}

// With a majorant grid, empty cells are crossed in one step each and the estimates stay
// unbiased: the layered slab's transmittance is exp(-0.03 x 40), by ratio tracking and by
// delta tracking's escapes, and no tentative collision falls in an empty cell.
TEST(PathTracer, AMajorantGridSkipsEmptyCellsAndStaysUnbiased) {
  const double exact = std::exp(-0.03 * 40.0);
  const vec3 up(0.0f, 0.0f, 1.0f);
  double ratio = 0.0;
  int through = 0;
  const int n = 40000;
  gaps::segments_seen = 0;
  for (int i = 0; i < n; ++i) {
    ratio += gaps::pt_ratio_tracking(vec3(0.0f), up, 100.0f, gaps::pt_stream(8u, uint(i), 0u));
    through += gaps::pt_delta_tracking(vec3(0.0f), up, 100.0f, gaps::pt_stream(9u, uint(i), 0u)) > 100.0f;
  }
  EXPECT_NEAR(ratio / n, exact, 0.01);
  EXPECT_NEAR(double(through) / n, exact, 0.01);
  // At most the 10 cells of the slab per path, two paths per iteration.
  EXPECT_LE(gaps::segments_seen, 2 * 10 * n);
  EXPECT_GT(gaps::segments_seen, n);
}

TEST(PathTracer, HenyeyGreensteinSamplesHaveTheMeanCosineG) {
  // The mean cosine of Henyey-Greenstein is g; the samples are unit vectors.
  for (float g : {-0.5f, 0.0f, 0.3f, 0.85f}) {
    const vec3 d = normalize(vec3(0.3f, -0.5f, 0.8f));
    double sum = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      uint s = sphere::pt_stream(3u, uint(i), 0u);
      vec3 w = sphere::pt_sample_hg(d, g, sphere::pt_uniform(s, 0u), sphere::pt_uniform(s, 1u));
      ASSERT_NEAR(length(w), 1.0f, 1e-4f);
      sum += dot(w, d);
    }
    EXPECT_NEAR(sum / n, g, 0.01) << "g " << g;
  }
}

// Draine's lobe of the droplets' Mie fit (mie_fit at 20 um: alpha 27) and a mild one: the
// sampled cosines' histogram is Draine's phase function, within 5 standard deviations a bin,
// and nearly every draw weighs 1. A weighted draw from Henyey-Greenstein alone has the right
// histogram only after its weights, which ranged over 0.06-1.7 (see pt_sample_draine_cos).
TEST(PathTracer, DraineSamplesHaveDrainesDensityAndWeightOne) {
  const vec4 fit = mie_fit(20.0f);
  for (vec2 ga : {vec2(fit.y, fit.z), vec2(0.3f, 1.0f)}) {
    constexpr int kBins = 40;
    constexpr int n = 200000;
    std::vector<double> histogram(kBins, 0.0);
    int weighted = 0;
    for (int i = 0; i < n; ++i) {
      const vec2 c = sphere::pt_sample_draine_cos(ga.x, ga.y, sphere::pt_stream(5u, uint(i), 1u));
      ASSERT_GE(c.x, -1.0f);
      ASSERT_LE(c.x, 1.0f);
      if (c.y != 1.0f) ++weighted;
      histogram[std::min(int((c.x + 1.0f) * 0.5f * kBins), kBins - 1)] += c.y;
    }
    EXPECT_LT(weighted, n / 1000) << "g " << ga.x;
    for (int b = 0; b < kBins; ++b) {
      // The bin's probability: 2 pi times the phase function's integral over its cosines.
      double expected = 0.0;
      constexpr int kSteps = 200;
      for (int k = 0; k < kSteps; ++k) {
        const float mu = -1.0f + (b + (k + 0.5f) / kSteps) * 2.0f / kBins;
        expected += 2.0 * M_PI * draine_phase(ga.x, ga.y, mu) * (2.0 / kBins / kSteps);
      }
      expected *= n;
      EXPECT_NEAR(histogram[b], expected, 5.0 * std::sqrt(expected) + 2.0)
          << "g " << ga.x << " alpha " << ga.y << " bin " << b;
    }
  }
}

// A conservative plane-parallel slab of optical depth 46 (the overcast's median column) lit at
// normal incidence, paths walked as the planet's tracer scatters them in cloud: the droplets'
// Mie fit (9 um), each lobe drawn as path_trace.comp draws it, weights and all. What passes
// through matches what a Henyey-Greenstein medium of the same mean cosine lets through
// (similarity: at this depth the transport depends on (1 - g) tau alone), within 10%, and the
// diffusion asymptote 4/3 K(1) / ((1 - g) tau + 1.42) within 15%. Weighting every Draine draw
// by the phase's ratio to a Henyey-Greenstein mixture, as the tracer did until stop 59, kept
// the weights' mean at 1, but 4000 such walks let through 0.004 (here 0.237 against 0.237 and
// 0.243).
TEST(PathTracer, ADropletDeckLetsThroughWhatSimilaritySays) {
  const vec4 fit = mie_fit(18.0f);
  const float g = mie_mean_cosine(fit);
  constexpr float kTau = 46.0f;
  const auto transmitted = [&](bool droplets) {
    constexpr int n = 4000;
    double through = 0.0;
    for (int i = 0; i < n; ++i) {
      float z = 0.0f, mu = 1.0f, weight = 1.0f;
      for (uint k = 0; k < 100000u; ++k) {
        const uint s = sphere::pt_stream(9u, uint(i), k);
        z += mu * -std::log(1.0f - sphere::pt_uniform(s, 0u));
        if (z < 0.0f) break;
        if (z > kTau) {
          through += weight;
          break;
        }
        vec2 c(sphere::pt_sample_hg_cos(g, sphere::pt_uniform(s, 1u)), 1.0f);
        if (droplets)
          c = sphere::pt_uniform(s, 2u) < fit.w
                  ? sphere::pt_sample_draine_cos(fit.y, fit.z, sphere::pt_hash(s ^ 0x2545f491u))
                  : vec2(sphere::pt_sample_hg_cos(fit.x, sphere::pt_uniform(s, 1u)), 1.0f);
        weight *= c.y;
        const float phi = 2.0f * float(M_PI) * sphere::pt_uniform(s, 3u);
        mu = std::clamp(mu * c.x + std::sqrt(std::max(1.0f - mu * mu, 0.0f) *
                                             std::max(1.0f - c.x * c.x, 0.0f)) *
                                       std::cos(phi),
                        -1.0f, 1.0f);
      }
    }
    return through / n;
  };
  const double droplets = transmitted(true), hg = transmitted(false);
  const double asymptote = 4.0 / 3.0 * (9.0 / 7.0) / ((1.0 - g) * kTau + 1.42);
  std::printf("g %.3f: droplets %.3f, Henyey-Greenstein %.3f, diffusion asymptote %.3f\n", g,
              droplets, hg, asymptote);
  EXPECT_NEAR(droplets / hg, 1.0, 0.1);
  EXPECT_NEAR(droplets / asymptote, 1.0, 0.15);
  EXPECT_NEAR(hg / asymptote, 1.0, 0.15);
}

// Albedo 1, lit only by a uniform environment of radiance 1: every path leaves the sphere
// with its weight intact, so every pixel sees exactly 1 (any lost or created energy shows).
TEST(PathTracer, AFurnaceReturnsTheEnvironment) {
  const vec3 eye(0.0f, -200.0f, 10.0f);
  for (float g : {0.0f, 0.85f}) {
    double sum = 0.0;
    const int n = 2000;
    for (int i = 0; i < n; ++i)
      sum += sphere::pt_path_radiance(eye, normalize(vec3(0.05f, 1.0f, 0.0f)), vec3(0.0f, 0.0f, 1.0f),
                                      0.0f, 1.0f, 1.0f, g, 100000, sphere::pt_stream(4u, uint(i), 0u));
    EXPECT_NEAR(sum / n, 1.0, 1e-5) << "g " << g;
  }
  // With albedo 0.5 light is lost at each collision: less comes out.
  double dim = 0.0;
  for (int i = 0; i < 2000; ++i)
    dim += sphere::pt_path_radiance(eye, vec3(0.0f, 1.0f, 0.0f), vec3(0.0f, 0.0f, 1.0f), 0.0f, 1.0f,
                                    0.5f, 0.0f, 100000, sphere::pt_stream(5u, uint(i), 0u));
  EXPECT_LT(dim / 2000, 0.6);
}

// Single scattering in the homogeneous sphere, integrated along the view ray with 20000
// midpoint steps: sigma_s T(eye, x) p(mu) E T(x, light).
double single_scattering(vec3 eye, vec3 dir, vec3 light, float irradiance, float albedo, float g) {
  vec2 b = sphere::pt_bounds(eye, dir);
  if (b.y <= b.x) return 0.0;
  const int n = 20000;
  const double dt = double(b.y - b.x) / n;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = b.x + (i + 0.5) * dt;
    const vec3 x = eye + dir * float(t);
    const double to_light = sphere::pt_bounds(x, light).y;
    sum += std::exp(-sphere::kSigma * (t - b.x)) * std::exp(-sphere::kSigma * to_light) * dt;
  }
  return albedo * sphere::kSigma * henyey_greenstein(g, dot(dir, light)) * irradiance * sum;
}

double path_mean(vec3 eye, vec3 dir, vec3 light, float albedo, float g, int n, uint seed) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i)
    sum += sphere::pt_path_radiance(eye, dir, light, 3.0f, 0.0f, albedo, g, 0,
                                    sphere::pt_stream(seed, uint(i), 7u));
  return sum / n;
}

TEST(PathTracer, SingleScatteringMatchesANumericalIntegral) {
  const vec3 eye(0.0f, -150.0f, 0.0f);
  const vec3 light = normalize(vec3(0.3f, -0.4f, 0.8f));
  // Through the middle and through the rim, forward and isotropic scattering.
  for (float x : {0.0f, 30.0f, 45.0f})
    for (float g : {0.0f, 0.7f}) {
      const vec3 dir = normalize(vec3(x, 150.0f, 5.0f));
      const double exact = single_scattering(eye, dir, light, 3.0f, 0.9f, g);
      const double estimate = path_mean(eye, dir, light, 0.9f, g, 40000, 11u);
      EXPECT_NEAR(estimate, exact, 0.02 * exact) << "x " << x << " g " << g;
    }
}

// The root-mean-square error of a pixel's mean over N paths falls as 1/sqrt(N): 4 times the
// paths halve it.
TEST(PathTracer, ErrorFallsAsOneOverTheRootOfTheSamples) {
  const vec3 eye(0.0f, -150.0f, 0.0f);
  const vec3 light = normalize(vec3(0.3f, -0.4f, 0.8f));
  const vec3 dir = normalize(vec3(20.0f, 150.0f, 5.0f));
  const double exact = single_scattering(eye, dir, light, 3.0f, 0.9f, 0.5f);
  std::vector<double> rms;
  for (int n : {16, 64, 256}) {
    double sq = 0.0;
    const int trials = 400;
    for (int k = 0; k < trials; ++k) {
      const double e = path_mean(eye, dir, light, 0.9f, 0.5f, n, 100u + uint(k) * 7919u + uint(n)) - exact;
      sq += e * e;
    }
    rms.push_back(std::sqrt(sq / trials));
  }
  EXPECT_NEAR(rms[0] / rms[1], 2.0, 0.3);
  EXPECT_NEAR(rms[1] / rms[2], 2.0, 0.3);
}

}  // namespace

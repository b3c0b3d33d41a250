// The shaders' pure functions (shaders/common/*_inc.glsl compiled as C++) against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/glsl.h"

namespace g = nephele::glsl;
using glm::vec2;
using glm::vec3;

namespace {

// Integrates f(mu) over the unit sphere: 2 pi * integral over mu in [-1, 1] (midpoint rule).
template <typename F>
double integrate_sphere(F f, int n = 200000) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    double mu = -1.0 + (i + 0.5) * 2.0 / n;
    sum += f(float(mu));
  }
  return 2.0 * M_PI * sum * 2.0 / n;
}

}  // namespace

TEST(RaySphere, FromOutsideHitsNearAndFarSide) {
  vec2 t = g::ray_sphere(vec3(0, 0, -10), vec3(0, 0, 1), 2.0f);
  EXPECT_FLOAT_EQ(t.x, 8.0f);
  EXPECT_FLOAT_EQ(t.y, 12.0f);
}

TEST(RaySphere, FromInsideHasOneRootBehind) {
  vec2 t = g::ray_sphere(vec3(0, 0, 0.5f), vec3(0, 0, 1), 2.0f);
  EXPECT_FLOAT_EQ(t.x, -2.5f);
  EXPECT_FLOAT_EQ(t.y, 1.5f);
}

TEST(RaySphere, TangentRayTouchesOnce) {
  vec2 t = g::ray_sphere(vec3(-5, 2, 0), vec3(1, 0, 0), 2.0f);
  EXPECT_NEAR(t.x, 5.0f, 1e-3f);
  EXPECT_NEAR(t.y, 5.0f, 1e-3f);
}

TEST(RaySphere, MissReturnsNegativeRoots) {
  vec2 t = g::ray_sphere(vec3(-5, 2.5f, 0), vec3(1, 0, 0), 2.0f);
  EXPECT_LT(t.y, 0.0f);
  vec2 behind = g::ray_sphere(vec3(0, 0, 10), vec3(0, 0, 1), 2.0f);
  EXPECT_LT(behind.y, 0.0f);  // sphere entirely behind the ray
}

TEST(RaySphere, PlanetScaleStaysAccurateInFloat) {
  // Straight up from the ground of a 6360 km planet to a shell 1500 m up: exactly 1500 m.
  const float r = 6360e3f;
  vec2 t = g::ray_sphere(vec3(0, 0, r + 2.0f), vec3(0, 0, 1), r + 1500.0f);
  EXPECT_NEAR(t.y, 1498.0f, 0.5f);
  // Horizontal ray from the ground to the same shell: sqrt((r + h)^2 - r^2).
  vec2 h = g::ray_sphere(vec3(0, 0, r), vec3(1, 0, 0), r + 1500.0f);
  const double expected = std::sqrt((double(r) + 1500.0) * (double(r) + 1500.0) - double(r) * r);
  EXPECT_NEAR(h.y, expected, expected * 1e-4);
}

TEST(Remap, MapsEndpointsAndExtrapolates) {
  EXPECT_FLOAT_EQ(g::remap(0.5f, 0.0f, 1.0f, 10.0f, 20.0f), 15.0f);
  EXPECT_FLOAT_EQ(g::remap(2.0f, 1.0f, 3.0f, 0.0f, 1.0f), 0.5f);
  EXPECT_FLOAT_EQ(g::remap(4.0f, 1.0f, 3.0f, 0.0f, 1.0f), 1.5f);
  EXPECT_FLOAT_EQ(g::remap(0.2f, 0.0f, 1.0f, 1.0f, 0.0f), 0.8f);
}

TEST(Phase, HenyeyGreensteinIntegratesToOneAndMeanCosineIsG) {
  for (float gg : {-0.5f, 0.0f, 0.3f, 0.8f}) {
    EXPECT_NEAR(integrate_sphere([&](float mu) { return g::henyey_greenstein(gg, mu); }), 1.0,
                2e-3)
        << "g = " << gg;
    double mean_cos =
        integrate_sphere([&](float mu) { return mu * g::henyey_greenstein(gg, mu); });
    EXPECT_NEAR(mean_cos, gg, 2e-3) << "g = " << gg;
  }
}

TEST(Phase, ForwardLobePeaksWhenLookingAtTheLight) {
  // mu = dot(view direction, direction to the sun) = 1 looking straight at the sun.
  EXPECT_GT(g::henyey_greenstein(0.8f, 1.0f), 10.0f * g::henyey_greenstein(0.8f, -1.0f));
  EXPECT_FLOAT_EQ(g::henyey_greenstein(0.0f, 0.3f), float(1.0 / (4.0 * M_PI)));
}

TEST(Phase, DualLobeRayleighAndCornetteShanksIntegrateToOne) {
  EXPECT_NEAR(integrate_sphere([](float mu) { return g::dual_lobe_hg(0.8f, -0.3f, 0.7f, mu); }),
              1.0, 2e-3);
  double dual_mean = integrate_sphere(
      [](float mu) { return mu * g::dual_lobe_hg(0.8f, -0.3f, 0.7f, mu); });
  EXPECT_NEAR(dual_mean, 0.7 * 0.8 + 0.3 * -0.3, 3e-3);
  EXPECT_NEAR(integrate_sphere([](float mu) { return g::rayleigh_phase(mu); }), 1.0, 1e-4);
  EXPECT_NEAR(integrate_sphere([](float mu) { return g::cornette_shanks_phase(0.8f, mu); }), 1.0,
              3e-3);
}

// The moments that scatter a light field's spherical harmonics of degree l (Funk-Hecke):
// 2 pi integral of p(mu) P_l(mu), against the closed form; g = 0 is Rayleigh's phase.
TEST(Phase, CornetteShanksLegendreMomentsMatchTheIntegrals) {
  for (float g : {0.0f, 0.3f, 0.76f, 0.9f}) {
    const vec3 lambda = g::cornette_shanks_moments(g);
    const auto moment = [g](int l) {
      return integrate_sphere([g, l](float mu) {
        const double p_l = l == 0 ? 1.0 : l == 1 ? mu : 0.5 * (3.0 * mu * mu - 1.0);
        return float(g::cornette_shanks_phase(g, mu) * p_l);
      });
    };
    EXPECT_NEAR(lambda.x, moment(0), 2e-3) << g;
    EXPECT_NEAR(lambda.y, moment(1), 2e-3) << g;
    EXPECT_NEAR(lambda.z, moment(2), 2e-3) << g;
  }
  const vec3 rayleigh = g::cornette_shanks_moments(0.0f);
  EXPECT_NEAR(rayleigh.z, integrate_sphere([](float mu) {
                return float(g::rayleigh_phase(mu) * 0.5 * (3.0 * mu * mu - 1.0));
              }),
              1e-4);
  EXPECT_FLOAT_EQ(rayleigh.z, 0.1f);
}

// The 6 spherical harmonics of the multiple-scattering field are orthonormal on the sphere.
TEST(SphericalHarmonics, TheFieldsBasisIsOrthonormal) {
  const int n = 200;
  double gram[6][6] = {};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 2 * n; ++j) {
      const double z = 1.0 - (i + 0.5) * 2.0 / n, phi = M_PI * (j + 0.5) / n;
      const double s = std::sqrt(1.0 - z * z);
      const g::ShBasis b = g::sh_basis(vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z)));
      const double y[6] = {b.low.x, b.low.y, b.low.z, b.high.x, b.high.y, b.high.z};
      const double d_omega = 4.0 * M_PI / (2.0 * n * n);
      for (int a = 0; a < 6; ++a)
        for (int c = 0; c < 6; ++c) gram[a][c] += y[a] * y[c] * d_omega;
    }
  for (int a = 0; a < 6; ++a)
    for (int c = 0; c < 6; ++c) EXPECT_NEAR(gram[a][c], a == c ? 1.0 : 0.0, 1e-3) << a << c;
}

// A view ray scatters the multiple-scattering field through the true phases: with a table
// holding a known field L (band-limited, so its harmonics are exact), ms_field_scattering
// gives the integral of L(w) p(w . d) over the sphere for Rayleigh and Cornette-Shanks, for
// views in every direction and the sun off the frame's axes.
TEST(MultipleScatteringField, ScattersAKnownFieldThroughBothPhases) {
  g::Atmosphere a{};
  a.planet_radius_m = 6360e3f;
  a.top_radius_m = 6460e3f;
  a.mie_g = 0.8f;
  const float c[6] = {1.0f, 0.2f, -0.15f, 0.12f, 0.1f, -0.06f};  // c_k, sh_basis's order
  std::vector<glm::vec4> table(size_t(6 * g::MS_FIELD_W) * 2 * g::MS_FIELD_H, glm::vec4(0.0f));
  for (int row = 0; row < g::MS_FIELD_H; ++row)  // half 0
    for (int k = 0; k < 6; ++k)
      for (int i = 0; i < g::MS_FIELD_W; ++i)
        table[size_t(row) * 6 * g::MS_FIELD_W + size_t(k) * g::MS_FIELD_W + i] = glm::vec4(
            vec3(k == 0 ? std::log(c[0] * 0.2820948f + g::MS_LUT_FLOOR) : c[k] / c[0]), 1.0f);
  const g::sampler2D field{table.data(), 6 * g::MS_FIELD_W, 2 * g::MS_FIELD_H};
  const vec3 pos = vec3(0.3f, -0.2f, 1.0f) * (a.planet_radius_m + 3000.0f) / std::sqrt(1.13f);
  const vec3 sun = glm::normalize(vec3(0.6f, 0.5f, 0.4f));
  const glm::mat3 frame = g::ms_field_frame(pos, sun);  // columns: x, y, z (up) of the field
  const auto field_at = [&](vec3 w) {
    const g::ShBasis b = g::sh_basis(glm::transpose(frame) * w);
    return c[0] * b.low.x + c[1] * b.low.y + c[2] * b.low.z + c[3] * b.high.x +
           c[4] * b.high.y + c[5] * b.high.z;
  };
  for (vec3 d : {vec3(0, 0, 1), vec3(1, 0, 0), vec3(-0.3f, 0.8f, -0.2f), sun, -sun}) {
    d = glm::normalize(d);
    double rayleigh = 0.0, mie = 0.0;
    const int n = 400;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < 2 * n; ++j) {
        const double z = 1.0 - (i + 0.5) * 2.0 / n, phi = M_PI * (j + 0.5) / n;
        const double s = std::sqrt(1.0 - z * z);
        const vec3 w(float(s * std::cos(phi)), float(s * std::sin(phi)), float(z));
        const double l = field_at(w) * 4.0 * M_PI / (2.0 * n * n);
        rayleigh += l * g::rayleigh_phase(glm::dot(w, d));
        mie += l * g::cornette_shanks_phase(a.mie_g, glm::dot(w, d));
      }
    const g::MsScattering got = g::ms_field_scattering(a, field, 0, pos, sun, d);
    EXPECT_NEAR(got.rayleigh.g, rayleigh, 2e-3 * rayleigh) << d.x << " " << d.y << " " << d.z;
    EXPECT_NEAR(got.mie.g, mie, 5e-3 * mie) << d.x << " " << d.y << " " << d.z;
  }
}

// floor_div rounds down for negative numbers too, so that a - b floor_div(a, b) wraps into
// [0, b) as the noise's cells and the weather's steps need (GLSL's % leaves it to the device).
TEST(Math, FloorDivRoundsDownAndWrapsNegativeNumbers) {
  EXPECT_EQ(g::floor_div(7, 3), 2);
  EXPECT_EQ(g::floor_div(6, 3), 2);
  EXPECT_EQ(g::floor_div(-1, 3), -1);
  EXPECT_EQ(g::floor_div(-3, 3), -1);
  EXPECT_EQ(g::floor_div(-4, 3), -2);
  EXPECT_EQ(g::floor_div(-1, 360), -1);
  for (int a = -50; a <= 50; ++a)
    EXPECT_EQ(a - 12 * g::floor_div(a, 12), ((a % 12) + 12) % 12) << a;
  EXPECT_EQ(g::wrap_cell(glm::ivec3(-1, 12, 25), 12), glm::ivec3(11, 0, 1));
}

TEST(Noise, PerlinTilesWithItsPeriod) {
  for (int i = 0; i < 50; ++i) {
    vec3 p(0.37f * i, 1.3f + 0.11f * i, 2.9f - 0.07f * i);
    const int period = 4;
    float a = g::perlin_tiled(p, period, 7u);
    EXPECT_NEAR(a, g::perlin_tiled(p + vec3(period, 0, 0), period, 7u), 1e-5f);
    EXPECT_NEAR(a, g::perlin_tiled(p + vec3(0, period, 0), period, 7u), 1e-5f);
    EXPECT_NEAR(a, g::perlin_tiled(p + vec3(0, 0, -period), period, 7u), 1e-5f);
  }
}

TEST(Noise, WorleyTilesAndStaysInRange) {
  float lo = 1.0f, hi = 0.0f;
  for (int i = 0; i < 400; ++i) {
    vec3 p(0.173f * i, std::fmod(0.61f * i, 5.0f), std::fmod(0.29f * i, 7.0f));
    const int period = 5;
    float w = g::worley_tiled(p, period, 3u);
    lo = std::min(lo, w);
    hi = std::max(hi, w);
    EXPECT_GE(w, 0.0f);
    EXPECT_LE(w, 1.0f);
    EXPECT_NEAR(w, g::worley_tiled(p + vec3(period, -period, period), period, 3u), 1e-5f);
  }
  EXPECT_LT(lo, 0.4f);  // spans most of its range: not a constant
  EXPECT_GT(hi, 0.8f);
}

TEST(Noise, WorleyIsOneAtAFeaturePoint) {
  // The feature point of cell (1, 2, 3) sits at cell + hash.
  vec3 feature = vec3(1, 2, 3) + g::hash_cell(glm::ivec3(1, 2, 3), 9u);
  EXPECT_NEAR(g::worley_tiled(feature, 8, 9u), 1.0f, 1e-5f);
}

TEST(Noise, FbmTilesOverTheUnitCube) {
  for (int i = 0; i < 30; ++i) {
    vec3 uvw(0.031f * i, 0.5f, 0.017f * i);
    EXPECT_NEAR(g::worley_fbm(uvw, 4, 1u), g::worley_fbm(uvw + vec3(1, 0, 0), 4, 1u), 1e-4f);
    EXPECT_NEAR(g::perlin_worley(uvw, 4, 1u), g::perlin_worley(uvw + vec3(0, 1, 1), 4, 1u),
                1e-4f);
  }
}

TEST(CloudModel, CoverageEndsMeanClearAndOvercast) {
  for (float r : {0.0f, 0.3f, 0.99f}) {
    EXPECT_EQ(g::cloud_local_coverage(r, 0.0f), 0.0f);
    EXPECT_EQ(g::cloud_local_coverage(r, 1.0f), 1.0f);
  }
  EXPECT_FLOAT_EQ(g::cloud_local_coverage(0.4f, 0.5f), 0.4f);  // the map as it is
  EXPECT_EQ(g::cloud_apply_coverage(0.9f, 0.0f), 0.0f);
  EXPECT_FLOAT_EQ(g::cloud_apply_coverage(0.7f, 1.0f), 0.7f);
  EXPECT_EQ(g::cloud_apply_coverage(0.2f, 0.5f), 0.0f);  // noise below 1 - coverage is cut
}

TEST(CloudModel, HeightGradientsVanishOutsideTheLayer) {
  EXPECT_EQ(g::cloud_shape_gradient(0.0f, 1.0f), 0.0f);
  EXPECT_EQ(g::cloud_shape_gradient(0.8f, 0.6f), 0.0f);  // above the weather map's max height
  EXPECT_FLOAT_EQ(g::cloud_shape_gradient(0.1f, 1.0f), 1.0f);
  EXPECT_EQ(g::cloud_density_gradient(0.0f), 0.0f);
  EXPECT_EQ(g::cloud_density_gradient(1.0f), 0.0f);
  EXPECT_GT(g::cloud_density_gradient(0.8f), g::cloud_density_gradient(0.3f));  // dense tops
}

TEST(CloudModel, BeerPowderFollowsTheSeedsFormula) {
  // Without powder: Beer-Lambert alone.
  EXPECT_FLOAT_EQ(g::cloud_beer_powder(1.5f, 0.2f, 0.0f), std::exp(-1.5f));
  // Looking at the sun (mu = 1) the powder term is 1; looking away it is 2 (1 - e^-2tau).
  EXPECT_FLOAT_EQ(g::cloud_beer_powder(0.5f, 1.0f, 1.0f), std::exp(-0.5f));
  EXPECT_NEAR(g::cloud_beer_powder(0.5f, -1.0f, 1.0f), std::exp(-0.5f) * 2.0f * (1.0f - std::exp(-1.0f)),
              1e-6f);
}

TEST(CloudModel, DiffuseTransmittanceFollowsTheTwoStreamSlab) {
  EXPECT_FLOAT_EQ(g::cloud_diffuse_transmittance(0.0f), 1.0f);
  // A stratocumulus deck of optical depth 10 lets about half the light through, a
  // cumulonimbus of 200 about 4%; both far above the direct beam's exp(-tau).
  EXPECT_NEAR(g::cloud_diffuse_transmittance(10.0f), 0.47f, 0.01f);
  EXPECT_NEAR(g::cloud_diffuse_transmittance(200.0f), 0.043f, 0.002f);
  EXPECT_GT(g::cloud_diffuse_transmittance(3.0f), 10.0f * std::exp(-3.0f));
}

// The ground's sun and cloud light under a cloud (cloud_ground_light_shares): the direct beam
// recovered from the diffuse transmittance, the sunlit ground getting the sun and all the
// clouds' light, a closed deck's its diffuse transmittance's half and half the clouds' light.
TEST(CloudModel, GroundLightSharesTheCloudOverheadWithTheCloudsAround) {
  for (float g : {0.76f, 0.85f})
    for (float tau : {0.1f, 1.0f, 5.0f, 20.0f})
      EXPECT_NEAR(g::cloud_direct_transmittance(g::cloud_diffuse_transmittance(tau, g), g),
                  std::exp(-tau), 1e-4f * std::exp(-tau) + 1e-7f)
          << "g " << g << ", tau " << tau;
  const glm::vec3 light(0.1f);
  const glm::vec2 sunlit = g::cloud_ground_light_shares(1.0f, 0.76f, light);
  EXPECT_FLOAT_EQ(sunlit.x, 1.0f);
  EXPECT_FLOAT_EQ(sunlit.y, 1.0f);
  const float t_d = g::cloud_diffuse_transmittance(60.0f, 0.76f);  // a thick cloud: no beam
  const glm::vec2 deck = g::cloud_ground_light_shares(t_d, 0.76f, light);
  EXPECT_NEAR(deck.x, 0.5f * t_d, 1e-6f);
  EXPECT_NEAR(deck.y, 0.5f, 1e-6f);
  // A cloud of optical depth 1 passes e^-1 directly; half of the rest is cloud overhead.
  const float t_d1 = g::cloud_diffuse_transmittance(1.0f, 0.76f);
  const float w = 1.0f - std::exp(-1.0f);
  const glm::vec2 thin = g::cloud_ground_light_shares(t_d1, 0.76f, light);
  EXPECT_NEAR(thin.x, std::exp(-1.0f) + 0.5f * w * (t_d1 - std::exp(-1.0f)), 1e-5f);
  EXPECT_NEAR(thin.y, 1.0f - 0.5f * w, 1e-5f);
  // No clouds' light measured (no volumetric clouds): the sun's share is the direct and
  // diffuse light together, as before the clouds' light was known.
  EXPECT_EQ(g::cloud_ground_light_shares(t_d, 0.76f, glm::vec3(0.0f)), glm::vec2(t_d, 0.0f));
}

// The ground's light under clouds relative to the clear ground's (cloud_ground_light_ratio), as
// the clouds' bases take it: 1 under a clear sky; under a closed deck (no sun through) the sky
// through the deck and half the deck's own light (the other half is the deck overhead, whose
// light the sun's share holds); between, more light than the sun's share alone gives.
TEST(CloudModel, GroundLightUnderCloudsKeepsTheSkysAndTheCloudsLight) {
  const glm::vec3 sun(0.27f, 0.28f, 0.26f), sky(0.03f, 0.04f, 0.06f);
  const glm::vec3 clear = g::cloud_ground_light_ratio(1.0f, 1.0f, glm::vec3(0.0f), sun, sky);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(clear[c], 1.0f, 1e-6f);
  const glm::vec3 down(0.05f);
  const glm::vec3 deck = g::cloud_ground_light_ratio(0.0f, 0.1f, down, sun, sky);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(deck[c], (0.1f * sky[c] + 0.5f * down[c]) / (sun[c] + sky[c]), 1e-6f);
  // A broken field: the sun's share 0.6, the sky's 0.7, and the clouds' light added.
  const glm::vec3 broken = g::cloud_ground_light_ratio(0.6f, 0.7f, down, sun, sky);
  for (int c = 0; c < 3; ++c) {
    EXPECT_GT(broken[c], 0.6f);
    EXPECT_NEAR(broken[c], (0.6f * sun[c] + 0.7f * sky[c] + 0.8f * down[c]) / (sun[c] + sky[c]),
                1e-6f);
  }
}

// The radiance a cloud layer adds, seen from above, to the clear ground's (cloud_layer_gain):
// nothing without clouds (all ground seen, lit as the clear ground); a closed white deck adds
// its own light less the ground's it hides; a broken field adds its clouds' light and loses
// the ground's in their shadows; never negative.
TEST(CloudModel, ALayerSeenFromAboveAddsItsLightToTheGrounds) {
  const glm::vec3 white(0.30f, 0.31f, 0.32f);
  const float albedo = 0.1f;
  const glm::vec3 clear =
      g::cloud_layer_gain(glm::vec3(0.0f), 1.0f, glm::vec3(1.0f), white, albedo);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(clear[c], 0.0f, 1e-7f);
  // A deck reflecting 70% of the light on it: 0.7 white, the ground hidden.
  const glm::vec3 deck = g::cloud_layer_gain(0.7f * white, 0.0f, glm::vec3(0.3f), white, albedo);
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(deck[c], (0.7f - albedo) * white[c], 1e-6f);
  // Half the ground seen, itself lit 0.8 times as the clear ground.
  const glm::vec3 broken = g::cloud_layer_gain(0.25f * white, 0.5f, glm::vec3(0.8f), white, albedo);
  for (int c = 0; c < 3; ++c)
    EXPECT_NEAR(broken[c], (0.25f + (0.4f - 1.0f) * albedo) * white[c], 1e-6f);
  // Dark clouds over a bright ground: no negative light.
  const glm::vec3 dark = g::cloud_layer_gain(glm::vec3(0.0f), 0.0f, glm::vec3(1.0f), white, 0.9f);
  for (int c = 0; c < 3; ++c) EXPECT_EQ(dark[c], 0.0f);
}

// The two-stream fluxes along a sun chord (cloud_two_stream_fluxes) against the two-stream
// equations integrated numerically: dF_on/dtau = -gamma1 F_on + gamma2 F_back,
// dF_back/dtau = gamma1 F_back - gamma2 F_on, with F_on(0) = 1 and F_back(T) = 0, by RK4 and
// shooting on F_back(0) (the equations are linear).
glm::dvec2 two_stream_by_rk4(double w, double chord, double at) {
  const double g = 0.85, gamma1 = (7.0 - w * (4.0 + 3.0 * g)) / 4.0;
  const double gamma2 = -(1.0 - w * (4.0 - 3.0 * g)) / 4.0;
  const auto run = [&](double back0, double until) {
    glm::dvec2 f(1.0, back0);
    const auto d = [&](glm::dvec2 v) {
      return glm::dvec2(-gamma1 * v.x + gamma2 * v.y, gamma1 * v.y - gamma2 * v.x);
    };
    const int n = 20000;
    const double h = until / n;
    for (int i = 0; i < n; ++i) {
      const glm::dvec2 k1 = d(f), k2 = d(f + 0.5 * h * k1), k3 = d(f + 0.5 * h * k2),
                       k4 = d(f + h * k3);
      f += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
    }
    return f;
  };
  const double b0 = run(0.0, chord).y, b1 = run(1.0, chord).y;
  return run(-b0 / (b1 - b0), at);
}

TEST(CloudModel, TwoStreamFluxesSolveTheTwoStreamEquations) {
  for (float w : {1.0f, 0.9999f, 0.99f, 0.9f})
    for (float chord : {0.5f, 8.0f, 60.0f})
      for (float share : {0.0f, 0.3f, 0.8f}) {
        const float tau = chord * share;
        const glm::vec2 f = g::cloud_two_stream_fluxes(tau, chord - tau, w);
        const glm::dvec2 expected = two_stream_by_rk4(w, chord, tau);
        EXPECT_NEAR(f.x, expected.x, 1e-3 * expected.x + 1e-6)
            << "on: albedo " << w << ", chord " << chord << ", tau " << tau;
        EXPECT_NEAR(f.y, expected.y, 1e-3 * expected.y + 1e-6)
            << "back: albedo " << w << ", chord " << chord << ", tau " << tau;
      }
  // The light enters at the sunlit end whole and none comes back from beyond the far end.
  EXPECT_FLOAT_EQ(g::cloud_two_stream_fluxes(0.0f, 40.0f, 0.99f).x, 1.0f);
  EXPECT_FLOAT_EQ(g::cloud_two_stream_fluxes(40.0f, 0.0f, 0.99f).y, 0.0f);
  // Without absorption the net flux is the same all along the chord: what the cloud passes,
  // 1 / (1 + gamma1 T), gamma1 = 3/4 (1 - 0.85); and a deep cloud sends most light back.
  for (float tau : {0.0f, 10.0f, 50.0f, 99.0f}) {
    const glm::vec2 f = g::cloud_two_stream_fluxes(tau, 100.0f - tau, 1.0f);
    EXPECT_NEAR(f.x - f.y, 1.0f / (1.0f + 0.1125f * 100.0f), 1e-4f) << "tau " << tau;
  }
  EXPECT_GT(g::cloud_two_stream_fluxes(0.0f, 100.0f, 1.0f).y, 0.9f);
  // With the phase function's own asymmetry (the droplets': 0.76 at 9 um, delta-scaled), the
  // same law with gamma1 = 3/4 (1 - g): less forward scattering passes less.
  for (float asymmetry : {0.0f, 0.5f, 0.76f}) {
    const glm::vec2 f = g::cloud_two_stream_fluxes(40.0f, 60.0f, 1.0f, asymmetry);
    EXPECT_NEAR(f.x - f.y, 1.0f / (1.0f + 0.75f * (1.0f - asymmetry) * 100.0f), 1e-4f) << asymmetry;
  }
  // Droplets absorbing 1% (albedo 0.99) send back a deep cloud's r = gamma2 / (gamma1 + k).
  EXPECT_NEAR(g::cloud_two_stream_fluxes(0.0f, 1000.0f, 0.99f).y, 0.5506f, 1e-3f);
}

TEST(CloudModel, TwoStreamRadianceFavoursTheLightsDirection) {
  // The sunlit face of a deep cloud: no diffuse light going on yet, much coming back. Seen from
  // the sun's side (the view ray pointing away from the sun, mu = -1) it is brighter than an
  // isotropic field would make it; seen against the sun (mu = 1) darker; g1 = 0 is isotropic.
  const float tau = 0.0f;
  const glm::vec2 f = g::cloud_two_stream_fluxes(tau, 200.0f, 1.0f);
  const float iso = g::cloud_two_stream_radiance(f, tau, 1.0f, 0.0f);
  EXPECT_NEAR(iso, (f.x - 1.0f + f.y) / (2.0f * 3.14159265f), 1e-6f);
  EXPECT_GT(g::cloud_two_stream_radiance(f, tau, -1.0f, 0.5f), 1.5f * iso);
  EXPECT_LT(g::cloud_two_stream_radiance(f, tau, 1.0f, 0.5f), 0.5f * iso);
  // The direct beam is single scattering's, not the field's: a clear chord scatters nothing.
  EXPECT_NEAR(g::cloud_two_stream_radiance(g::cloud_two_stream_fluxes(0.0f, 0.0f, 1.0f), 0.0f,
                                           0.3f, 0.5f),
              0.0f, 1e-6f);
}

TEST(CloudModel, GroundSkyLightComesThroughTheGapsAndTheClouds) {
  // Clear sky, and a closed deck passing 20% everywhere.
  EXPECT_FLOAT_EQ(g::cloud_ground_sky_share(1.0f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(g::cloud_ground_sky_share(0.2f, 0.2f), 0.2f);
  // In the shadow of a broken field (60% cover of T = 0.2: mean 0.52) the gaps' light comes in;
  // a sunlit spot in it loses some sky to the clouds around.
  EXPECT_NEAR(g::cloud_ground_sky_share(0.2f, 0.52f), 0.36f, 1e-6f);
  EXPECT_NEAR(g::cloud_ground_sky_share(1.0f, 0.52f), 0.76f, 1e-6f);
}

TEST(Atmosphere, TransmittanceStraightUpMatchesTheClosedForm) {
  g::Atmosphere a{};  // zero: no ozone
  a.planet_radius_m = 6360e3f;
  a.top_radius_m = 6460e3f;
  a.rayleigh_sigma_s = vec3(5.802e-6f, 13.558e-6f, 33.1e-6f);
  a.rayleigh_height_m = 8000.0f;
  a.mie_sigma_s = 3.996e-6f;
  a.mie_sigma_t = 4.44e-6f;
  a.mie_height_m = 1200.0f;
  a.mie_g = 0.8f;
  // Optical depth of an exponential profile from 0 to H_top: sigma H (1 - exp(-H_top / H)).
  const double top = 100e3;
  for (int c = 0; c < 3; ++c) {
    double tau = a.rayleigh_sigma_s[c] * 8000.0 * (1 - std::exp(-top / 8000.0)) +
                 4.44e-6 * 1200.0 * (1 - std::exp(-top / 1200.0));
    vec3 t = g::atmosphere_transmittance_to_top(a, vec3(0, 0, a.planet_radius_m), vec3(0, 0, 1),
                                                400);
    EXPECT_NEAR(t[c], std::exp(-tau), 1e-3) << "channel " << c;
  }
  // Below the horizon the planet blocks the sun.
  EXPECT_EQ(g::atmosphere_transmittance_to_top(a, vec3(0, 0, a.planet_radius_m + 10.0f),
                                               glm::normalize(vec3(1, 0, -0.2f)), 16)
                .x,
            0.0f);
}

TEST(Atmosphere, SkyIsBlueAtNoonAndRedderNearTheHorizonAtSunset) {
  g::Atmosphere a{6360e3f, 6460e3f, vec3(5.802e-6f, 13.558e-6f, 33.1e-6f), 8000.0f,
                  3.996e-6f,  4.44e-6f, 1200.0f, 0.8f};
  vec3 eye(0, 0, a.planet_radius_m + 2.0f);
  vec3 noon_sun = glm::normalize(vec3(0, 0.3f, 1));
  vec3 zenith = g::sky_single_scattering(a, eye, vec3(0, 0, 1), noon_sun, 32, 16, 0.1f, vec3(0))
                    .radiance;
  EXPECT_GT(zenith.b, zenith.g);
  EXPECT_GT(zenith.g, zenith.r);
  vec3 low_sun = glm::normalize(vec3(0, 1, 0.03f));
  vec3 toward_sun =
      g::sky_single_scattering(a, eye, glm::normalize(vec3(0, 1, 0.05f)), low_sun, 32, 16, 0.1f,
                               vec3(0))
          .radiance;
  EXPECT_GT(toward_sun.r / toward_sun.b, zenith.r / zenith.b * 3.0f);
}

// The five genera's height gradients (seed 002): each is 1 in its core and 0 well outside it,
// the cores in the order of their heights, and neighbours blend.
TEST(CloudTypes, EachGenusSitsAtItsHeight) {
  struct Genus {
    float type, core_lo, core_hi, empty_above;
  };
  // type, a height fraction range inside the core, the height above which it is empty.
  const Genus genera[] = {{0.0f, 0.05f, 0.12f, 0.22f},   // stratus
                          {0.25f, 0.08f, 0.28f, 0.42f},  // stratocumulus
                          {0.5f, 0.42f, 0.58f, 0.72f},   // altocumulus
                          {0.75f, 0.07f, 0.25f, 0.80f},  // cumulus
                          {1.0f, 0.05f, 0.92f, 1.0f}};   // cumulonimbus
  for (const Genus& gen : genera) {
    for (float h = gen.core_lo; h <= gen.core_hi; h += 0.01f)
      EXPECT_FLOAT_EQ(g::cloud_type_gradient(h, gen.type), 1.0f) << gen.type << " at " << h;
    for (float h = gen.empty_above; h <= 1.0f; h += 0.01f)
      EXPECT_EQ(g::cloud_type_gradient(h, gen.type), 0.0f) << gen.type << " at " << h;
    EXPECT_FLOAT_EQ(g::cloud_type_top(gen.type), gen.empty_above);
  }
  EXPECT_EQ(g::cloud_type_gradient(0.2f, 0.5f), 0.0f);  // altocumulus leaves the base empty
  // Halfway between stratus and stratocumulus: half of each.
  EXPECT_FLOAT_EQ(g::cloud_type_gradient(0.3f, 0.125f),
                  0.5f * g::cloud_type_gradient(0.3f, 0.25f));
  EXPECT_EQ(g::cloud_cumulonimbus_share(0.75f), 0.0f);
  EXPECT_EQ(g::cloud_cumulonimbus_share(1.0f), 1.0f);
}

// Precipitation turns any sky into cumulonimbus at 70% coverage or more (seed 002); the anvil
// spreads coverage at the top of cumulonimbus only.
TEST(CloudTypes, PrecipitationMakesCumulonimbusWithAnAnvil) {
  const vec2 dry = g::cloud_precipitate(0.3f, 0.25f, 0.0f);
  EXPECT_FLOAT_EQ(dry.x, 0.3f);
  EXPECT_FLOAT_EQ(dry.y, 0.25f);
  const vec2 storm = g::cloud_precipitate(0.3f, 0.25f, 1.0f);
  EXPECT_FLOAT_EQ(storm.x, 0.95f);  // a solid core
  EXPECT_GE(g::cloud_precipitate(0.3f, 0.25f, 0.2f).x, 0.3f + 0.2f * (0.7f - 0.3f));
  EXPECT_FLOAT_EQ(storm.y, 1.0f);
  EXPECT_FLOAT_EQ(g::cloud_precipitate(0.97f, 0.0f, 1.0f).x, 0.97f);  // never less cloud
  // The anvil: a sheet at the top over the cell, nothing below it or outside the cell.
  EXPECT_FLOAT_EQ(g::cloud_anvil_coverage(0.8f, 1.0f), 0.85f);
  EXPECT_EQ(g::cloud_anvil_coverage(0.5f, 1.0f), 0.0f);
  EXPECT_EQ(g::cloud_anvil_coverage(0.8f, 0.0f), 0.0f);  // no cell, no anvil
  EXPECT_GT(g::cloud_anvil_coverage(0.7f, 1.0f), 0.0f);
  EXPECT_LT(g::cloud_anvil_coverage(0.7f, 1.0f), 0.85f);
  // The cell's core turns cumulonimbus only where the storm channel is strong; its anvil
  // spreads over more of it.
  EXPECT_EQ(g::cloud_storm_cell(0.1f, 1.0f).x, 0.0f);
  EXPECT_GT(g::cloud_storm_cell(0.1f, 1.0f).y, 0.25f);
  EXPECT_LT(g::cloud_storm_cell(0.2f, 1.0f).x, g::cloud_storm_cell(0.2f, 1.0f).y);
  EXPECT_FLOAT_EQ(g::cloud_storm_cell(0.8f, 1.0f).x, 1.0f);
  EXPECT_EQ(g::cloud_storm_cell(0.8f, 0.0f), vec2(0.0f));  // no precipitation, no storm
}

// The seed's wind: (wind + h shear) (time + h skew). The bottom moves with the wind alone; the
// top with the sheared wind and a lead of `skew` seconds, so tops lean downwind. Over a
// cloud's lifetime the shear's lead stops growing (shear_time_s).
TEST(Wind, GrowsWithHeightAndLeansTheTopsDownwind) {
  const vec2 wind(8.0f, 2.0f), shear(3.0f, 1.0f);
  const float time_s = 100.0f, skew_s = 60.0f;
  const vec2 drift = wind * time_s;
  const float shear_time_s = g::shear_time_s(time_s);
  const vec2 bottom = g::cloud_wind_offset(drift, wind, shear, shear_time_s, skew_s, 0.0f);
  EXPECT_FLOAT_EQ(bottom.x, 800.0f);
  EXPECT_FLOAT_EQ(bottom.y, 200.0f);
  for (float h : {0.3f, 0.7f, 1.0f}) {
    const vec2 seed = (wind + h * shear) * (time_s + h * skew_s);
    const vec2 offset = g::cloud_wind_offset(drift, wind, shear, shear_time_s, skew_s, h);
    // 100 s into a lifetime of 3600 s the shear has acted 99.97 s: the seed's within 0.1 m.
    EXPECT_NEAR(offset.x, seed.x, 0.1f) << h;
    EXPECT_NEAR(offset.y, seed.y, 0.1f) << h;
  }
  // A day later the tops lead their bases by at most the lifetime's shear (not 86 km).
  for (float t : {86400.0f, -86400.0f, 1e6f}) {
    const vec2 lead =
        g::cloud_wind_offset(wind * t, wind, shear, g::shear_time_s(t), skew_s, 1.0f) - wind * t;
    EXPECT_LE(glm::length(lead - (wind + shear) * skew_s),
              glm::length(shear) * g::SHEAR_LIFETIME_S * 1.0001f) << t;
    EXPECT_GT(glm::length(lead - (wind + shear) * skew_s),
              0.99f * glm::length(shear) * g::SHEAR_LIFETIME_S) << t;
  }
  // At time 0 only the lean remains: h x skew x wind (plus the shear over the lead).
  const vec2 lean = g::cloud_wind_offset(vec2(0.0f), wind, shear, 0.0f, skew_s, 1.0f);
  EXPECT_FLOAT_EQ(lean.x, (8.0f + 3.0f) * 60.0f);
  // Without shear and skew every height moves together.
  const vec2 rigid = g::cloud_wind_offset(drift, wind, vec2(0.0f), shear_time_s, 0.0f, 0.8f);
  EXPECT_EQ(rigid, drift);
}

// The flow map's two phases (seed 002): weights sum to 1 at every moment, each phase's weight
// is 0 where its displacement jumps back to 0 (so the restart is invisible), and no phase is
// displaced by more than one cycle's flow.
TEST(Wind, FlowPhasesBlendToOneAndHideTheirRestart) {
  for (int i = 0; i <= 100; ++i) {
    const float phase = float(i) / 100.0f;
    const vec2 a = g::cloud_flow_phase(phase, 0), b = g::cloud_flow_phase(phase, 1);
    EXPECT_NEAR(a.x + b.x, 1.0f, 1e-6f) << phase;
    EXPECT_GE(a.y, 0.0f);
    EXPECT_LT(a.y, 1.0f);
    EXPECT_NEAR(std::fmod(b.y - a.y + 1.0f, 1.0f), 0.5f, 1e-6f);  // half a cycle apart
  }
  EXPECT_NEAR(g::cloud_flow_phase(0.0f, 0).x, 0.0f, 1e-6f);   // phase 0 restarts here
  EXPECT_NEAR(g::cloud_flow_phase(0.5f, 1).x, 0.0f, 1e-6f);   // phase 1 half a cycle later
  EXPECT_NEAR(g::cloud_flow_phase(0.5f, 0).x, 1.0f, 1e-6f);
  EXPECT_NEAR(g::cloud_flow_phase(0.999f, 0).x, 0.0f, 0.01f);  // fades out before it jumps
}

// Clouds made of water droplets (shaders/common/droplets_inc.glsl, issue 42): extinction from
// the liquid water content and the effective radius, the droplets' albedo, the fitted Mie phase
// function (normalised, its mean cosine that of cloud droplets, sampled through two HG lobes
// with a bounded weight), and the genera's blend by cloud type.
#include <gtest/gtest.h>

#include <cmath>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "render/glsl.h"

namespace nephele {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The integral of f(mu) over the sphere, 2 pi integral f(cos theta) sin theta dtheta, by the
// midpoint rule in theta (fine enough for a lobe of g = 0.995, about 0.07 rad wide).
template <typename F>
double over_sphere(F f) {
  const int n = 400000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double theta = (double(i) + 0.5) * kPi / double(n);
    sum += f(float(std::cos(theta))) * std::sin(theta);
  }
  return 2.0 * kPi * sum * kPi / double(n);
}

TEST(Droplets, ExtinctionIsThreeWaterOverTwiceTheDensityOfWaterTimesTheRadius) {
  // SI: 3 LWC / (2 rho_w r_eff), 0.5 g/m^3 of droplets of 10 um.
  const double expected = 3.0 * 0.5e-3 / (2.0 * 1000.0 * 10e-6);
  EXPECT_NEAR(glsl::droplet_extinction_per_m(0.5f, 10.0f), expected, 1e-6);
  // Twice the water, twice the extinction; twice the radius, half.
  EXPECT_NEAR(glsl::droplet_extinction_per_m(1.0f, 10.0f), 2.0 * expected, 1e-6);
  EXPECT_NEAR(glsl::droplet_extinction_per_m(0.5f, 20.0f), 0.5 * expected, 1e-6);
  // The default cumulus: an optical depth of 10-100 over a kilometre of its core.
  const Scene scene;
  const float tau_km = 1000.0f * glsl::droplet_extinction_per_m(scene.droplets.cumulus_water_g_m3,
                                                                scene.droplets.cumulus_radius_um);
  EXPECT_GE(tau_km, 10.0f);
  EXPECT_LE(tau_km, 100.0f);
}

TEST(Droplets, AbsorbAlmostNothingInTheVisible) {
  float last = 1.0f;
  for (float r : {2.5f, 5.0f, 10.0f, 15.0f, 25.0f}) {
    const float omega = glsl::droplet_albedo(r);
    EXPECT_GT(omega, 0.9999f) << r;
    EXPECT_LT(omega, 1.0f) << r;
    EXPECT_LE(omega, last) << "larger droplets absorb more";
    last = omega;
  }
  // 1 - omega = 2.52 x kappa: 5.6e-7 at 10 um.
  EXPECT_NEAR(1.0 - double(glsl::droplet_albedo(10.0f)), 5.64e-7, 0.3e-7);
}

TEST(Droplets, TheMieFitIsAPhaseFunctionOfCloudDroplets) {
  for (float d : {5.0f, 10.0f, 20.0f, 30.0f, 50.0f}) {
    const glm::vec4 fit = glsl::mie_fit(d);
    const double norm = over_sphere([&](float mu) { return glsl::mie_phase(fit, mu); });
    EXPECT_NEAR(norm, 1.0, 0.005) << "d = " << d;
    const double mean = over_sphere([&](float mu) { return mu * glsl::mie_phase(fit, mu); });
    EXPECT_NEAR(mean, glsl::mie_mean_cosine(fit), 0.005) << "d = " << d;
    // A diffraction peak hundreds of times the backward light.
    EXPECT_GT(glsl::mie_phase(fit, 1.0f), 300.0f * glsl::mie_phase(fit, -1.0f)) << d;
    // Draine's lobe alone is normalised too.
    const double draine =
        over_sphere([&](float mu) { return glsl::draine_phase(fit.y, fit.z, mu); });
    EXPECT_NEAR(draine, 1.0, 0.002) << "d = " << d;
  }
  // Cloud droplets of r_eff 10 um scatter with an asymmetry of about 0.86 in the visible.
  EXPECT_NEAR(glsl::mie_mean_cosine(glsl::mie_fit(20.0f)), 0.86, 0.025);
}

// The path tracer draws the droplets' directions from the mixture of the HG lobe and an HG
// lobe of the Draine lobe's g, and weights by the phase over that mixture: the weight stays
// under Draine's bound, and the weighted mixture integrates what the phase does.
TEST(Droplets, TheTracersMixtureSamplingHasABoundedUnbiasedWeight) {
  for (float d : {5.0f, 20.0f, 50.0f}) {
    const glm::vec4 fit = glsl::mie_fit(d);
    const auto mixture = [&](float mu) {
      return glm::mix(glsl::henyey_greenstein(fit.x, mu), glsl::henyey_greenstein(fit.y, mu),
                      fit.w);
    };
    const float bound = (1.0f + fit.z) / (1.0f + fit.z * (1.0f + 2.0f * fit.y * fit.y) / 3.0f);
    for (int i = 0; i <= 2000; ++i) {
      const float mu = -1.0f + 2.0f * float(i) / 2000.0f;
      EXPECT_LE(glsl::mie_phase(fit, mu) / mixture(mu), bound * 1.0001f) << d << " " << mu;
    }
    // E_mixture[w f] = integral p f: f a smooth test function.
    const auto f = [](float mu) {
      return 1.0f + mu * mu * mu + 0.5f * std::exp(-4.0f * (1.0f - mu));
    };
    const double weighted = over_sphere(
        [&](float mu) { return mixture(mu) * (glsl::mie_phase(fit, mu) / mixture(mu)) * f(mu); });
    const double direct = over_sphere([&](float mu) { return glsl::mie_phase(fit, mu) * f(mu); });
    EXPECT_NEAR(weighted, direct, 1e-4 * direct) << d;
  }
}

TEST(Droplets, GeneraBlendByCloudType) {
  const glm::vec4 st_to_cu(1.0f, 2.0f, 3.0f, 4.0f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(0.0f, st_to_cu, 5.0f), 1.0f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(0.25f, st_to_cu, 5.0f), 2.0f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(0.5f, st_to_cu, 5.0f), 3.0f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(0.75f, st_to_cu, 5.0f), 4.0f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(1.0f, st_to_cu, 5.0f), 5.0f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(0.625f, st_to_cu, 5.0f), 3.5f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(0.9f, st_to_cu, 5.0f), 4.6f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(-1.0f, st_to_cu, 5.0f), 1.0f);
  EXPECT_FLOAT_EQ(glsl::cloud_genus_blend(2.0f, st_to_cu, 5.0f), 5.0f);
}

// The frame carries the genera's extinction as shares of the largest, which cloud_shape.z is,
// the droplets' albedo and phase; the seed's optics leave every genus at extinction_per_m.
TEST(Droplets, TheFrameCarriesEachGenusExtinctionAndTheDropletsPhase) {
  Scene scene;
  scene.clouds.optics = "droplets";
  scene.clouds.type = 0.75f;
  const gpu::FrameParams f = make_frame_params(scene, 0);
  const DropletParams& d = scene.droplets;
  const CloudOptics optics = cloud_optics(scene);
  const float kept = 1.0f - glsl::droplet_albedo(d.cumulus_radius_um) * optics.peak_fraction;
  // Each genus' water where the field is kDropletCoreField.
  const float cb =
      1.5f * d.cumulonimbus_water_g_m3 / d.cumulonimbus_radius_um * kept / kDropletCoreField;
  const float cu = 1.5f * d.cumulus_water_g_m3 / d.cumulus_radius_um * kept / kDropletCoreField;
  EXPECT_NEAR(f.cloud_shape.z, cb, 1e-6f);  // the largest of the defaults
  EXPECT_NEAR(f.cloud_genus_sigma.w * f.cloud_shape.z, cu, 1e-6f);
  EXPECT_NEAR(f.cloud_genus_sigma.x * f.cloud_shape.z,
              1.5f * d.stratus_water_g_m3 / d.stratus_radius_um * kept / kDropletCoreField, 1e-5f);
  EXPECT_FLOAT_EQ(f.cloud_droplets.x, 1.0f);
  EXPECT_EQ(f.cloud_droplets.y, 1.0f);
  EXPECT_NEAR(f.cloud_shape.w, optics.albedo, 1e-7f);
  EXPECT_NEAR(f.cloud_mie.y, glsl::mie_fit(2.0f * d.cumulus_radius_um).y, 1e-6f);
  EXPECT_EQ(f.cloud_mie.w, 1.0f);  // the Draine lobe alone: the peak is delta-scaled
  EXPECT_NEAR(f.cloud_droplets.z, glsl::mie_mean_cosine(f.cloud_mie), 1e-6f);
  EXPECT_EQ(f.cloud_droplets.w, f.cloud_droplets.z);  // the diffuse light's asymmetry

  Scene seed;
  seed.clouds.optics = "seed";
  seed.clouds.lighting = "seed";
  seed.clouds.extinction_per_m = 0.7f;
  const gpu::FrameParams s = make_frame_params(seed, 0);
  EXPECT_FLOAT_EQ(s.cloud_shape.z, 0.7f);
  EXPECT_EQ(s.cloud_genus_sigma, glm::vec4(1.0f));
  EXPECT_EQ(s.cloud_droplets.x, 1.0f);
  EXPECT_EQ(s.cloud_droplets.y, 0.0f);
  EXPECT_FLOAT_EQ(s.cloud_droplets.z, 0.7f * 0.8f + 0.3f * -0.3f);
  // The seed's lighting carries its diffuse light with the seed's droplet asymmetry; the
  // two-stream light with the lobes' own mean cosine (the lab's medium).
  EXPECT_FLOAT_EQ(s.cloud_droplets.w, glsl::CLOUD_DROPLET_G);
  seed.clouds.lighting = "two-stream";
  EXPECT_FLOAT_EQ(make_frame_params(seed, 0).cloud_droplets.w, s.cloud_droplets.z);
}

// Delta-scaling takes the diffraction peak (the fit's HG lobe, g above 0.97, about half the
// scattering) out of extinction and phase function and changes nothing else: absorption
// sigma_t (1 - albedo) and the scattering outside the peak are the droplets' own, and the
// phase function left (the Draine lobe) is normalised, less forward than the whole.
TEST(Droplets, TheDiffractionPeakGoesOnForwards) {
  for (float radius : {2.5f, 5.0f, 9.0f, 15.0f, 25.0f}) {
    Scene scene;
    scene.clouds.optics = "droplets";
    scene.clouds.type = 0.75f;  // cumulus
    scene.droplets.cumulus_radius_um = radius;
    const CloudOptics o = cloud_optics(scene);
    const glm::vec4 fit = glsl::mie_fit(2.0f * radius);
    EXPECT_GT(fit.x, 0.97f) << radius;
    EXPECT_NEAR(o.peak_fraction, 1.0f - fit.w, 1e-6f) << radius;
    EXPECT_GT(o.peak_fraction, 0.4f) << radius;
    EXPECT_LT(o.peak_fraction, 0.6f) << radius;
    const double sigma = glsl::droplet_extinction_per_m(scene.droplets.cumulus_water_g_m3, radius);
    const double omega = glsl::droplet_albedo(radius);
    const double sigma_d = o.genus_sigma_t_per_m[3] * kDropletCoreField;  // at the core
    // (The albedo is a float: 1 - albedo to within two of its steps, 1.2e-7.)
    EXPECT_NEAR(sigma_d * (1.0 - double(o.albedo)), sigma * (1.0 - omega), 1.2e-7 * sigma);
    EXPECT_NEAR(sigma_d * o.albedo, sigma * omega * (1.0 - o.peak_fraction), 1e-6 * sigma);
    double integral = 0.0, first_moment = 0.0;
    const int n = 20000;
    for (int i = 0; i < n; ++i) {
      const float mu = -1.0f + 2.0f * (float(i) + 0.5f) / float(n);
      const double p = glsl::mie_phase(o.mie, mu) * 2.0 * glsl::PI * 2.0 / n;
      integral += p;
      first_moment += p * mu;
    }
    EXPECT_NEAR(integral, 1.0, 2e-3) << radius;
    EXPECT_NEAR(first_moment, glsl::mie_mean_cosine(o.mie), 2e-3) << radius;
    EXPECT_LT(glsl::mie_mean_cosine(o.mie), glsl::mie_mean_cosine(fit) - 0.1f) << radius;
  }
}

TEST(Droplets, TheSeedsOpticalKeysAreRefusedWithDroplets) {
  for (const char* key : {"extinction_per_m = 2.0", "albedo = 0.95", "phase_g_forward = 0.6",
                          "phase_g_backward = -0.2", "phase_lobe_weight = 0.5"}) {
    const std::string text = std::string("[clouds]\noptics = \"droplets\"\n") + key + "\n";
    try {
      validate_scene(parse_scene_toml(text, "test"));
      ADD_FAILURE() << key << " was accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find("clouds." + std::string(key).substr(0, std::string(key).find(' '))),
                std::string::npos)
          << what;
      EXPECT_NE(what.find("[droplets]"), std::string::npos) << what;
      EXPECT_NE(what.find("clouds.optics = \"seed\""), std::string::npos) << what;
    }
    // With the seed's optics the key is the seed's.
    EXPECT_NO_THROW(validate_scene(
        parse_scene_toml(std::string("[clouds]\noptics = \"seed\"\n") + key + "\n", "test")));
  }
  EXPECT_THROW(validate_scene(parse_scene_toml("[clouds]\noptics = \"water\"\n", "test")),
               InputError);
  EXPECT_THROW(validate_scene(parse_scene_toml("[droplets]\ncumulus_radius_um = 40.0\n", "test")),
               InputError);
  EXPECT_THROW(validate_scene(parse_scene_toml("[droplets]\nstratus_water_g_m3 = 0.0\n", "test")),
               InputError);
}

}  // namespace
}  // namespace nephele

// Nishita and Nakamae's metaball clouds (render/modules/metaball_clouds/metaball_clouds.h, seed
// 004, issue 23): the cumulus made from the scene, their voxel grid against the balls' closed-form
// field and mass, and the second order's phase (classic_inc.glsl) against Henyey-Greenstein's
// moments.
#include "render/modules/metaball_clouds/metaball_clouds.h"

#include <gtest/gtest.h>

#include <cmath>

#include "nephele/scene_io.h"
#include "render/glsl.h"

namespace nephele {
namespace {

Scene metaball_scene() {
  Scene s = load_preset("default");
  s.clouds.model = CloudModel::Nishita;
  return s;
}

// As many balls as asked, in as many clouds, standing on the layer's bottom (no centre below
// half its radius above it, none above the top) within the square asked for; the same seed
// makes the same clouds, another seed others.
TEST(MetaballClouds, TheCumulusStandInTheirSquareAndLayer) {
  Scene s = metaball_scene();
  for (const int count : {338, 358, 7}) {
    s.classic.nishita_metaballs = count;
    s.classic.nishita_clouds = std::min(count, 4);
    const std::vector<Metaball> balls = make_cumulus_metaballs(s, 17);
    ASSERT_EQ(int(balls.size()), count);
    for (const Metaball& b : balls) {
      EXPECT_GT(b.radius_m, 0.0f);
      EXPECT_GE(b.density, 0.6f);
      EXPECT_LE(b.density, 1.0f);
      EXPECT_GE(b.centre_m.z, s.clouds.bottom_altitude_m + 0.5f * b.radius_m - 1e-3f);
      EXPECT_LE(b.centre_m.z, s.clouds.top_altitude_m);
      for (int a = 0; a < 2; ++a)
        EXPECT_LE(std::abs(b.centre_m[a] - s.classic.nishita_center_m[a]), 0.5f * s.classic.nishita_extent_m);
    }
  }
  s.classic.nishita_metaballs = 338;
  const std::vector<Metaball> a = make_cumulus_metaballs(s, 17), b = make_cumulus_metaballs(s, 17),
                              c = make_cumulus_metaballs(s, 18);
  EXPECT_EQ(a[200].centre_m, b[200].centre_m);
  EXPECT_NE(a[200].centre_m, c[200].centre_m);
}

// The grid holds the balls' field at its voxels' centres, and their mass: a ball's field
// integrates to q 4 pi R^3 (1/3 - 22/45 + 17/63 - 4/81) = 0.8156 q R^3.
TEST(MetaballClouds, TheGridHoldsTheFieldAndItsMass) {
  Scene s = metaball_scene();
  s.classic.nishita_metaballs = 60;
  s.classic.nishita_clouds = 2;
  const std::vector<Metaball> balls = make_cumulus_metaballs(s, 5);
  const MetaballGrid g = voxelize_metaballs(balls, 96);
  EXPECT_EQ(std::max(std::max(g.dims.x, g.dims.y), g.dims.z), 96);
  for (int i = 0; i < 300; ++i) {
    const glm::ivec3 v((i * 37) % g.dims.x, (i * 11) % g.dims.y, (i * 7) % g.dims.z);
    const glm::vec3 p = g.corner_m + (glm::vec3(v) + 0.5f) * g.voxel_m;
    EXPECT_NEAR(g.at(v.x, v.y, v.z), metaball_field(balls, p), 1e-5f);
  }
  double mass = 0.0, expected = 0.0;
  for (const float d : g.density) mass += double(d) * std::pow(double(g.voxel_m), 3.0);
  const double shape = 4.0 * glsl::PI * (1.0 / 3.0 - 22.0 / 45.0 + 17.0 / 63.0 - 4.0 / 81.0);
  for (const Metaball& b : balls) expected += b.density * shape * std::pow(double(b.radius_m), 3.0);
  EXPECT_NEAR(mass / expected, 1.0, 0.02);
}

// The second order's phase, Henyey-Greenstein kept to its first two Legendre terms: light from
// one direction is scattered with a mean of 1 over the sphere and the mean cosine g (HG's own)
// while g <= 1/3; beyond, 1 + 3 g cos is cut at zero behind, which adds a little light and
// lowers the mean cosine (g = 0.6: 0.52). Light from every direction alike is scattered
// isotropically, and the Fibonacci directions the sky is gathered from cover the sphere evenly.
TEST(MetaballClouds, TheSecondOrdersPhaseKeepsHenyeyGreensteinsMoments) {
  const glm::vec3 s(0.0f, 0.6f, 0.8f);
  for (const float g : {0.0f, 0.3f, 1.0f / 3.0f, 0.6f}) {
    const int n = 400;
    double mean = 0.0, cosine = 0.0, hg_cosine = 0.0;
    for (int i = 0; i < n; ++i) {
      const double mu = -1.0 + (i + 0.5) * 2.0 / n;  // cos between s and the direction out
      const double weight = 2.0 * glsl::PI * 2.0 / n;
      // An out direction at angle acos(mu) from s.
      const glm::vec3 perpendicular = glm::normalize(glm::cross(s, glm::vec3(1.0f, 0.0f, 0.0f)));
      const glm::vec3 w = float(mu) * s + float(std::sqrt(1.0 - mu * mu)) * perpendicular;
      const double p = glsl::nishita_second_order(1.0f, s, g, w);
      mean += p * weight;
      cosine += p * mu * weight;
      hg_cosine += glsl::henyey_greenstein(g, float(mu)) * mu * weight;
    }
    EXPECT_NEAR(hg_cosine, g, 1e-3) << "g " << g;
    if (g <= 1.0f / 3.0f + 1e-6f) {
      EXPECT_NEAR(mean, 1.0, 1e-3) << "g " << g;
      EXPECT_NEAR(cosine, g, 1e-3) << "g " << g;
    } else {
      EXPECT_NEAR(mean, 1.0, 0.1) << "g " << g;
      EXPECT_NEAR(cosine, 0.52, 0.01) << "g " << g;
    }
  }
  EXPECT_FLOAT_EQ(glsl::nishita_second_order(2.0f, glm::vec3(0.0f), 0.8f, s), 2.0f / (4.0f * glsl::PI));
  glm::vec3 sum(0.0f);
  int up = 0;
  for (int i = 0; i < glsl::NISHITA_SKY_DIRECTIONS; ++i) {
    const glm::vec3 d = glsl::nishita_sphere_dir(i, glsl::NISHITA_SKY_DIRECTIONS);
    EXPECT_NEAR(glm::length(d), 1.0f, 1e-5f);
    sum += d;
    up += d.z > 0.0f;
  }
  EXPECT_LT(glm::length(sum) / float(glsl::NISHITA_SKY_DIRECTIONS), 0.05f);
  EXPECT_EQ(up, glsl::NISHITA_SKY_DIRECTIONS / 2);
}

}  // namespace
}  // namespace nephele

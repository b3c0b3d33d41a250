// The ground-fog layer's pure functions (shaders/common/ground_fog_inc.glsl) against
// Koschmieder's law, an independent double-precision statement of the profile, fine numerical
// integrations along straight rays (flat) and along the sun's rays (on the sphere), and the
// energy of the fog in front of a surface.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "render/glsl.h"

namespace {

namespace fog {
using namespace nephele::glsl;
#include "common/ground_fog_inc.glsl"
}  // namespace fog

using fog::GroundFog;

constexpr double kEarthRadiusM = 6360e3;

// The profile as the header states it, in double: 0 below the base, 1 up to top - soft, then
// 1 - smoothstep(top - soft, top, z) to 0 at the top; a hard top (soft 0) includes the top.
double reference_density(const GroundFog& f, double z) {
  if (z < f.base_m) return 0.0;
  if (f.soft_m <= 0.0f) return z <= f.top_m ? 1.0 : 0.0;
  const double u = std::clamp((z - (double(f.top_m) - f.soft_m)) / f.soft_m, 0.0, 1.0);
  return 1.0 - u * u * (3.0 - 2.0 * u);
}

// Optical depth along a straight segment of length L from altitude z0 to z1, altitude linear
// along it: a midpoint rule of n steps (the hard edges at the base and a hard top cost at most
// one step's error each, 1/n of the depth).
double numerical_optical_depth(const GroundFog& f, double z0, double z1, double length,
                               int n = 400000) {
  double sum = 0.0;
  for (int i = 0; i < n; ++i) sum += reference_density(f, z0 + (z1 - z0) * (i + 0.5) / n);
  return double(f.sigma_t_per_m) * length * sum / n;
}

// Optical depth to the sun from altitude z on a sphere of radius R, the sun at elevation
// sine mu: a straight ray from (0, R + z) along (sqrt(1 - mu^2), mu) to where it leaves the
// top's sphere, the density taken at each point's altitude |p| - R.
double numerical_sun_depth(const GroundFog& f, double z, double mu, int n = 400000) {
  const double r = kEarthRadiusM + z;
  const double r_top = kEarthRadiusM + double(f.top_m);
  if (r >= r_top) return 0.0;
  const double t_exit = -r * mu + std::sqrt(r * r * mu * mu + r_top * r_top - r * r);
  const double cx = std::sqrt(1.0 - mu * mu);
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = t_exit * (i + 0.5) / n;
    const double x = cx * t, y = r + mu * t;
    sum += reference_density(f, std::sqrt(x * x + y * y) - kEarthRadiusM);
  }
  return double(f.sigma_t_per_m) * t_exit * sum / n;
}

// The column of the density above z to the top, numerically.
double reference_density_column(const GroundFog& f, double z) {
  if (z >= f.top_m) return 0.0;
  return numerical_optical_depth(f, z, f.top_m, f.top_m - z, 100000) / f.sigma_t_per_m;
}

// A fog 300 m thick with a 80 m soft top, visibility 300 m.
GroundFog soft_fog() {
  return fog::ground_fog_layer(100.0f, 400.0f, 80.0f, 300.0f, 1.0f);
}
GroundFog hard_fog() {
  return fog::ground_fog_layer(100.0f, 400.0f, 0.0f, 300.0f, 1.0f);
}

struct Ray {
  const char* name;
  float z0_m, z1_m, length_m;
};

// Rays of every kind against the layer 100..400 m (soft top from 320 m).
std::vector<Ray> rays() {
  return {
      {"up from below the base to above the top", 50.0f, 600.0f, 2000.0f},
      {"up from inside the body to outside", 200.0f, 700.0f, 1500.0f},
      {"up from the body into the fade", 150.0f, 380.0f, 900.0f},
      {"down from above into the body", 900.0f, 150.0f, 3000.0f},
      {"down from above, ending in the fade", 1000.0f, 350.0f, 4000.0f},
      {"down from above through the whole layer to below it", 800.0f, 20.0f, 5000.0f},
      {"down from the fade to below the base", 390.0f, 60.0f, 700.0f},
      {"steep up across the layer", 0.0f, 500.0f, 500.0f},
      {"within the fade, up", 330.0f, 395.0f, 2500.0f},
      {"grazing the body, 1 mm over 20 km", 250.0f, 250.001f, 20000.0f},
      {"grazing the fade, 1 cm over 10 km", 390.0f, 390.01f, 10000.0f},
      {"grazing, 5 cm across the start of the fade", 319.98f, 320.03f, 8000.0f},
      {"grazing just below the top, 1 cm down", 399.5f, 399.49f, 30000.0f},
      {"grazing across the base, 2 cm", 99.99f, 100.01f, 6000.0f},
  };
}

TEST(GroundFogKoschmieder, VisibilityGivesTwoPercentContrast) {
  for (float v : {20.0f, 100.0f, 300.0f, 1000.0f, 5000.0f}) {
    const float sigma = fog::ground_fog_sigma_t_per_m(v);
    EXPECT_NEAR(std::exp(-double(sigma) * v), 0.02, 0.02 * 1e-3) << v;
    EXPECT_NEAR(double(sigma) * v, 3.912, 3.912 * 1e-6) << v;  // weather_state's constant
  }
  EXPECT_FLOAT_EQ(fog::KOSCHMIEDER, 3.912f);
  // The layer's extinction is the visibility's.
  EXPECT_FLOAT_EQ(soft_fog().sigma_t_per_m, 3.912f / 300.0f);
  // A zero or negative visibility stays finite.
  EXPECT_TRUE(std::isfinite(fog::ground_fog_sigma_t_per_m(0.0f)));
  EXPECT_TRUE(std::isfinite(fog::ground_fog_sigma_t_per_m(-5.0f)));
}

TEST(GroundFogProfile, MatchesTheStatedProfile) {
  for (const GroundFog& f : {soft_fog(), hard_fog()})
    for (double z = 0.0; z <= 500.0; z += 0.37)
      EXPECT_NEAR(fog::ground_fog_density(f, float(z)), reference_density(f, float(z)), 1e-6)
          << "soft " << f.soft_m << " z " << z;
  const GroundFog f = soft_fog();
  EXPECT_EQ(fog::ground_fog_density(f, 99.999f), 0.0f);
  EXPECT_EQ(fog::ground_fog_density(f, 100.0f), 1.0f);
  EXPECT_EQ(fog::ground_fog_density(f, 250.0f), 1.0f);
  EXPECT_EQ(fog::ground_fog_density(f, 320.0f), 1.0f);
  EXPECT_FLOAT_EQ(fog::ground_fog_density(f, 360.0f), 0.5f);  // the fade's middle
  EXPECT_EQ(fog::ground_fog_density(f, 400.0f), 0.0f);
  EXPECT_EQ(fog::ground_fog_density(f, 401.0f), 0.0f);
}

TEST(GroundFogProfile, SoftTopIsContinuousWithItsSlopeAndMonotone) {
  const GroundFog f = soft_fog();
  const float e = 1e-3f;
  for (float z : {320.0f, 400.0f}) {
    EXPECT_NEAR(fog::ground_fog_density(f, z - e), fog::ground_fog_density(f, z + e), 1e-5) << z;
    // Smoothstep: the slope is 0 at both ends of the fade (1.5 / soft = 0.019 per m in its middle).
    const float slope =
        (fog::ground_fog_density(f, z + 0.05f) - fog::ground_fog_density(f, z - 0.05f)) / 0.1f;
    EXPECT_NEAR(slope, 0.0f, 1e-4) << z;
  }
  float previous = 1.0f;
  for (float z = 100.0f; z <= 420.0f; z += 0.25f) {
    const float d = fog::ground_fog_density(f, z);
    EXPECT_LE(d, previous) << z;
    EXPECT_GE(d, 0.0f);
    EXPECT_LE(d, 1.0f);
    previous = d;
  }
}

TEST(GroundFogProfile, CumulativeIntegralIsTheDensitysAntiderivative) {
  for (const GroundFog& f : {soft_fog(), hard_fog()}) {
    EXPECT_EQ(fog::ground_fog_cumulative_m(f, 50.0f), 0.0f);
    const double total = double(f.top_m - f.base_m) - 0.5 * f.soft_m;  // 260 m, 300 m
    EXPECT_NEAR(fog::ground_fog_cumulative_m(f, 400.0f), total, 1e-4);
    EXPECT_NEAR(fog::ground_fog_cumulative_m(f, 900.0f), total, 1e-4);
    for (float z = 90.0f; z <= 410.0f; z += 3.1f) {
      // C against the numerical integral of the density; the column above is C(top) - C(z).
      const double c = numerical_optical_depth(f, 0.0, z, z, 100000) / f.sigma_t_per_m;
      EXPECT_NEAR(fog::ground_fog_cumulative_m(f, z), c, 1e-4 * total) << z;
      EXPECT_NEAR(fog::ground_fog_column_above_m(f, z), total - c, 1e-4 * total) << z;
      // dC/dz = density (a central difference, away from the base's and a hard top's jumps).
      if (std::abs(z - f.base_m) > 1.0f && std::abs(z - f.top_m) > 1.0f) {
        const double dc =
            fog::ground_fog_cumulative_m(f, z + 0.5f) - fog::ground_fog_cumulative_m(f, z - 0.5f);
        EXPECT_NEAR(dc, reference_density(f, z), 2e-4) << z;
      }
    }
  }
}

TEST(GroundFogOpticalDepth, MatchesNumericalIntegrationAlongRays) {
  for (const GroundFog& f : {soft_fog(), hard_fog()})
    for (const Ray& r : rays()) {
      const double expected = numerical_optical_depth(f, r.z0_m, r.z1_m, r.length_m);
      const float tau = fog::ground_fog_optical_depth(f, r.z0_m, r.z1_m, r.length_m);
      EXPECT_NEAR(tau, expected, 1e-4 * expected) << r.name << ", soft " << f.soft_m;
      // Either direction along the segment.
      EXPECT_FLOAT_EQ(fog::ground_fog_optical_depth(f, r.z1_m, r.z0_m, r.length_m), tau) << r.name;
    }
}

TEST(GroundFogOpticalDepth, HorizontalRays) {
  const GroundFog f = soft_fog();
  const float sigma = f.sigma_t_per_m;
  // In the body: sigma_t L.
  EXPECT_FLOAT_EQ(fog::ground_fog_optical_depth(f, 250.0f, 250.0f, 5000.0f), sigma * 5000.0f);
  // In the fade: sigma_t L density(z).
  for (float z : {321.0f, 360.0f, 399.0f, 399.99f})
    EXPECT_NEAR(fog::ground_fog_optical_depth(f, z, z, 5000.0f),
                sigma * 5000.0 * reference_density(f, z),
                1e-5 * sigma * 5000.0 * reference_density(f, z))
        << z;
  // Above the top and below the base: none.
  EXPECT_EQ(fog::ground_fog_optical_depth(f, 450.0f, 450.0f, 1e5f), 0.0f);
  EXPECT_EQ(fog::ground_fog_optical_depth(f, 400.0f, 400.0f, 1e5f), 0.0f);
  EXPECT_EQ(fog::ground_fog_optical_depth(f, 50.0f, 50.0f, 1e5f), 0.0f);
  // Rays wholly above or below the layer: none.
  EXPECT_EQ(fog::ground_fog_optical_depth(f, 450.0f, 2000.0f, 3000.0f), 0.0f);
  EXPECT_EQ(fog::ground_fog_optical_depth(f, 2000.0f, 400.0f, 3000.0f), 0.0f);
  EXPECT_EQ(fog::ground_fog_optical_depth(f, 0.0f, 99.0f, 3000.0f), 0.0f);
  // Nearly horizontal rays tend to the horizontal one: no jump at the limit.
  for (float z : {250.0f, 340.0f, 390.0f}) {
    const float flat = fog::ground_fog_optical_depth(f, z, z, 10000.0f);
    for (float dz : {1e-7f, 1e-5f, 1e-3f, 1e-2f}) {
      const float z1 = z + dz;
      EXPECT_NEAR(fog::ground_fog_optical_depth(f, z, z1, 10000.0f), flat,
                  1e-4 * flat + 1.5 * sigma * 10000.0 * (z1 - z) / f.soft_m)
          << z << " " << dz;
    }
  }
}

TEST(GroundFogOpticalDepth, HardTopIsFiniteAndCorrect) {
  const GroundFog f = hard_fog();
  const float sigma = f.sigma_t_per_m;
  EXPECT_EQ(f.soft_m, 0.0f);
  EXPECT_EQ(fog::ground_fog_density(f, 400.0f), 1.0f);
  EXPECT_EQ(fog::ground_fog_density(f, 400.0001f), 0.0f);
  // Horizontal at, just below and just above the top.
  EXPECT_FLOAT_EQ(fog::ground_fog_optical_depth(f, 400.0f, 400.0f, 1000.0f), sigma * 1000.0f);
  EXPECT_FLOAT_EQ(fog::ground_fog_optical_depth(f, 399.99f, 399.99f, 1000.0f), sigma * 1000.0f);
  EXPECT_EQ(fog::ground_fog_optical_depth(f, 400.01f, 400.01f, 1000.0f), 0.0f);
  // Crossing the top: the share of the segment below it, whatever its length.
  for (float dz : {1e-4f, 1e-2f, 1.0f, 100.0f}) {
    const float tau = fog::ground_fog_optical_depth(f, 400.0f - dz, 400.0f + dz, 1000.0f);
    EXPECT_TRUE(std::isfinite(tau)) << dz;
    EXPECT_NEAR(tau, 0.5f * sigma * 1000.0f, 2e-3 * sigma * 1000.0f) << dz;
  }
  // The soft top's limit: a softness of 1 mm barely differs from none.
  const GroundFog thin = fog::ground_fog_layer(100.0f, 400.0f, 1e-3f, 300.0f, 1.0f);
  for (const Ray& r : rays()) {
    const float hard = fog::ground_fog_optical_depth(f, r.z0_m, r.z1_m, r.length_m);
    const float soft = fog::ground_fog_optical_depth(thin, r.z0_m, r.z1_m, r.length_m);
    EXPECT_TRUE(std::isfinite(soft)) << r.name;
    // At most the fade's missing half-millimetre of fog along the segment's altitude range.
    const double bound = sigma * r.length_m * 0.5e-3 / std::max(std::abs(r.z1_m - r.z0_m), 1e-3f);
    EXPECT_NEAR(soft, hard, 1e-4 * hard + bound) << r.name;
  }
  // The column: exactly the thickness at the base, nothing at and above the top.
  EXPECT_FLOAT_EQ(fog::ground_fog_column_above_m(f, 100.0f), 300.0f);
  EXPECT_EQ(fog::ground_fog_column_above_m(f, 400.0f), 0.0f);
  EXPECT_EQ(fog::ground_fog_column_above_m(f, 500.0f), 0.0f);
}

TEST(GroundFogLayer, SoftnessAndTopAreClampedToALayer) {
  // A softness over the thickness: the fade spans the whole layer.
  const GroundFog f = fog::ground_fog_layer(100.0f, 200.0f, 500.0f, 200.0f, 1.0f);
  EXPECT_EQ(f.soft_m, 100.0f);
  EXPECT_EQ(fog::ground_fog_density(f, 100.0f), 1.0f);
  EXPECT_FLOAT_EQ(fog::ground_fog_cumulative_m(f, 300.0f), 50.0f);
  const double expected = numerical_optical_depth(f, 50.0, 250.0, 400.0);
  EXPECT_NEAR(fog::ground_fog_optical_depth(f, 50.0f, 250.0f, 400.0f), expected, 1e-4 * expected);
  // A negative softness: a hard top.
  EXPECT_EQ(fog::ground_fog_layer(100.0f, 200.0f, -5.0f, 200.0f, 1.0f).soft_m, 0.0f);
  // A top below the base: no fog, and nothing undefined.
  const GroundFog empty = fog::ground_fog_layer(300.0f, 100.0f, 20.0f, 200.0f, 1.0f);
  EXPECT_EQ(empty.top_m, 300.0f);
  EXPECT_EQ(empty.soft_m, 0.0f);
  for (float z : {0.0f, 299.0f, 300.0f, 301.0f}) {
    EXPECT_EQ(fog::ground_fog_optical_depth(empty, z, z + 10.0f, 100.0f), 0.0f) << z;
    EXPECT_EQ(fog::ground_fog_sun_transmittance(empty, z, 0.0f, float(kEarthRadiusM)), 1.0f) << z;
  }
}

TEST(GroundFogInFront, TransmittanceAndInScatterShareTheEnergy) {
  const GroundFog f = soft_fog();
  for (const Ray& r : rays()) {
    const glm::vec4 v = fog::ground_fog_in_front(f, r.z0_m, r.z1_m, r.length_m);
    const double tau = numerical_optical_depth(f, r.z0_m, r.z1_m, r.length_m);
    EXPECT_NEAR(v.a, std::exp(-tau), 1e-4 * std::exp(-tau) + 1e-7) << r.name;
    // Albedo 1: what is not transmitted is scattered in, the same in every channel.
    EXPECT_NEAR(v.r + v.a, 1.0f, 1e-6) << r.name;
    EXPECT_EQ(v.r, v.g);
    EXPECT_EQ(v.r, v.b);
  }
  // A ray that never enters the fog: nothing added, everything transmitted.
  for (const Ray& r : std::vector<Ray>{{"above", 450.0f, 3000.0f, 4000.0f},
                                       {"above, horizontal", 401.0f, 401.0f, 1e5f},
                                       {"below", 10.0f, 90.0f, 2000.0f}}) {
    const glm::vec4 v = fog::ground_fog_in_front(f, r.z0_m, r.z1_m, r.length_m);
    EXPECT_EQ(v.r, 0.0f) << r.name;
    EXPECT_EQ(v.a, 1.0f) << r.name;
  }
  // A thick fog hides the surface and replaces it by the lighting.
  const glm::vec4 deep = fog::ground_fog_in_front(f, 200.0f, 200.0f, 1e5f);
  EXPECT_EQ(deep.a, 0.0f);
  EXPECT_FLOAT_EQ(deep.r, 1.0f);
}

// The in-scatter is albedo (1 - T) for any density along the ray: the integral of
// sigma_s(t) T(0, t) dt, computed numerically, along a ray through the soft top.
TEST(GroundFogInFront, InScatterIsTheIntegralOfScatteringTimesTransmittance) {
  const GroundFog f = fog::ground_fog_layer(100.0f, 400.0f, 80.0f, 300.0f, 0.9f);
  for (const Ray& r : rays()) {
    const int n = 200000;
    double tau = 0.0, inscatter = 0.0;
    const double dt = double(r.length_m) / n;
    for (int i = 0; i < n; ++i) {
      const double z = r.z0_m + (double(r.z1_m) - r.z0_m) * (i + 0.5) / n;
      const double sigma_t = f.sigma_t_per_m * reference_density(f, z);
      // The step's exact share for constant sigma_t over it: T (1 - exp(-sigma_t dt)).
      inscatter += f.albedo * std::exp(-tau) * -std::expm1(-sigma_t * dt);
      tau += sigma_t * dt;
    }
    const glm::vec4 v = fog::ground_fog_in_front(f, r.z0_m, r.z1_m, r.length_m);
    EXPECT_NEAR(v.g, inscatter, 1e-4 * inscatter + 1e-7) << r.name;
    EXPECT_NEAR(v.g, 0.9 * (1.0 - v.a), 1e-6) << r.name;
  }
}

TEST(GroundFogSun, HighSunIsTheColumnOverTheElevationSine) {
  const GroundFog f = soft_fog();
  for (float z : {50.0f, 100.0f, 250.0f, 350.0f, 399.0f})
    for (float elevation_deg : {10.0f, 30.0f, 60.0f, 90.0f}) {
      const float mu = std::sin(elevation_deg * float(M_PI) / 180.0f);
      const float tau = fog::ground_fog_sun_optical_depth(f, z, mu, float(kEarthRadiusM));
      EXPECT_FLOAT_EQ(fog::ground_fog_sun_transmittance(f, z, mu, float(kEarthRadiusM)),
                      std::exp(-tau));
      // Flat earth: sigma_t column / sin(elevation), within the sphere's h / 2r (and more
      // near the horizon: 0.05% at 10 degrees).
      const double flat = f.sigma_t_per_m * reference_density_column(f, z) / mu;
      EXPECT_NEAR(tau, flat, 1e-3 * flat) << z << " " << elevation_deg;
    }
}

TEST(GroundFogSun, MatchesTheSpheresSlantPathDownToTheHorizon) {
  // On the sphere the path climbs ever faster: near the horizon it spends longer low in the
  // layer than the column / sin(elevation) says (which is infinite at the horizon).
  for (const GroundFog& f : {hard_fog(), soft_fog()})
    for (float z : {100.0f, 250.0f, 330.0f, 390.0f})
      for (float elevation_deg : {90.0f, 30.0f, 5.0f, 2.0f, 0.5f, 0.0f}) {
        const float mu = std::sin(elevation_deg * float(M_PI) / 180.0f);
        const float tau = fog::ground_fog_sun_optical_depth(f, z, mu, float(kEarthRadiusM));
        const double expected = numerical_sun_depth(f, z, mu);
        const double tolerance = 1e-4;
        ASSERT_TRUE(std::isfinite(tau)) << z << " " << elevation_deg;
        EXPECT_NEAR(tau, expected, tolerance * expected)
            << "soft " << f.soft_m << " z " << z << " elevation " << elevation_deg;
      }
}

TEST(GroundFogSun, LimitsAndMonotony) {
  const GroundFog f = soft_fog();
  const float r = float(kEarthRadiusM);
  // At and above the top: no fog in the way.
  EXPECT_EQ(fog::ground_fog_sun_transmittance(f, 400.0f, 0.3f, r), 1.0f);
  EXPECT_EQ(fog::ground_fog_sun_transmittance(f, 400.0f, 0.0f, r), 1.0f);
  EXPECT_EQ(fog::ground_fog_sun_transmittance(f, 1000.0f, 0.0f, r), 1.0f);
  // Below the base: as at the base (the clear air under it does not dim the sun).
  EXPECT_EQ(fog::ground_fog_sun_transmittance(f, 20.0f, 0.4f, r),
            fog::ground_fog_sun_transmittance(f, 100.0f, 0.4f, r));
  // Straight up: sigma_t times the column.
  EXPECT_NEAR(-std::log(fog::ground_fog_sun_transmittance(f, 100.0f, 1.0f, r)),
              f.sigma_t_per_m * 260.0, 1e-4 * f.sigma_t_per_m * 260.0);
  // A sun below the horizon is taken at the horizon; near the top, grazing stays finite.
  EXPECT_EQ(fog::ground_fog_sun_transmittance(f, 300.0f, -0.2f, r),
            fog::ground_fog_sun_transmittance(f, 300.0f, 0.0f, r));
  float below = 0.0f;
  for (float z : {399.0f, 399.99f, 399.9999f}) {
    const float t = fog::ground_fog_sun_transmittance(f, z, 0.0f, r);
    EXPECT_TRUE(std::isfinite(t)) << z;
    EXPECT_GT(t, 0.98f) << z;
    EXPECT_GT(t, below) << z;
    below = t;
  }
  EXPECT_GT(below, 0.99999f);
  // A uniform layer with the sun on the horizon: sigma_t times the horizontal distance to the
  // top's sphere, sqrt(2 r h) (13.8 km through 300 m of fog over the earth), not 1 / 0.
  const GroundFog hard = hard_fog();
  const double r_base = kEarthRadiusM + 100.0;
  const double horizontal_m = std::sqrt(2.0 * r_base * 300.0);
  EXPECT_NEAR(fog::ground_fog_sun_optical_depth(hard, 100.0f, 0.0f, r),
              hard.sigma_t_per_m * horizontal_m, 1e-4 * hard.sigma_t_per_m * horizontal_m);
  // Brighter the higher the sun, and the higher the point.
  for (float z = 60.0f; z <= 410.0f; z += 10.0f) {
    float previous = 0.0f;
    for (float mu = 0.0f; mu <= 1.0f; mu += 0.05f) {
      const float t = fog::ground_fog_sun_transmittance(f, z, mu, r);
      EXPECT_GE(t, previous) << z << " " << mu;
      previous = t;
    }
  }
  for (float mu : {0.0f, 0.1f, 0.5f}) {
    float previous = 0.0f;
    for (float z = 60.0f; z <= 410.0f; z += 2.5f) {
      const float t = fog::ground_fog_sun_transmittance(f, z, mu, r);
      EXPECT_GE(t, previous) << z << " " << mu;
      previous = t;
    }
  }
}

}  // namespace

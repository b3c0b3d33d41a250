// The Preetham et al. (1999) analytic daylight sky (shaders/common/preetham_inc.glsl compiled
// as C++) against its closed forms, recomputed here in double precision, and against the
// qualitative behaviour of a clear sky.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "render/glsl.h"

namespace g = nephele::glsl;
using glm::vec2;
using glm::vec3;

namespace {

const vec3 kUp(0.0f, 0.0f, 1.0f);

double deg(double d) { return d * M_PI / 180.0; }

// Unit direction at elevation `elev_deg` above the horizon and azimuth `az_deg` (z up).
vec3 direction(double elev_deg, double az_deg) {
  double e = deg(elev_deg), a = deg(az_deg);
  return vec3(float(std::cos(e) * std::cos(a)), float(std::cos(e) * std::sin(a)),
              float(std::sin(e)));
}

// Y_z (kcd/m^2), appendix A.2 of the paper, in double precision.
double zenith_luminance_kcd(double T, double theta_s) {
  double chi = (4.0 / 9.0 - T / 120.0) * (M_PI - 2.0 * theta_s);
  return (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;
}

// (T^2, T, 1) M (theta_s^3, theta_s^2, theta_s, 1)^T with the paper's 3x4 matrix M.
double zenith_chromaticity(const double (&m)[3][4], double T, double theta_s) {
  const double row[3] = {T * T, T, 1.0};
  const double col[4] = {theta_s * theta_s * theta_s, theta_s * theta_s, theta_s, 1.0};
  double sum = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 4; ++j) sum += row[i] * m[i][j] * col[j];
  return sum;
}

const double kMx[3][4] = {{0.00166, -0.00375, 0.00209, 0.0},
                          {-0.02903, 0.06377, -0.03202, 0.00394},
                          {0.11693, -0.21196, 0.06052, 0.25886}};
const double kMy[3][4] = {{0.00275, -0.00610, 0.00317, 0.0},
                          {-0.04214, 0.08970, -0.04153, 0.00516},
                          {0.15346, -0.26756, 0.06670, 0.26688}};

// Luminance (Rec. 709 weights) of a linear sRGB colour.
double luminance(vec3 c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

// (max - min) / max of a linear sRGB colour: 0 for grey.
double saturation(vec3 c) {
  double hi = std::max({c.x, c.y, c.z}), lo = std::min({c.x, c.y, c.z});
  return (hi - lo) / hi;
}

bool finite(vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

TEST(PreethamZenith, LuminanceMatchesClosedForm) {
  for (double T : {2.0, 2.5, 4.0, 6.0, 10.0}) {
    for (double theta_s : {0.0, 0.3, deg(30.0), deg(60.0), 1.3, M_PI / 2.0}) {
      double expected = zenith_luminance_kcd(T, theta_s);
      EXPECT_NEAR(g::preetham_zenith_luminance_kcd(float(T), float(theta_s)), expected,
                  1e-4 * std::abs(expected) + 1e-5)
          << "T = " << T << ", theta_s = " << theta_s;
    }
  }
  // With the sun at the horizon chi = 0: Y_z = -0.2155 T + 2.4192 exactly.
  EXPECT_NEAR(g::preetham_zenith_luminance_kcd(3.0f, float(M_PI / 2.0)), -0.2155 * 3.0 + 2.4192,
              1e-5);
}

TEST(PreethamZenith, ChromaticityMatchesPaperMatrices) {
  for (double T : {2.0, 2.5, 4.0, 6.0, 10.0}) {
    for (double theta_s : {0.0, 0.3, deg(30.0), deg(60.0), 1.3, M_PI / 2.0}) {
      vec2 xy = g::preetham_zenith_chromaticity(float(T), float(theta_s));
      EXPECT_NEAR(xy.x, zenith_chromaticity(kMx, T, theta_s), 2e-6)
          << "T = " << T << ", theta_s = " << theta_s;
      EXPECT_NEAR(xy.y, zenith_chromaticity(kMy, T, theta_s), 2e-6)
          << "T = " << T << ", theta_s = " << theta_s;
      // A daylight zenith: bluish to white, well inside the spectral locus.
      EXPECT_GT(xy.x, 0.2f);
      EXPECT_LT(xy.x, 0.35f);
      EXPECT_GT(xy.y, 0.2f);
      EXPECT_LT(xy.y, 0.37f);
    }
  }
}

TEST(PreethamPerez, MatchesFormula) {
  const double A = -1.0, B = -0.46, C = 5.27, D = -2.28, E = 0.20;
  for (double cos_theta : {1.0, 0.5, 0.1}) {
    for (double gamma : {0.0, 0.4, 1.5, 3.0}) {
      double cg = std::cos(gamma);
      double expected =
          (1.0 + A * std::exp(B / cos_theta)) * (1.0 + C * std::exp(D * gamma) + E * cg * cg);
      EXPECT_NEAR(g::preetham_perez(float(A), float(B), float(C), float(D), float(E),
                                    float(cos_theta), float(gamma)),
                  expected, 1e-5 * std::abs(expected));
    }
  }
}

// The full model in double precision, with the distribution coefficients written as the
// paper's appendix A.2 table: {slope, intercept} of A..E for Y, x and y.
TEST(Preetham, MatchesPaperTableInDouble) {
  const double kY[5][2] = {{0.1787, -1.4630}, {-0.3554, 0.4275}, {-0.0227, 5.3251},
                           {0.1206, -2.5771}, {-0.0670, 0.3703}};
  const double kX[5][2] = {{-0.0193, -0.2592}, {-0.0665, 0.0008}, {-0.0004, 0.2125},
                           {-0.0641, -0.8989}, {-0.0033, 0.0452}};
  const double kYc[5][2] = {{-0.0167, -0.2608}, {-0.0950, 0.0092}, {-0.0079, 0.2102},
                            {-0.0441, -1.6537}, {-0.0109, 0.0529}};
  auto perez = [](const double (&k)[5][2], double T, double cos_theta, double gamma) {
    double c[5];
    for (int i = 0; i < 5; ++i) c[i] = k[i][0] * T + k[i][1];
    double cg = std::cos(gamma);
    return (1.0 + c[0] * std::exp(c[1] / cos_theta)) *
           (1.0 + c[2] * std::exp(c[3] * gamma) + c[4] * cg * cg);
  };
  for (double T : {2.0, 2.5, 4.0, 7.0}) {
    for (double theta_s : {0.2, deg(45.0), 1.4}) {
      for (double cos_theta : {0.9, 0.5, 0.1}) {
        for (double gamma : {0.05, 0.8, 2.5}) {
          double Y = 1000.0 * zenith_luminance_kcd(T, theta_s) * perez(kY, T, cos_theta, gamma) /
                     perez(kY, T, 1.0, theta_s);
          double x = zenith_chromaticity(kMx, T, theta_s) * perez(kX, T, cos_theta, gamma) /
                     perez(kX, T, 1.0, theta_s);
          double y = zenith_chromaticity(kMy, T, theta_s) * perez(kYc, T, cos_theta, gamma) /
                     perez(kYc, T, 1.0, theta_s);
          vec3 got = g::preetham_xyY(float(T), float(cos_theta), float(gamma), float(theta_s));
          EXPECT_NEAR(got.x, x, 1e-5) << T << " " << theta_s << " " << cos_theta << " " << gamma;
          EXPECT_NEAR(got.y, y, 1e-5) << T << " " << theta_s << " " << cos_theta << " " << gamma;
          EXPECT_NEAR(got.z, Y, 1e-4 * Y) << T << " " << theta_s << " " << cos_theta << " "
                                          << gamma;
        }
      }
    }
  }
}

TEST(Preetham, ZenithViewReturnsZenithValues) {
  for (float T : {2.0f, 2.5f, 5.0f, 9.0f}) {
    for (float theta_s : {0.1f, 0.7f, 1.2f, 1.5f}) {
      // At the zenith gamma = theta_s, so the Perez ratio F(0, theta_s) / F(0, theta_s) is 1.
      vec3 xyY = g::preetham_xyY(T, 1.0f, theta_s, theta_s);
      vec2 xy_z = g::preetham_zenith_chromaticity(T, theta_s);
      EXPECT_FLOAT_EQ(xyY.x, xy_z.x);
      EXPECT_FLOAT_EQ(xyY.y, xy_z.y);
      EXPECT_FLOAT_EQ(xyY.z, 1000.0f * g::preetham_zenith_luminance_kcd(T, theta_s));
    }
  }
  // Through the direction interface: looking straight up gives Y_z / 128000 lux.
  vec3 sun = direction(40.0, 0.0);
  vec3 rgb = g::preetham_sky_radiance(3.0f, kUp, sun, kUp);
  float theta_s = std::acos(sun.z);
  double Y_z = 1000.0 * zenith_luminance_kcd(3.0, theta_s) / 128000.0;
  EXPECT_NEAR(luminance(rgb), Y_z, 2e-3 * Y_z);
}

TEST(Preetham, ZenithRadianceInRendererRange) {
  // T = 2.5: clear zenith by day lands where the renderer's physical sky does (0.03 to 0.08
  // per sr per unit solar illuminance).
  const float T = 2.5f;
  for (double elev : {30.0, 60.0}) {
    vec3 rgb = g::preetham_sky_radiance(T, kUp, direction(elev, 0.0), kUp);
    vec3 horizon = g::preetham_sky_radiance(T, direction(1.0, 90.0), direction(elev, 0.0), kUp);
    std::printf("[ preetham ] T = 2.5, sun %2.0f deg: zenith rgb (%.4f, %.4f, %.4f) /sr, "
                "luminance %.4f /sr; horizon (1 deg up, 90 deg from sun) luminance %.4f /sr, "
                "horizon/zenith %.2f\n",
                elev, rgb.x, rgb.y, rgb.z, luminance(rgb), luminance(horizon),
                luminance(horizon) / luminance(rgb));
    EXPECT_GT(luminance(rgb), 0.03) << "sun elevation " << elev;
    EXPECT_LT(luminance(rgb), 0.08) << "sun elevation " << elev;
  }
  // Higher sun, brighter zenith.
  EXPECT_GT(luminance(g::preetham_sky_radiance(T, kUp, direction(60.0, 0.0), kUp)),
            luminance(g::preetham_sky_radiance(T, kUp, direction(30.0, 0.0), kUp)));
}

TEST(Preetham, BrighterTowardsTheSun) {
  for (float T : {2.5f, 6.0f}) {
    for (double sun_elev : {20.0, 45.0, 70.0}) {
      vec3 sun = direction(sun_elev, 0.0);
      for (double view_elev : {10.0, 30.0}) {
        double near = luminance(g::preetham_sky_radiance(T, direction(view_elev, 15.0), sun, kUp));
        double side = luminance(g::preetham_sky_radiance(T, direction(view_elev, 90.0), sun, kUp));
        EXPECT_GT(near, side) << "T = " << T << ", sun " << sun_elev << ", view " << view_elev;
      }
      // The circumsolar sky (3 deg above the sun) outshines the zenith, by more than twice
      // while the zenith is well away from the sun.
      double at_sun = luminance(g::preetham_sky_radiance(T, direction(sun_elev + 3.0, 0.0),
                                                         sun, kUp));
      double zenith = luminance(g::preetham_sky_radiance(T, kUp, sun, kUp));
      EXPECT_GT(at_sun, (sun_elev < 60.0 ? 2.0 : 1.0) * zenith)
          << "T = " << T << ", sun " << sun_elev;
    }
  }
}

TEST(Preetham, SymmetricAboutTheSunsVertical) {
  vec3 sun = direction(35.0, 0.0);
  for (double az : {20.0, 90.0, 150.0}) {
    vec3 a = g::preetham_sky_radiance(3.0f, direction(25.0, az), sun, kUp);
    vec3 b = g::preetham_sky_radiance(3.0f, direction(25.0, -az), sun, kUp);
    EXPECT_NEAR(a.x, b.x, 1e-5f * (1.0f + a.x));
    EXPECT_NEAR(a.y, b.y, 1e-5f * (1.0f + a.y));
    EXPECT_NEAR(a.z, b.z, 1e-5f * (1.0f + a.z));
  }
}

TEST(Preetham, ClearZenithIsBlueAndHorizonWhiter) {
  const float T = 2.5f;
  for (double sun_elev : {45.0, 60.0, 75.0}) {
    vec3 sun = direction(sun_elev, 0.0);
    vec3 zenith = g::preetham_sky_radiance(T, kUp, sun, kUp);
    EXPECT_GT(zenith.z, zenith.x) << "sun " << sun_elev;  // blue > red
    EXPECT_GT(zenith.z, zenith.y) << "sun " << sun_elev;  // blue > green
    for (double az : {90.0, 180.0}) {
      vec3 horizon = g::preetham_sky_radiance(T, direction(2.0, az), sun, kUp);
      EXPECT_LT(saturation(horizon), saturation(zenith)) << "sun " << sun_elev << ", az " << az;
      // ... and brighter (the horizon brightening of a clear sky), unless the sun is so high
      // that the zenith lies in its aureole (at 75 deg the zenith wins in this model).
      if (sun_elev <= 60.0) {
        EXPECT_GT(luminance(horizon), luminance(zenith)) << "sun " << sun_elev << ", az " << az;
      }
    }
  }
}

// What turbidity does in this model. Haze brightens and whitens the zenith (Y_z grows with T,
// the zenith chromaticity moves towards white), and it flattens the gradation from zenith to
// horizon: A_Y = 0.1787 T - 1.4630 rises towards 0, so the zenith factor 1 + A_Y exp(B_Y) of
// the Perez function rises towards 1 and the horizon/zenith luminance ratio FALLS with T
// (about 4.3 at T = 2, 2.0 at T = 2.5, 0.6 at T = 8 for a 30 deg sun, 2 deg above the horizon
// 120 deg from the sun). The horizon reddens towards yellow-orange as T grows.
TEST(Preetham, TurbidityBrightensAndWhitensZenithAndFlattensGradation) {
  for (double sun_elev : {30.0, 60.0}) {
    vec3 sun = direction(sun_elev, 0.0);
    double prev_zenith = 0.0, prev_ratio = 1e9, prev_saturation = 1.0, prev_horizon_br = 1e9;
    for (float T : {2.0f, 3.0f, 5.0f, 8.0f}) {
      vec3 zenith = g::preetham_sky_radiance(T, kUp, sun, kUp);
      vec3 horizon = g::preetham_sky_radiance(T, direction(2.0, 120.0), sun, kUp);
      double ratio = luminance(horizon) / luminance(zenith);
      EXPECT_GT(luminance(zenith), prev_zenith) << "T = " << T << ", sun " << sun_elev;
      EXPECT_LT(saturation(zenith), prev_saturation) << "T = " << T << ", sun " << sun_elev;
      EXPECT_LT(ratio, prev_ratio) << "T = " << T << ", sun " << sun_elev;
      // The horizon's blue/red falls: it turns from bluish white to yellow-orange.
      EXPECT_LT(horizon.z / horizon.x, prev_horizon_br) << "T = " << T << ", sun " << sun_elev;
      prev_zenith = luminance(zenith);
      prev_saturation = saturation(zenith);
      prev_ratio = ratio;
      prev_horizon_br = horizon.z / horizon.x;
    }
  }
}

TEST(Preetham, ClampsSunBelowHorizonAndViewsBelowHorizon) {
  const float T = 3.0f;
  // A sun below the horizon is treated as a sun at the horizon for the zenith values.
  vec3 below = g::preetham_sky_radiance(T, kUp, direction(-10.0, 0.0), kUp);
  vec3 xyY = g::preetham_xyY(T, 1.0f, float(M_PI / 2.0), float(deg(100.0)));
  double Y_horizon_sun = 1000.0 * zenith_luminance_kcd(T, M_PI / 2.0) / 128000.0;
  EXPECT_NEAR(xyY.z / 128000.0f, Y_horizon_sun, 1e-4 * Y_horizon_sun);
  EXPECT_NEAR(luminance(below), Y_horizon_sun, 0.05 * Y_horizon_sun);  // gamma differs a bit
  // A view below the horizon gets the horizon's value (cos theta clamped).
  vec3 sun = direction(40.0, 0.0);
  vec3 down = g::preetham_sky_radiance(T, direction(-20.0, 90.0), sun, kUp);
  vec3 level = g::preetham_sky_radiance(T, direction(0.0, 90.0), sun, kUp);
  vec3 down_xyY = g::preetham_xyY(T, -0.3f, 1.0f, 0.5f);
  vec3 level_xyY = g::preetham_xyY(T, 0.01f, 1.0f, 0.5f);
  EXPECT_FLOAT_EQ(down_xyY.z, level_xyY.z);
  EXPECT_TRUE(finite(down));
  EXPECT_NEAR(luminance(down), luminance(level), 0.1 * luminance(level));  // gamma differs
}

TEST(Preetham, FiniteAndNonNegativeEverywhere) {
  for (float T : {1.0f, 2.0f, 2.5f, 6.0f, 10.0f, 15.0f}) {
    for (double sun_elev : {-20.0, -1.0, 0.0, 0.5, 10.0, 45.0, 89.9, 90.0}) {
      vec3 sun = direction(sun_elev, 0.0);
      for (double view_elev : {-90.0, -10.0, 0.0, 0.3, 5.0, 45.0, 90.0}) {
        for (double az : {0.0, 45.0, 180.0}) {
          vec3 rgb = g::preetham_sky_radiance(T, direction(view_elev, az), sun, kUp);
          EXPECT_TRUE(finite(rgb)) << "T = " << T << ", sun " << sun_elev << ", view "
                                   << view_elev << ", az " << az;
          EXPECT_GE(luminance(rgb), 0.0) << "T = " << T << ", sun " << sun_elev << ", view "
                                         << view_elev << ", az " << az;
        }
      }
    }
  }
}

TEST(PreethamColour, D65WhiteMapsToOne) {
  vec3 white = g::xyY_to_linear_srgb(vec3(0.3127f, 0.3290f, 1.0f));
  EXPECT_NEAR(white.x, 1.0f, 1e-3f);
  EXPECT_NEAR(white.y, 1.0f, 1e-3f);
  EXPECT_NEAR(white.z, 1.0f, 1e-3f);
  // Linear in Y.
  vec3 half = g::xyY_to_linear_srgb(vec3(0.3127f, 0.3290f, 0.5f));
  EXPECT_NEAR(half.x, 0.5f * white.x, 1e-6f);
  EXPECT_NEAR(half.z, 0.5f * white.z, 1e-6f);
  // The sRGB primaries' chromaticities map to pure primaries, with Y the luminance weight.
  vec3 red = g::xyY_to_linear_srgb(vec3(0.64f, 0.33f, 0.2126f));
  EXPECT_NEAR(red.x, 1.0f, 2e-3f);
  EXPECT_NEAR(red.y, 0.0f, 2e-3f);
  EXPECT_NEAR(red.z, 0.0f, 2e-3f);
  vec3 blue = g::xyY_to_linear_srgb(vec3(0.15f, 0.06f, 0.0722f));
  EXPECT_NEAR(blue.x, 0.0f, 2e-3f);
  EXPECT_NEAR(blue.y, 0.0f, 2e-3f);
  EXPECT_NEAR(blue.z, 1.0f, 2e-3f);
}

// The classical cloud models' pure functions (shaders/common/classic_inc.glsl, seed 004,
// issue 23) against closed forms, quadratures and spectra.
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <vector>

#include "render/glsl.h"

namespace nephele {
namespace {

using glsl::blinn_layer;
using glsl::blinn_phase;
using glsl::blinn_reflection;
using glsl::blinn_transmission;

constexpr double kPi = 3.14159265358979323846;

// (1 / 4 pi) integral over the sphere of phi(alpha) g(cos alpha): a midpoint rule in alpha.
double sphere_mean(const std::function<double(double)>& phi, const std::function<double(double)>& g) {
  const int n = 20000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double alpha = (i + 0.5) * kPi / n;
    sum += phi(alpha) * g(std::cos(alpha)) * std::sin(alpha) * kPi / n;
  }
  return 0.5 * sum;
}

// Every one of Blinn's phase functions has a mean of 1 over the sphere (his normalisation:
// phi / 4 pi integrates to 1), and the parametrised ones the mean cosine of their parameter:
// x / 3 for 1 + x cos alpha, g for Henyey-Greenstein. The seed's Lambert factor (8/3) pi
// instead of 8 / (3 pi) breaks the normalisation by pi^2.
TEST(BlinnPhase, EveryFunctionHasAMeanOfOneAndItsMeanCosine) {
  struct Case {
    int kind;
    float x;
    double mean_cosine;
  };
  const std::vector<Case> cases = {
      {glsl::BLINN_PHASE_CONSTANT, 0.0f, 0.0},
      {glsl::BLINN_PHASE_ANISOTROPIC, 0.6f, 0.2},
      {glsl::BLINN_PHASE_ANISOTROPIC, -0.9f, -0.3},
      // The Lambert sphere reflects: mostly back towards the light (alpha = 0).
      {glsl::BLINN_PHASE_LAMBERT, 0.0f, 4.0 / 9.0},
      {glsl::BLINN_PHASE_RAYLEIGH, 0.0f, 0.0},
      {glsl::BLINN_PHASE_HG, 0.5f, 0.5},
      {glsl::BLINN_PHASE_HG, -0.7f, -0.7},
  };
  for (const Case& c : cases) {
    const auto phi = [&](double alpha) {
      return double(blinn_phase(c.kind, c.x, float(std::cos(alpha)), false));
    };
    EXPECT_NEAR(sphere_mean(phi, [](double) { return 1.0; }), 1.0, 2e-3) << c.kind << " " << c.x;
    EXPECT_NEAR(sphere_mean(phi, [](double mu) { return mu; }), c.mean_cosine, 2e-3)
        << c.kind << " " << c.x;
  }
  const auto seed_lambert = [](double alpha) {
    return double(blinn_phase(glsl::BLINN_PHASE_LAMBERT, 0.0f, float(std::cos(alpha)), true));
  };
  EXPECT_NEAR(sphere_mean(seed_lambert, [](double) { return 1.0; }), kPi * kPi, 2e-2);
  // The functions at their landmarks: Lambert's full and new phase, Rayleigh's.
  EXPECT_NEAR(blinn_phase(glsl::BLINN_PHASE_LAMBERT, 0.0f, 1.0f, false), 8.0 / 3.0, 1e-5);
  EXPECT_NEAR(blinn_phase(glsl::BLINN_PHASE_LAMBERT, 0.0f, -1.0f, false), 0.0, 1e-5);
  EXPECT_NEAR(blinn_phase(glsl::BLINN_PHASE_RAYLEIGH, 0.0f, 0.0f, false), 0.75, 1e-6);
}

// The single-scattering integral through the layer, summed slice by slice: light attenuated
// down to depth t along mu0, scattered, attenuated out along mu (on its own side, or through
// the rest of the layer).
double layer_quadrature(double tau, double mu, double mu0, bool same_side) {
  const int n = 200000;
  double sum = 0.0;
  for (int i = 0; i < n; ++i) {
    const double t = (i + 0.5) * tau / n;
    const double out = same_side ? t : tau - t;
    sum += std::exp(-t / mu0) * std::exp(-out / mu) * (tau / n) / mu;
  }
  return sum;  // Blinn's B per omega phi
}

TEST(BlinnLayer, MatchesTheSingleScatteringIntegralForManyDepthsAndAngles) {
  for (const double tau : {0.01, 0.3, 1.0, 4.0, 20.0})
    for (const double mu : {0.1, 0.45, 1.0})
      for (const double mu0 : {0.2, 0.45, 0.8}) {
        const double reflected = layer_quadrature(tau, mu, mu0, true);
        const double transmitted = layer_quadrature(tau, mu, mu0, false);
        EXPECT_NEAR(blinn_reflection(float(tau), float(mu), float(mu0)), reflected,
                    1e-4 + 1e-4 * reflected)
            << tau << " " << mu << " " << mu0;
        EXPECT_NEAR(blinn_transmission(float(tau), float(mu), float(mu0)), transmitted,
                    1e-4 + 1e-3 * transmitted)
            << tau << " " << mu << " " << mu0;
      }
  // mu = mu0 exactly and nearly: the limit (tau/mu) e^(-tau/mu), the seed's s, continuously.
  for (const float tau : {0.2f, 1.0f, 5.0f})
    for (const float mu : {0.3f, 0.7f}) {
      const double s = tau / mu * std::exp(-tau / mu);
      EXPECT_NEAR(blinn_transmission(tau, mu, mu), s, 1e-6);
      EXPECT_NEAR(blinn_transmission(tau, mu, mu * (1.0f + 1e-5f)), s, 1e-4);
      EXPECT_NEAR(blinn_transmission(tau, mu, mu * (1.0f + 2e-2f)),
                  layer_quadrature(tau, mu, mu * (1.0 + 2e-2), false), 1e-4);
    }
}

// B and Tr: Blinn's (the general geometry) and the seed's printing, which agrees with Blinn's
// only for light from behind along the view, and adds omega phi(pi) to the transparency.
TEST(BlinnLayer, TheOriginalAndTheSeedsForms) {
  const float tau = 1.5f, mu = 0.6f, omega = 0.8f, phi = 1.3f, phi_pi = 0.4f;
  const glm::vec2 behind = blinn_layer(tau, mu, mu, false, omega, phi, phi_pi, false);
  EXPECT_NEAR(behind.x, omega * phi * tau / mu * std::exp(-tau / mu), 1e-6);
  EXPECT_NEAR(behind.y, std::exp(-tau / mu), 1e-7);
  const glm::vec2 seed = blinn_layer(tau, mu, mu, false, omega, phi, phi_pi, true);
  EXPECT_NEAR(seed.x, behind.x / mu, 1e-6);  // the seed's extra 1/mu
  EXPECT_NEAR(seed.y, behind.y + omega * phi_pi, 1e-7);
  const glm::vec2 front = blinn_layer(tau, mu, 0.9f, true, omega, phi, phi_pi, false);
  EXPECT_NEAR(front.x, omega * phi * blinn_reflection(tau, mu, 0.9f), 1e-7);
  // Without particles, nothing scattered and everything let through.
  const glm::vec2 none = blinn_layer(0.0f, mu, 0.9f, true, omega, phi, phi_pi, false);
  EXPECT_EQ(none.x, 0.0f);
  EXPECT_EQ(none.y, 1.0f);
  EXPECT_NEAR(glsl::blinn_optical_depth(1e8f, 10e-6f, 1000.0f), 1e8 * kPi * 1e-10 * 1000.0, 1e-3);
}

// Gardner's texture is k (sum_x + T0)(sum_y + T0); along x (y and z fixed) the x factor is a
// sum of sines at FX_1, 2 FX_1, 4 FX_1, ... with amplitudes falling by 0.707 a term,
// phase-shifted by a constant (PX_i depends on y and z only). A DFT of a strip shows exactly
// those lines.
TEST(GardnerTexture, ItsSpectrumHasTheDoublingFrequenciesAndFallingAmplitudes) {
  const int n = 4096, terms = 5;
  const float length_m = 4096.0f;
  const float f1 = 2.0f * float(kPi) * 4.0f / length_m;  // 4 periods over the strip
  const glm::vec3 at(0.0f, 37.0f, 11.0f);
  std::vector<std::complex<double>> strip(n);
  for (int i = 0; i < n; ++i) {
    const glm::vec3 p = at + glm::vec3(length_m * float(i) / float(n), 0.0f, 0.0f);
    strip[size_t(i)] = glsl::gardner_sum_x(p, glm::vec2(f1, f1), terms, false);
    const float sy = glsl::gardner_sum_y(p, glm::vec2(f1, f1), terms, false);
    ASSERT_NEAR(glsl::gardner_texture(p, glm::vec2(f1, f1), 0.5f, 0.8f, terms, false),
                0.8f * (strip[size_t(i)].real() + 0.5f) * (sy + 0.5f), 1e-5);
  }
  // A plain DFT at the bins that matter, and at the bins between them.
  const auto amplitude = [&](int bin) {
    std::complex<double> sum = 0.0;
    for (int i = 0; i < n; ++i) sum += strip[size_t(i)] * std::polar(1.0, -2.0 * kPi * bin * i / n);
    return 2.0 * std::abs(sum) / n;
  };
  std::vector<double> lines;
  for (int i = 0; i < terms; ++i) lines.push_back(amplitude(4 << i));
  for (int i = 1; i < terms; ++i) {
    EXPECT_NEAR(lines[size_t(i)] / lines[size_t(i - 1)], 0.707, 0.003) << "term " << i;
  }
  double off_lines = 0.0;
  for (int bin : {3, 5, 6, 7, 9, 12, 24, 40, 100}) off_lines = std::max(off_lines, amplitude(bin));
  EXPECT_LT(off_lines, 1e-3 * lines[0]);
  EXPECT_GT(lines[0], 0.0);
}

// The seed's printing of T is a sum of lines in x and y (no sines): unbounded, growing with x.
TEST(GardnerTexture, TheSeedsFormIsNotPeriodic) {
  const float f = 0.01f;
  const float a = glsl::gardner_texture(glm::vec3(0.0f, 0.0f, 0.0f), glm::vec2(f), 0.5f, 1.0f, 4, true);
  const float b = glsl::gardner_texture(glm::vec3(1e4f, 0.0f, 0.0f), glm::vec2(f), 0.5f, 1.0f, 4, true);
  EXPECT_GT(b - a, 100.0f);
  // The original stays within k (sum C_i + T0)^2.
  double bound = 0.5;
  for (int i = 0; i < 4; ++i) bound += std::pow(0.707, i);
  for (int i = 0; i < 1000; ++i) {
    const glm::vec3 p(float(i) * 13.7f, float(i) * 7.1f, float(i) * 3.3f);
    EXPECT_LE(std::abs(glsl::gardner_texture(p, glm::vec2(f), 0.5f, 1.0f, 4, false)), bound * bound + 1e-4);
  }
}

TEST(GardnerShading, IntensityAndTranslucencyAtTheirLimits) {
  EXPECT_FLOAT_EQ(glsl::gardner_intensity(0.3f, 0.9f, 0.6f, 0.0f, 0.0f, 0.0f), 0.3f);  // diffuse
  EXPECT_FLOAT_EQ(glsl::gardner_intensity(0.3f, 0.9f, 0.6f, 0.0f, 0.0f, 1.0f), 0.9f);  // specular
  EXPECT_FLOAT_EQ(glsl::gardner_intensity(0.3f, 0.9f, 0.6f, 0.0f, 1.0f, 0.5f), 0.6f);  // texture
  EXPECT_FLOAT_EQ(glsl::gardner_intensity(0.3f, 0.9f, 0.6f, 1.0f, 0.4f, 0.5f), 1.0f);  // ambient
  EXPECT_NEAR(glsl::gardner_intensity(0.2f, 0.8f, 0.5f, 0.25f, 0.5f, 0.5f),
              0.75f * (0.5f * (0.5f * 0.2f + 0.5f * 0.8f) + 0.5f * 0.5f) + 0.25f, 1e-6);
  // At the centre (g = 1) the threshold is T1, at the edge (g = 0) T2: the same texture value
  // is opaque in the middle and clear at the rim.
  EXPECT_FLOAT_EQ(glsl::gardner_translucency(0.6f, 0.3f, 0.7f, 0.2f, 1.0f), 1.0f);
  EXPECT_FLOAT_EQ(glsl::gardner_translucency(0.6f, 0.3f, 0.7f, 0.2f, 0.0f), 0.0f);
  EXPECT_NEAR(glsl::gardner_translucency(0.6f, 0.3f, 0.7f, 1.0f, 0.5f), 0.1f, 1e-6);
}

// Wyvill's soft-object polynomial: 1 at the centre, 0 with a zero slope at the radius; the
// density and its gradient against the closed form and central differences.
TEST(Metaball, DensityAndGradientAgainstClosedForms) {
  EXPECT_FLOAT_EQ(glsl::metaball_falloff(0.0f), 1.0f);
  EXPECT_NEAR(glsl::metaball_falloff(1.0f - 1e-6f), 0.0f, 1e-5);
  EXPECT_EQ(glsl::metaball_falloff(1.5f), 0.0f);
  EXPECT_NEAR(glsl::metaball_falloff(0.5f),
              1.0 - 22.0 / 9.0 * 0.25 + 17.0 / 9.0 * 0.0625 - 4.0 / 9.0 * 0.015625, 1e-6);
  const glm::vec4 ball(100.0f, -50.0f, 2000.0f, 400.0f);
  const float q = 0.7f;
  for (const glm::vec3 p : {glm::vec3(100.0f, -50.0f, 2000.0f), glm::vec3(250.0f, 0.0f, 2100.0f),
                            glm::vec3(-150.0f, 100.0f, 1800.0f), glm::vec3(600.0f, 0.0f, 2000.0f)}) {
    const glm::vec4 m = glsl::metaball(p, ball, q);
    const float u = glm::length(p - glm::vec3(ball)) / ball.w;
    EXPECT_NEAR(m.x, q * glsl::metaball_falloff(u), 1e-6);
    const float h = 0.05f;
    for (int k = 0; k < 3; ++k) {
      glm::vec3 e(0.0f);
      e[k] = h;
      const float numeric = (glsl::metaball(p + e, ball, q).x - glsl::metaball(p - e, ball, q).x) / (2.0f * h);
      EXPECT_NEAR(m[k + 1], numeric, 2e-5) << "axis " << k;
    }
  }
}

}  // namespace
}  // namespace nephele

namespace nephele {
namespace {

// Gardner's cumulus field: each present ellipsoid lies inside its own cell's column (so a ray
// that visits the cells in order meets them in order), stands on the layer's bottom below its
// top, and a share `coverage` of the cells holds one.
TEST(GardnerCumulus, EllipsoidsStayInTheirCellsAndCoverTheirShare) {
  const float spacing = 3000.0f, bottom = 1500.0f, top = 4000.0f;
  for (const float coverage : {0.2f, 0.5f, 0.8f}) {
    int present = 0, cells = 0;
    for (int i = -50; i < 50; ++i)
      for (int j = -50; j < 50; ++j) {
        const glsl::GardnerEllipsoid e =
            glsl::gardner_cell_ellipsoid(glm::ivec2(i, j), spacing, bottom, top, coverage, 3u);
        ++cells;
        if (!e.present) continue;
        ++present;
        ASSERT_GE(e.centre.x - e.radii.x, float(i) * spacing - 1e-2f);
        ASSERT_LE(e.centre.x + e.radii.x, float(i + 1) * spacing + 1e-2f);
        ASSERT_GE(e.centre.y - e.radii.y, float(j) * spacing - 1e-2f);
        ASSERT_LE(e.centre.y + e.radii.y, float(j + 1) * spacing + 1e-2f);
        ASSERT_NEAR(e.centre.z - e.radii.z, bottom, 1e-2f);
        ASSERT_LE(e.centre.z + e.radii.z, top + 1e-2f);
      }
    EXPECT_NEAR(double(present) / cells, coverage, 0.02) << coverage;
  }
}

// The ray against an ellipsoid: through a sphere's centre, t = distance - R and the limb curve
// 1; off-centre by q R, sqrt(1 - q^2); past it, no hit; a stretched ellipsoid is the sphere
// in its own units.
TEST(GardnerCumulus, RayEllipsoidHitsAndItsLimbCurve) {
  const glm::vec3 c(100.0f, 200.0f, 2000.0f), sphere(500.0f);
  const glm::vec2 through = glsl::ray_ellipsoid(glm::vec3(100.0f, 200.0f, 0.0f),
                                                glm::vec3(0.0f, 0.0f, 1.0f), c, sphere);
  EXPECT_NEAR(through.x, 1500.0f, 1e-2f);
  EXPECT_NEAR(through.y, 1.0f, 1e-6f);
  const glm::vec2 off = glsl::ray_ellipsoid(glm::vec3(400.0f, 200.0f, 0.0f),
                                            glm::vec3(0.0f, 0.0f, 1.0f), c, sphere);
  EXPECT_NEAR(off.x, 2000.0f - 400.0f, 1e-1f);  // sqrt(500^2 - 300^2) = 400
  EXPECT_NEAR(off.y, 0.8f, 1e-5f);
  EXPECT_LT(glsl::ray_ellipsoid(glm::vec3(700.0f, 200.0f, 0.0f), glm::vec3(0.0f, 0.0f, 1.0f), c,
                                sphere).x, 0.0f);
  const glm::vec2 stretched = glsl::ray_ellipsoid(glm::vec3(100.0f + 2.0f * 300.0f, 200.0f, 0.0f),
                                                  glm::vec3(0.0f, 0.0f, 1.0f), c,
                                                  glm::vec3(1000.0f, 500.0f, 500.0f));
  EXPECT_NEAR(stretched.x, off.x, 1e-1f);
  EXPECT_NEAR(stretched.y, off.y, 1e-5f);
}

}  // namespace
}  // namespace nephele

namespace nephele {
namespace {

// Gardner's impressionistic objects: the quadric in the seed's ten coefficients, its value and
// gradient against the ellipsoid they stand for.
TEST(GardnerQuadrics, TheEllipsoidsCoefficientsDescribeIt) {
  const glm::vec3 centre(300.0f, -200.0f, 2500.0f), radii(900.0f, 500.0f, 700.0f);
  const float yaw = 0.6f;
  const glsl::Quadric q = glsl::quadric_ellipsoid(centre, radii, yaw);
  const glm::vec3 e1(std::cos(yaw), std::sin(yaw), 0.0f), e2(-std::sin(yaw), std::cos(yaw), 0.0f),
      e3(0.0f, 0.0f, 1.0f);
  for (int i = 0; i < 50; ++i) {
    const float th = 0.37f * float(i), ph = 0.11f * float(i) - 2.0f;
    const glm::vec3 unit(std::cos(th) * std::cos(ph), std::sin(th) * std::cos(ph), std::sin(ph));
    const glm::vec3 p = centre + radii.x * unit.x * e1 + radii.y * unit.y * e2 + radii.z * unit.z * e3;
    EXPECT_NEAR(glsl::quadric_value(q, p), 0.0f, 1e-4f);
    EXPECT_LT(glsl::quadric_value(q, centre + 0.9f * (p - centre)), 0.0f);
    EXPECT_GT(glsl::quadric_value(q, centre + 1.1f * (p - centre)), 0.0f);
    for (int k = 0; k < 3; ++k) {
      glm::vec3 h(0.0f);
      h[k] = 0.5f;
      const float numeric = (glsl::quadric_value(q, p + h) - glsl::quadric_value(q, p - h)) / 1.0f;
      EXPECT_NEAR(glsl::quadric_gradient(q, p)[k], numeric, 1e-5f);
    }
  }
}

// A sphere cut by the plane z >= 0, seen from the side along +y: rays hit exactly the half
// disc above the cut (the outline Gardner's key points bound: the limb curve above the
// intersection line), entering the sphere where it is; from below, rays enter the flat face
// at the plane, face on. A dome sheared by a slanting plane is entered, from above, through
// that plane.
TEST(GardnerQuadrics, RaysFindTheVisibleSurfacesOfACutSphereAndDome) {
  glsl::ConvexObject o;
  o.shape = glsl::quadric_ellipsoid(glm::vec3(0.0f), glm::vec3(1000.0f), 0.0f);
  o.planes[0] = glm::vec4(0.0f, 0.0f, -1.0f, 0.0f);
  o.plane_count = 1;
  int hits = 0;
  for (int i = -20; i <= 20; ++i)
    for (int j = -20; j <= 20; ++j) {
      const float x = 52.0f * float(i) + 1.0f, z = 52.0f * float(j) + 1.0f;
      const glm::vec4 side = glsl::ray_convex_object(o, glm::vec3(x, -5000.0f, z), glm::vec3(0.0f, 1.0f, 0.0f));
      const bool inside = x * x + z * z < 1.0e6f && z > 0.0f;
      EXPECT_EQ(side.x < side.y, inside) << x << ", " << z;
      if (!inside) continue;
      ++hits;
      EXPECT_NEAR(side.x, 5000.0f - std::sqrt(1.0e6f - x * x - z * z), 0.05f);
      EXPECT_EQ(side.z, -1.0f);
      const glm::vec4 below = glsl::ray_convex_object(o, glm::vec3(x, z, -5000.0f), glm::vec3(0.0f, 0.0f, 1.0f));
      EXPECT_NEAR(below.x, 5000.0f, 1e-3f);
      EXPECT_EQ(below.z, 0.0f);
      EXPECT_NEAR(below.w, 1.0f, 1e-6f);
    }
  EXPECT_GT(hits, 500);
  glsl::ConvexObject dome;
  dome.shape = glsl::quadric_dome(glm::vec3(0.0f, 0.0f, 1000.0f), glm::vec2(400.0f, 300.0f), 1000.0f);
  const glm::vec3 n = glm::normalize(glm::vec3(1.0f, 0.0f, 2.5f));
  dome.planes[0] = glm::vec4(0.0f, 0.0f, -1.0f, 0.0f);
  dome.planes[1] = glm::vec4(n, -glm::dot(n, glm::vec3(0.0f, 0.0f, 800.0f)));
  dome.plane_count = 2;
  const glm::vec4 top = glsl::ray_convex_object(dome, glm::vec3(0.0f, 0.0f, 5000.0f), glm::vec3(0.0f, 0.0f, -1.0f));
  EXPECT_EQ(top.z, 1.0f);
  EXPECT_NEAR(top.x, 4200.0f, 1e-2f);
  EXPECT_NEAR(top.y, 5000.0f, 1e-2f);
  EXPECT_NEAR(top.w, n.z, 1e-5f);
  // Beside the dome's rim at the base (400 m east of its axis it meets the ground): a miss.
  const glm::vec4 beside = glsl::ray_convex_object(dome, glm::vec3(410.0f, 0.0f, 5000.0f), glm::vec3(0.0f, 0.0f, -1.0f));
  EXPECT_GE(beside.x, beside.y);
}

// Every object of a cell's impressionistic cloud stays in the cell's column and above the
// layer's bottom and below its top: vertical rays over the cell and its neighbours hit them
// only over the cell, between those heights, and within the reach of the cloud's axis that
// the march culls by.
TEST(GardnerQuadrics, ACellsObjectsStayInItsColumn) {
  const float spacing = 3000.0f, bottom = 1500.0f, top = 4000.0f;
  for (const glm::ivec2 cell : {glm::ivec2(3, -2), glm::ivec2(-7, 11), glm::ivec2(0, 0)}) {
    int hits = 0;
    for (int k = 0; k < glsl::GARDNER_CELL_OBJECTS; ++k) {
      const glsl::ConvexObject o = glsl::gardner_cell_object(cell, k, spacing, bottom, top, 9u);
      for (int i = 0; i < 90; ++i)
        for (int j = 0; j < 90; ++j) {
          const glm::vec2 xy = (glm::vec2(cell) - 1.0f + (glm::vec2(i, j) + 0.5f) / 30.0f) * spacing;
          const glm::vec4 hit = glsl::ray_convex_object(o, glm::vec3(xy, 20000.0f), glm::vec3(0.0f, 0.0f, -1.0f));
          if (hit.x >= hit.y) continue;
          ++hits;
          const glm::vec2 in_cell = xy / spacing - glm::vec2(cell);
          EXPECT_TRUE(in_cell.x >= 0.0f && in_cell.x <= 1.0f && in_cell.y >= 0.0f && in_cell.y <= 1.0f)
              << "object " << k << " at " << xy.x << ", " << xy.y;
          EXPECT_LE(20000.0f - hit.x, top + 1.0f);
          const glm::vec3 axis = glsl::gardner_cell_axis(cell, spacing, 9u);
          EXPECT_LE(glm::length(xy - glm::vec2(axis)), axis.z);  // the march's cull
          EXPECT_GE(20000.0f - hit.y, bottom - 1.0f);  // nothing below the flat base
        }
    }
    EXPECT_GT(hits, 150);
  }
}

}  // namespace
}  // namespace nephele

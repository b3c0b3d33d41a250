// Lebedev's 14-point rule (shaders/common/lebedev_inc.glsl, compiled as C++) as the cloud
// diffusion's exchange uses it: its weights sum to the sphere, its directions are the axes and
// the diagonals, it integrates polynomials up to degree 5 exactly, and its partial currents
// (with the correction from the fluence) are exact for any P1 radiance field a + b . w, where the
// rule alone gives 0.9595 pi a for the isotropic part.
#include <gtest/gtest.h>

#include <cmath>

#include "render/glsl.h"

namespace {

namespace g = nephele::glsl;

// The rule's fluence and six partial currents (+x, -x, +y, -y, +z, -z: the light travelling
// along each) of a radiance field L(w), w the direction the light comes from, as
// diffusion_exchange.comp forms them.
struct Gathered {
  double phi = 0.0;
  double currents[6] = {};
};

template <typename F>
Gathered gather(F radiance, bool corrected) {
  Gathered out;
  for (int k = 0; k < g::LEBEDEV_POINTS; ++k) {
    const glm::vec3 w = glm::normalize(glm::vec3(g::lebedev_step(k)));
    const double l = double(g::lebedev_weight(k)) * radiance(w);
    out.phi += l;
    for (int axis = 0; axis < 3; ++axis) {
      const int slot = g::lebedev_current_slot(k, axis);
      if (slot >= 0) out.currents[slot] += std::abs(w[axis]) * l;
    }
  }
  const double correction = corrected ? g::lebedev_current_correction(float(out.phi)) : 0.0;
  for (double& j : out.currents) j += correction;
  return out;
}

TEST(Lebedev, TheWeightsCoverTheSphereAndTheDirectionsAreTheAxesAndDiagonals) {
  double sum = 0.0;
  int axes = 0, diagonals = 0;
  glm::ivec3 total(0);
  for (int k = 0; k < g::LEBEDEV_POINTS; ++k) {
    sum += g::lebedev_weight(k);
    const glm::ivec3 o = g::lebedev_step(k);
    total += o;
    const int moved = std::abs(o.x) + std::abs(o.y) + std::abs(o.z);
    EXPECT_EQ(std::max(std::abs(o.x), std::max(std::abs(o.y), std::abs(o.z))), 1) << k;
    axes += moved == 1;
    diagonals += moved == 3;
    for (int j = 0; j < k; ++j) EXPECT_NE(g::lebedev_step(j), o) << j << " " << k;
  }
  EXPECT_NEAR(sum, 4.0 * M_PI, 1e-5);
  EXPECT_EQ(axes, 6);
  EXPECT_EQ(diagonals, 8);
  EXPECT_EQ(total, glm::ivec3(0));
}

TEST(Lebedev, ItIntegratesPolynomialsOfDegreeFiveExactly) {
  // x^a y^b z^c over the unit sphere: 0 for an odd power, else
  // 2 G(A) G(B) G(C) / G(A + B + C) with A = (a + 1) / 2 ... (G the gamma function).
  for (int a = 0; a <= 5; ++a)
    for (int b = 0; a + b <= 5; ++b)
      for (int c = 0; a + b + c <= 5; ++c) {
        double rule = 0.0;
        for (int k = 0; k < g::LEBEDEV_POINTS; ++k) {
          const glm::vec3 w = glm::normalize(glm::vec3(g::lebedev_step(k)));
          rule += g::lebedev_weight(k) * std::pow(w.x, a) * std::pow(w.y, b) * std::pow(w.z, c);
        }
        double exact = 0.0;
        if (a % 2 == 0 && b % 2 == 0 && c % 2 == 0) {
          const double A = (a + 1) / 2.0, B = (b + 1) / 2.0, C = (c + 1) / 2.0;
          exact = 2.0 * std::tgamma(A) * std::tgamma(B) * std::tgamma(C) / std::tgamma(A + B + C);
        }
        EXPECT_NEAR(rule, exact, 1e-5) << a << b << c;
      }
}

TEST(Lebedev, ThePartialCurrentsOfAP1FieldAreExactWithTheCorrection) {
  // L(w) = a + b . w for light coming from w, travelling along -w: the current along +x is the
  // integral of L |w.x| over w.x < 0, pi a - 2 pi / 3 b.x; along -x, pi a + 2 pi / 3 b.x.
  const double a = 1.0;
  const glm::vec3 b(0.3f, -0.2f, 0.5f);
  const auto field = [&](glm::vec3 w) { return a + double(glm::dot(b, w)); };
  const Gathered plain = gather(field, false);
  const Gathered fixed = gather(field, true);
  EXPECT_NEAR(fixed.phi, 4.0 * M_PI * a, 1e-5);
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = 0; sign < 2; ++sign) {
      const int slot = 2 * axis + sign;
      const double exact = M_PI * a + (sign == 0 ? -1.0 : 1.0) * 2.0 * M_PI / 3.0 * b[axis];
      EXPECT_NEAR(fixed.currents[slot], exact, 1e-5) << slot;
      // Without the correction the isotropic part is 4% short: every clear pocket of a cloud
      // lost that much of the light crossing it.
      EXPECT_NEAR(plain.currents[slot] - exact, -0.0405 * M_PI * a, 1e-3) << slot;
    }
}

}  // namespace

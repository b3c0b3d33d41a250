// The nine real spherical harmonics (shaders/common/sh_inc.glsl, compiled as C++): orthonormal
// over the sphere, and the clamped cosine's coefficients turn a radiance's projection into its
// irradiance (a uniform sky of radiance L gives pi L on any surface; a sky lit only from above
// gives pi L facing up and 0 facing down, to the 2% nine coefficients allow).
#include <gtest/gtest.h>

#include <cmath>

#include "render/glsl.h"

namespace {

using nephele::glsl::Sh9;
using nephele::glsl::sh9_basis;
using nephele::glsl::sh9_cosine_lobe;

// Sums f(direction, solid angle) over 128 x 256 cells of equal solid angle.
template <typename F>
void over_sphere(F f) {
  const int rows = 128, columns = 256;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < columns; ++c) {
      const float z = 1.0f - 2.0f * (float(r) + 0.5f) / float(rows);
      const float phi = (float(c) + 0.5f) / float(columns) * 6.2831853f;
      const float s = std::sqrt(1.0f - z * z);
      f(glm::vec3(s * std::cos(phi), s * std::sin(phi), z), 4.0 * M_PI / (rows * columns));
    }
}

TEST(SphericalHarmonics, TheNineFunctionsAreOrthonormal) {
  double gram[9][9] = {};
  over_sphere([&](const glm::vec3& d, double dw) {
    const Sh9 y = sh9_basis(d);
    for (int i = 0; i < 9; ++i)
      for (int j = 0; j < 9; ++j) gram[i][j] += double(y.y[i]) * double(y.y[j]) * dw;
  });
  for (int i = 0; i < 9; ++i)
    for (int j = 0; j < 9; ++j) EXPECT_NEAR(gram[i][j], i == j ? 1.0 : 0.0, 1e-3) << i << "," << j;
}

TEST(SphericalHarmonics, TheCosineLobeGivesTheIrradiance) {
  // Projections of a uniform sky (1 everywhere) and of the upper hemisphere only.
  double uniform[9] = {}, upper[9] = {};
  over_sphere([&](const glm::vec3& d, double dw) {
    const Sh9 y = sh9_basis(d);
    for (int k = 0; k < 9; ++k) {
      uniform[k] += y.y[k] * dw;
      if (d.z > 0.0f) upper[k] += y.y[k] * dw;
    }
  });
  const auto irradiance = [](const double* l, const glm::vec3& n) {
    const Sh9 y = sh9_basis(n);
    double e = 0.0;
    for (int k = 0; k < 9; ++k) e += sh9_cosine_lobe(k) * y.y[k] * l[k];
    return e;
  };
  for (const glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(1, 0, 0), glm::vec3(0, -0.6f, 0.8f)})
    EXPECT_NEAR(irradiance(uniform, n), M_PI, 1e-3);
  EXPECT_NEAR(irradiance(upper, {0, 0, 1}), M_PI, 0.02 * M_PI);
  EXPECT_NEAR(irradiance(upper, {0, 0, -1}), 0.0, 0.02 * M_PI);
  EXPECT_NEAR(irradiance(upper, {1, 0, 0}), 0.5 * M_PI, 0.02 * M_PI);
}

}  // namespace

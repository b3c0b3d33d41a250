// The display's tone map operators (shaders/common/tonemap_inc.glsl, output.tonemap) against
// their closed forms, and what each promises a picture: black stays black, brighter never
// maps darker, mid grey lands near the middle of the display range.
#include <gtest/gtest.h>

#include <cmath>

#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "render/glsl.h"

namespace nephele {
namespace {

double srgb(double v) { return v <= 0.0031308 ? 12.92 * v : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055; }

// Hable's curve with his constants, and AgX's closed form, in double.
double hable(double x) {
  const double A = 0.15, B = 0.50, C = 0.10, D = 0.20, E = 0.02, F = 0.30;
  return (x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F) - E / F;
}

glm::dvec3 agx_closed_form(glm::dvec3 c) {
  // Rows of the inset and outset matrices (AgX's primaries).
  const double inset[3][3] = {{0.842479062253094, 0.0784335999999992, 0.0792237451477643},
                              {0.0423282422610123, 0.878468636469772, 0.0791661274605434},
                              {0.0423756549057051, 0.0784336, 0.879142973793104}};
  const double outset[3][3] = {{1.19687900512017, -0.0980208811401368, -0.0990297440797205},
                               {-0.0528968517574562, 1.15190312990417, -0.0989611768448433},
                               {-0.0529716355144438, -0.0980434501171241, 1.15107367264116}};
  const double lo = -12.47393, hi = 4.026069;
  glm::dvec3 s;
  for (int i = 0; i < 3; ++i) {
    const double v = inset[i][0] * c.x + inset[i][1] * c.y + inset[i][2] * c.z;
    const double x = (std::clamp(std::log2(std::max(v, 1e-10)), lo, hi) - lo) / (hi - lo);
    s[i] = 15.5 * std::pow(x, 6) - 40.14 * std::pow(x, 5) + 31.96 * std::pow(x, 4) -
           6.868 * std::pow(x, 3) + 0.4298 * x * x + 0.1191 * x - 0.00232;
  }
  glm::dvec3 out;
  for (int i = 0; i < 3; ++i)
    out[i] = std::pow(std::clamp(outset[i][0] * s.x + outset[i][1] * s.y + outset[i][2] * s.z, 0.0, 1.0), 2.2);
  return out;
}

TEST(ToneMap, EachOperatorIsItsClosedForm) {
  for (double x = 0.0; x < 60.0; x = x * 1.3 + 0.01) {
    const glm::vec3 c = glm::vec3(float(x));
    EXPECT_NEAR(glsl::tone_map(glsl::TONEMAP_ACES, c).x,
                std::clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0), 1e-5);
    EXPECT_NEAR(glsl::tone_map(glsl::TONEMAP_REINHARD, c).x, x / (1.0 + x), 1e-6);
    EXPECT_NEAR(glsl::tone_map(glsl::TONEMAP_NONE, c).x, std::min(x, 1.0), 1e-6);
    EXPECT_NEAR(glsl::tone_map(glsl::TONEMAP_UNCHARTED2, c).x,
                std::clamp(hable(2.0 * x) / hable(11.2), 0.0, 1.0), 1e-5);
    // A coloured pixel too: AgX mixes the channels.
    const glm::dvec3 colour(x, 0.5 * x, 0.1 + 0.2 * x);
    const glm::vec3 agx = glsl::tone_map(glsl::TONEMAP_AGX, glm::vec3(colour));
    const glm::dvec3 expected = agx_closed_form(colour);
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(agx[i], expected[i], 2e-4) << "x " << x << " channel " << i;
  }
  // Hable's white point, 11.2 after his exposure bias of 2, is white.
  EXPECT_NEAR(glsl::tone_map(glsl::TONEMAP_UNCHARTED2, glm::vec3(5.6f)).x, 1.0f, 1e-6f);
}

TEST(ToneMap, BlackStaysBlackBrighterNeverDarkerMidGreyNearTheMiddle) {
  for (const ToneMap op : kToneMaps) {
    const int k = int(op);
    EXPECT_NEAR(glsl::tone_map(k, glm::vec3(0.0f)).x, 0.0f, 1e-3f) << to_string(op);
    float previous = -1.0f;
    for (float x = 0.0f; x < 1000.0f; x = x * 1.1f + 0.001f) {
      const float y = glsl::tone_map(k, glm::vec3(x)).x;
      EXPECT_GE(y, previous - 1e-6f) << to_string(op) << " at " << x;
      EXPECT_LE(y, 1.0f);
      previous = y;
    }
    // Grey stays grey.
    const glm::vec3 grey = glsl::tone_map(k, glm::vec3(0.18f));
    EXPECT_NEAR(grey.r, grey.g, 1e-4f) << to_string(op);
    EXPECT_NEAR(grey.b, grey.g, 1e-4f) << to_string(op);
    // 18% grey (exposed) lands in the middle third of the display's sRGB range with the
    // filmic operators (ACES 0.55, Uncharted 2 0.39); AgX puts it at 0.50 as designed.
    const double display = srgb(grey.g);
    std::printf("%s: 18%% grey at %.3f\n", to_string(op), display);
    if (op != ToneMap::None && op != ToneMap::Reinhard) {
      EXPECT_GT(display, 1.0 / 3.0) << to_string(op);
      EXPECT_LT(display, 2.0 / 3.0) << to_string(op);
    }
    if (op == ToneMap::Agx) EXPECT_NEAR(display, 0.50, 0.01);
  }
}

// The PNG writer encodes through the scene's operator: one pixel per operator, its code the
// operator's value sRGB-encoded; the names read back.
TEST(ToneMap, ThePngWriterUsesTheOperator) {
  Image image;
  image.width = image.height = 1;
  image.pixels = {glm::vec4(2.0f, 0.7f, 0.05f, 1.0f)};
  for (const ToneMap op : kToneMaps) {
    const std::vector<unsigned char> rgba = tonemap_srgb8(image, 0.5f, op);
    const glm::vec3 mapped = glsl::tone_map(int(op), glm::vec3(1.0f, 0.35f, 0.025f));
    for (int i = 0; i < 3; ++i)
      EXPECT_EQ(int(rgba[size_t(i)]), int(std::lround(srgb(mapped[i]) * 255.0))) << to_string(op);
    EXPECT_EQ(parse_tonemap(to_string(op)), op);
  }
  EXPECT_FALSE(parse_tonemap("filmic").has_value());
}

}  // namespace
}  // namespace nephele

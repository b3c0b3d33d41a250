// Lightning's laws (shaders/common/lightning_inc.glsl) and its block (render/modules/lightning):
// a flash's light over the frames adds up to its strokes' light, its strokes flicker, the glow
// leaving the cloud carries the flux, the candidates' chance gives the rate asked for, and the
// block is off without a rate or a cumulonimbus.
#include "render/modules/lightning/lightning.h"

#include <gtest/gtest.h>

#include <cmath>

#include "nephele/scene_io.h"
#include "render/glsl.h"

namespace {

namespace g = nephele::glsl;

// Frames of LIGHTNING_WINDOW_S one after another see each stroke's light once: their means times
// the window add up to the strokes' light, 1e8 lm s each, for both decays.
TEST(Lightning, TheFramesSeeEveryStrokesLightOnce) {
  for (const float decay_s : {g::LIGHTNING_STROKE_S, g::LIGHTNING_PULSE_S})
    for (int strokes = 1; strokes <= 4; ++strokes) {
      const float h = 0.13f * float(strokes);
      double sum = 0.0;
      const float end_s = g::lightning_duration_s(strokes, decay_s, h) + 0.5f;
      for (float t = g::LIGHTNING_WINDOW_S; t < end_s; t += g::LIGHTNING_WINDOW_S)
        sum += g::lightning_flux_lm(t, strokes, decay_s, h) * g::LIGHTNING_WINDOW_S;
      EXPECT_NEAR(sum, strokes * g::LIGHTNING_STROKE_LM_S,
                  0.01 * strokes * g::LIGHTNING_STROKE_LM_S)
          << strokes << " strokes, decay " << decay_s;
    }
}

// A flash of several return strokes flickers: between strokes the channel goes dark (the
// light a millisecond before a stroke is a small part of the light just after it), the
// strokes 40 to 80 ms apart; nothing before it starts.
TEST(Lightning, StrokesFlicker) {
  const float h = 0.9f;  // 4 strokes
  ASSERT_EQ(g::lightning_strokes(h), 4);
  EXPECT_EQ(g::lightning_strokes(0.0f), 1);
  for (int i = 1; i < 4; ++i) {
    const float gap = g::lightning_stroke_time_s(i, h) - g::lightning_stroke_time_s(i - 1, h);
    EXPECT_GE(gap, 0.04f);
    EXPECT_LE(gap, 0.08f);
    const float t = g::lightning_stroke_time_s(i, h);
    // Seen over a window of 2 ms instead of a frame's, to resolve the flicker.
    const auto instant = [&](float at) {
      return g::lightning_flux_lm(at, 4, g::LIGHTNING_STROKE_S, h) -
             g::lightning_flux_lm(at - 0.002f, 4, g::LIGHTNING_STROKE_S, h);
    };
    EXPECT_LT(instant(t - 0.001f), 0.1f * instant(t + 0.003f)) << "stroke " << i;
  }
  EXPECT_EQ(g::lightning_flux_lm(0.0f, 4, g::LIGHTNING_STROKE_S, h), 0.0f);
}

// The glow leaving the cloud's face carries the flash's flux: its exitance (pi times the
// luminance) integrated over the plane is the flux.
TEST(Lightning, TheGlowCarriesTheFlux) {
  const float flux = 2e9f;
  double sum = 0.0;
  for (double r = 0.5; r < 60000.0; r += 1.0)
    sum += M_PI * g::lightning_glow_cd_m2(flux, float(r)) * 2.0 * M_PI * r;
  EXPECT_NEAR(sum, flux, 0.01 * flux);
}

// The chance a candidate in a core flashes: the candidates that fall in a core, times it, give
// the cell's flashes a slot; capped at 1.
TEST(Lightning, TheCandidatesGiveTheRateAskedFor) {
  const float tile = nephele::kLightningTileM * nephele::kLightningTileM;
  const float chance = g::lightning_candidate_chance(8.0f, 8.0f, tile, nephele::kLightningCoreM2);
  EXPECT_NEAR(chance * 8.0f * nephele::kLightningCoreM2 / tile, 8.0f / 60.0f * g::LIGHTNING_SLOT_S,
              1e-5);
  EXPECT_EQ(g::lightning_candidate_chance(1e4f, 8.0f, tile, nephele::kLightningCoreM2), 1.0f);
}

// Off without a rate, without cumulonimbus (clouds.precipitation 0) or with a classical model;
// on, the slot and the time in it from a large time without float's loss.
TEST(Lightning, TheBlockIsOnOnlyForAStorm) {
  nephele::Scene s = nephele::load_preset("thunderstorm-dusk");
  EXPECT_EQ(nephele::lightning_block(s).when.w, 1.0f);
  s.time_s = 123456.789f;
  const nephele::gpu::LightningGpu on = nephele::lightning_block(s);
  EXPECT_EQ(on.slot.x, 123456);
  EXPECT_NEAR(on.when.x, double(s.time_s) - 123456.0, 1e-6);
  EXPECT_EQ(on.slot.z, int(std::floor(-100.0 / nephele::kLightningTileM)));
  nephele::Scene calm = s;
  calm.lightning.flashes_per_min = 0.0f;
  EXPECT_EQ(nephele::lightning_block(calm).when.w, 0.0f);
  nephele::Scene dry = s;
  dry.clouds.precipitation = 0.0f;
  EXPECT_EQ(nephele::lightning_block(dry).when.w, 0.0f);
}

}  // namespace

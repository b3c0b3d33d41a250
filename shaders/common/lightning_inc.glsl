// Lightning (render/modules/lightning): when a storm cell flashes, how bright a flash is over a
// frame, and how its light leaves the cloud. Pure functions, also compiled as C++ (src/render/
// glsl.h conventions).
//
// Flashes. A cumulonimbus flashes at a rate a user sets (flashes a minute a cell: a few in an
// ordinary thunderstorm, tens in a severe one). A quarter of the flashes strike the ground
// (cloud-to-ground), the rest stay in the cloud: the share is a key. A cloud-to-ground flash is
// 1 to 4 return strokes (the mean in the records is 3 to 4 with single strokes common) some
// 40 to 80 ms apart, each a burst of light decaying over LIGHTNING_STROKE_S, the channel dark
// between them: the flicker. An in-cloud flash is as many slower pulses.
//
// Light. A return stroke radiates about 1 MJ in visible light (a few tenths of a per cent of
// its 1e9 J) at about 100 lm/W, 1e8 lm s a stroke: taken alike for the in-cloud pulses. A frame
// sees the mean over its window (a thirtieth of a second) of that light.
//
// Inside the cloud the light scatters many times before it leaves: it comes out of the cloud's
// face around the flash, spread over about a diffusion length LIGHTNING_SPREAD_M. The exitance
// (lm/m^2) at distance r from the flash is flux exp(-r / l) / (2 pi l^2), which integrates to
// the flux over a plane; the face's luminance is that over pi.
#ifndef NEPHELE_LIGHTNING_INC
#define NEPHELE_LIGHTNING_INC

const float LIGHTNING_STROKE_LM_S = 1.0e8f;  // visible light of a stroke (lm s)
const float LIGHTNING_STROKE_S = 0.008f;     // a return stroke's decay (s)
const float LIGHTNING_PULSE_S = 0.03f;       // an in-cloud pulse's decay (s)
const float LIGHTNING_WINDOW_S = 1.0f / 30.0f;  // the frame's window over which a flash is seen
const float LIGHTNING_SPREAD_M = 2000.0f;    // how far the light spreads in the cloud (m)
const float LIGHTNING_SLOT_S = 1.0f;         // flashes start in slots of this length (s)

// The number of strokes (pulses) of a flash from a uniform hash h in [0, 1): 1 to 4.
int lightning_strokes(float h) { return 1 + min(int(h * 4.0f), 3); }

// When stroke `i` of a flash strikes after the flash starts (s): 40 to 80 ms apart, from the
// flash's hash h.
float lightning_stroke_time_s(int i, float h) {
  float t = 0.0f;
  for (int j = 1; j <= i; ++j) t += 0.04f + 0.04f * fract(h * 7.31f + 0.37f * float(j));
  return t;
}

// The mean luminous flux (lm) of a flash of `strokes` strokes decaying over `decay_s`, over the
// window ending `since_start_s` after it starts: each stroke's light, Q exp(-(t - t_i) / decay)
// / decay from its time t_i on, integrated over the window and divided by it.
float lightning_flux_lm(float since_start_s, int strokes, float decay_s, float h) {
  float sum = 0.0f;
  for (int i = 0; i < strokes; ++i) {
    float t = since_start_s - lightning_stroke_time_s(i, h);
    if (t <= 0.0f) continue;
    float begin = max(t - LIGHTNING_WINDOW_S, 0.0f);
    sum += exp(-begin / decay_s) - exp(-t / decay_s);
  }
  return LIGHTNING_STROKE_LM_S * sum / LIGHTNING_WINDOW_S;
}

// How long a flash of `strokes` strokes lasts (s): its last stroke and five decays.
float lightning_duration_s(int strokes, float decay_s, float h) {
  return lightning_stroke_time_s(strokes - 1, h) + 5.0f * decay_s;
}

// The luminance (cd/m^2) of the cloud's face at `r_m` from a flash of `flux_lm` inside it.
float lightning_glow_cd_m2(float flux_lm, float r_m) {
  float l = LIGHTNING_SPREAD_M;
  return flux_lm * exp(-r_m / l) / (2.0f * 3.14159265f * 3.14159265f * l * l);
}

// The chance that a candidate place in a storm cell's core flashes in a slot, for
// `per_min` flashes a minute a cell: the cell's flashes in a slot spread over the candidates
// that fall in its core (`candidates` a tile of `tile_m2`, a core of `core_m2`).
float lightning_candidate_chance(float per_min, float candidates, float tile_m2, float core_m2) {
  float in_core = candidates * core_m2 / tile_m2;
  return min(per_min / 60.0f * LIGHTNING_SLOT_S / max(in_core, 1e-6f), 1.0f);
}

#endif

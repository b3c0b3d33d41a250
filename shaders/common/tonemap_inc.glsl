// Tone mapping for display, shared by tonemap.comp and the PNG writer's tests: the ACES fit
// and the sRGB transfer function, as src/image/image.cpp applies them to 8-bit files.
#ifndef NEPHELE_TONEMAP_INC
#define NEPHELE_TONEMAP_INC

// Narkowicz 2015 fit of the ACES filmic curve, for x >= 0, clamped to [0, 1].
float aces_fit(float x) {
  float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return clamp(y, 0.0f, 1.0f);
}

// The sRGB opto-electronic transfer function (IEC 61966-2-1), v in [0, 1].
float srgb_oetf(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * pow(v, 1.0f / 2.4f) - 0.055f;
}

// One linear channel, already exposed, to its sRGB value in [0, 1]: NaN and negatives are
// black; values are capped at 1e4, far above where the curve saturates (about 7.2).
float display_channel(float v) {
  v = v > 0.0f ? min(v, 1.0e4f) : 0.0f;
  return srgb_oetf(aces_fit(v));
}

#endif

// Tone mapping for display, shared by tonemap.comp and the PNG writer (src/image/image.cpp,
// through render/glsl.h): the operators of output.tonemap (nephele/tonemap.h) and the sRGB
// transfer function. Each maps exposed linear radiance (>= 0) to [0, 1], linear, before the
// sRGB encoding.
#ifndef NEPHELE_TONEMAP_INC
#define NEPHELE_TONEMAP_INC

// The operators (nephele::ToneMap's order).
const int TONEMAP_ACES = 0;
const int TONEMAP_AGX = 1;
const int TONEMAP_UNCHARTED2 = 2;
const int TONEMAP_REINHARD = 3;
const int TONEMAP_NONE = 4;

// Narkowicz 2015 fit of the ACES filmic curve, for x >= 0, clamped to [0, 1].
float aces_fit(float x) {
  float y = (x * (2.51f * x + 0.03f)) / (x * (2.43f * x + 0.59f) + 0.14f);
  return clamp(y, 0.0f, 1.0f);
}

// Hable's filmic curve (Uncharted 2, as seed 002 takes it from filmicworlds.com): shoulder
// strength A, linear strength B, linear angle C, toe strength D, toe numerator E, toe
// denominator F.
float hable_curve(float x) {
  const float A = 0.15f, B = 0.50f, C = 0.10f, D = 0.20f, E = 0.02f, F = 0.30f;
  return (x * (A * x + C * B) + D * E) / (x * (A * x + B) + D * F) - E / F;
}

// Hable's operator: the curve at twice the exposure (his exposure bias), over its value at the
// white point W = 11.2.
float uncharted2(float x) {
  return clamp(hable_curve(2.0f * x) / hable_curve(11.2f), 0.0f, 1.0f);
}

// AgX (Sobotka 2022), in its common closed form: the colour turned into AgX's inset primaries,
// log2-encoded over [-12.47393, 4.026069] EV (mid grey 0.18 at 0.606), through a sigmoid fitted
// as a polynomial of degree 6, out of the inset and from its 2.2 display encoding to linear.
const float AGX_MIN_EV = -12.47393f;
const float AGX_MAX_EV = 4.026069f;

float agx_sigmoid(float x) {
  float x2 = x * x, x4 = x2 * x2;
  return 15.5f * x4 * x2 - 40.14f * x4 * x + 31.96f * x4 - 6.868f * x2 * x + 0.4298f * x2 +
         0.1191f * x - 0.00232f;
}

vec3 agx(vec3 c) {
  const mat3 inset = mat3(0.842479062253094f, 0.0423282422610123f, 0.0423756549057051f,
                          0.0784335999999992f, 0.878468636469772f, 0.0784336f,
                          0.0792237451477643f, 0.0791661274605434f, 0.879142973793104f);
  const mat3 outset = mat3(1.19687900512017f, -0.0528968517574562f, -0.0529716355144438f,
                           -0.0980208811401368f, 1.15190312990417f, -0.0980434501171241f,
                           -0.0990297440797205f, -0.0989611768448433f, 1.15107367264116f);
  vec3 v = inset * c;
  vec3 encoded;
  for (int i = 0; i < 3; ++i) {
    float e = clamp(log2(max(v[i], 1e-10f)), AGX_MIN_EV, AGX_MAX_EV);
    encoded[i] = agx_sigmoid((e - AGX_MIN_EV) / (AGX_MAX_EV - AGX_MIN_EV));
  }
  vec3 display = outset * encoded;
  vec3 linear;
  for (int i = 0; i < 3; ++i) linear[i] = pow(clamp(display[i], 0.0f, 1.0f), 2.2f);
  return linear;
}

// Exposed linear radiance (rgb >= 0) through operator `op`, to linear [0, 1].
vec3 tone_map(int op, vec3 c) {
  if (op == TONEMAP_AGX) return agx(c);
  vec3 out_c;
  for (int i = 0; i < 3; ++i) {
    float x = c[i];
    if (op == TONEMAP_UNCHARTED2) out_c[i] = uncharted2(x);
    else if (op == TONEMAP_REINHARD) out_c[i] = x / (1.0f + x);
    else if (op == TONEMAP_NONE) out_c[i] = clamp(x, 0.0f, 1.0f);
    else out_c[i] = aces_fit(x);
  }
  return out_c;
}

// The sRGB opto-electronic transfer function (IEC 61966-2-1), v in [0, 1].
float srgb_oetf(float v) {
  return v <= 0.0031308f ? 12.92f * v : 1.055f * pow(v, 1.0f / 2.4f) - 0.055f;
}

// One pixel, already exposed, to its sRGB values in [0, 1]: NaN and negatives are black;
// values are capped at 1e4, far above where the curves saturate.
vec3 display_rgb(int op, vec3 c) {
  vec3 v;
  for (int i = 0; i < 3; ++i) v[i] = c[i] > 0.0f ? min(c[i], 1.0e4f) : 0.0f;
  vec3 mapped = tone_map(op, v);
  return vec3(srgb_oetf(mapped.x), srgb_oetf(mapped.y), srgb_oetf(mapped.z));
}

#endif

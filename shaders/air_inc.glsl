// The air in front of the clouds, for the passes that draw clouds (clouds.comp,
// classic_clouds.comp). Reads the frame's parameters, so it is GLSL only.
#ifndef NEPHELE_AIR_INC
#define NEPHELE_AIR_INC

#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

const float FAR_M = 1.0e7f;  // distance written for rays that meet neither cloud nor ground

// Transmittance of the air over `dist_m` from the eye to a cloud sample at altitude
// `sample_alt_m`, with the extinction taken at the mean altitude (a simple aerial perspective;
// distant clouds fade into the haze of the sky behind them).
vec3 air_transmittance(float eye_alt_m, float sample_alt_m, float dist_m) {
  float h = max(0.5f * (eye_alt_m + sample_alt_m), 0.0f);
  vec3 sigma_t = frame.rayleigh.rgb * exp(-h / frame.rayleigh.w) + frame.mie.y * exp(-h / frame.mie.z);
  return exp(-sigma_t * dist_m);
}

#endif

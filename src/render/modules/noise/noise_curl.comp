#version 450
// Pass 1d: curl noise, 128^2, tiles (seed 002: "we offset the field with a 2D curl noise
// texture"; Bridson et al. 2007): the curl (d psi / dy, -d psi / dx) of a Perlin fBm
// potential psi, a divergence-free field of swirls. The clouds displace the detail noise by it
// (curl distortion) and read it at a larger scale as the flow map of local swirls. RG the
// field (unit root-mean-square), BA unused.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/noise_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// The potential at uv (tile units): three Perlin octaves of 4, 8 and 16 cells per tile.
float curl_potential(vec2 uv, uint seed) {
  float sum = 0.0f;
  float amplitude = 1.0f;
  int p = 4;
  for (int i = 0; i < 3; ++i) {
    sum += amplitude * perlin_tiled(vec3(uv * float(p), 0.5f), p, seed + uint(i)) / float(p);
    amplitude *= 0.6f;
    p *= 2;
  }
  return sum;
}

// Scales the field to a root-mean-square magnitude of 1 (measured over the tile by
// noise_texture_test.cpp's CurlNoise test, which checks it).
const float CURL_NORMALISATION = 1.13f;

void main() {
  ivec2 size = imageSize(curl_noise_out);
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(id, size))) return;
  vec2 uv = (vec2(id) + 0.5f) / vec2(size);
  uint seed = uint(frame.size.w) * 101u + 29u;
  float e = 0.25f / float(size.x);  // central differences a quarter texel apart
  float d_dx = curl_potential(uv + vec2(e, 0.0f), seed) - curl_potential(uv - vec2(e, 0.0f), seed);
  float d_dy = curl_potential(uv + vec2(0.0f, e), seed) - curl_potential(uv - vec2(0.0f, e), seed);
  vec2 curl = vec2(d_dy, -d_dx) / (2.0f * e) * CURL_NORMALISATION;
  imageStore(curl_noise_out, id, vec4(curl, 0.0f, 0.0f));
}

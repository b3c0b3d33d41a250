#version 450
// Pass: the frame's flashes (lightning_inc.glsl). Flashes start in slots of LIGHTNING_SLOT_S;
// in each slot every tile of the ground (LIGHTNING_TILES^2 around the camera, fixed to the
// ground) has LIGHTNING_CANDIDATES places hashed from the seed, the tile and the slot, and a
// place in a storm cell's core (the low layer's weather map, moved by the wind as its clouds
// are) flashes with the block's chance. The flashes of this slot and the last that are still
// bright are ranked by how brightly they light the camera, the first LIGHTNING_MAX_FLASHES of
// them written, and the bolt of the first that strikes the ground: a main channel from the
// cloud base to the ground that wanders as it falls, and three branches. One workgroup; the
// same seed and time give the same flashes.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/clouds_inc.glsl"
#include "common/noise_inc.glsl"
#include "common/lightning_inc.glsl"
#include "weather_map_inc.glsl"
#include "render/modules/lightning/lightning_gpu_inc.glsl"

layout(std140, set = 1, binding = 7) uniform LightningBlock { LightningGpu lightning; };
layout(std430, set = 1, binding = 6) writeonly buffer LightningFlashesOut { LightningFlashesGpu flashes; };

layout(local_size_x = 64) in;

const int PER_SLOT = LIGHTNING_TILES * LIGHTNING_TILES * LIGHTNING_CANDIDATES;
shared float flux_of[2 * PER_SLOT];  // each candidate's flux this frame (lm; 0: none)

// A candidate: its tile and slot's cell for the hashes.
ivec3 candidate_cell(int c) {
  int back = c / PER_SLOT, rest = c % PER_SLOT;
  int tile = rest / LIGHTNING_CANDIDATES;
  ivec2 t = lightning.slot.zw + ivec2(tile % LIGHTNING_TILES, tile / LIGHTNING_TILES) - LIGHTNING_TILES / 2;
  int slot = lightning.slot.x - 1 + back;
  return ivec3(t, slot * LIGHTNING_CANDIDATES + rest % LIGHTNING_CANDIDATES);
}

// Where a candidate is on the ground (planet frame x, y; m).
vec2 candidate_xy(int c) {
  ivec3 cell = candidate_cell(c);
  vec2 h = hash_cell(cell, uint(lightning.slot.y)).xy;
  return (vec2(cell.xy) + h) * lightning.cloud.z;
}

// Whether the candidate's flash strikes the ground (else it stays in the cloud), and the hash
// that times it.
vec3 candidate_timing(int c) { return hash_cell(candidate_cell(c), uint(lightning.slot.y) + 7919u); }
bool candidate_strikes(int c) { return candidate_timing(c).z < lightning.when.z; }

// A place on the ground's sphere at `altitude_m` over `xy`.
vec3 planet_at(vec2 xy, float altitude_m) {
  return normalize(vec3(xy, frame.radii_m.x)) * (frame.radii_m.x + altitude_m);
}

// Whether a storm cell's core is over xy, as the clouds have it now.
bool in_core(vec2 xy) {
  CloudLayerGpu layer = frame.cloud_layers[0];
  vec2 ground_xy = xy - vec2(layer.wind);
  vec4 weather = weather_map_at(layer, ground_xy);
  return cloud_storm_cell(weather.g, layer.shape.w).x >= 0.5f;
}

// The candidate's flux this frame (lm), 0 where it does not flash or is over.
float candidate_flux(int c) {
  ivec3 cell = candidate_cell(c);
  uint seed = uint(lightning.slot.y);
  if (hash_cell(cell, seed).z >= lightning.when.y) return 0.0f;
  vec3 h = candidate_timing(c);
  int back = c / PER_SLOT;
  float since_s = float(1 - back) * LIGHTNING_SLOT_S + lightning.when.x - h.x * LIGHTNING_SLOT_S;
  if (since_s <= 0.0f) return 0.0f;
  int strokes = lightning_strokes(h.y);
  float decay_s = candidate_strikes(c) ? LIGHTNING_STROKE_S : LIGHTNING_PULSE_S;
  if (since_s > lightning_duration_s(strokes, decay_s, h.y)) return 0.0f;
  if (!in_core(candidate_xy(c))) return 0.0f;
  return lightning_flux_lm(since_s, strokes, decay_s, h.y);
}

// The bolt of candidate c, from its cloud base over xy down to the ground.
void write_bolt(int c, vec2 xy, float flux_lm) {
  uint seed = uint(lightning.slot.y) + 104729u;
  ivec3 cell = candidate_cell(c);
  float base_m = lightning.cloud.x;
  const int MAIN = 36;
  float step_m = base_m / float(MAIN - 1);
  vec2 offset = vec2(0.0f);
  float length_m = 0.0f;
  vec3 lo = vec3(1e30f), hi = vec3(-1e30f);
  vec2 main_offset[MAIN];
  for (int j = 0; j < MAIN; ++j) {
    if (j > 0) {
      vec2 r = hash_cell(cell * ivec3(1, 1, 64) + ivec3(0, 0, j), seed).xy - 0.5f;
      offset += r * 1.1f * step_m;
      length_m += length(vec3(r * 1.1f * step_m, step_m));
    }
    main_offset[j] = offset;
    vec3 v = planet_at(xy + offset, base_m - float(j) * step_m);
    flashes.bolt_vertex[j] = vec4(v, j == 0 ? 0.0f : 1.0f);
    lo = min(lo, v);
    hi = max(hi, v);
  }
  int n = MAIN;
  for (int b = 0; b < 3; ++b) {
    vec3 h = hash_cell(cell * ivec3(1, 1, 64) + ivec3(0, 0, 40 + b), seed);
    int from = 3 + int(h.x * 20.0f);
    vec2 out_dir = normalize(vec2(cos(6.2831853f * h.y), sin(6.2831853f * h.y)));
    vec2 branch = main_offset[from];
    float altitude_m = base_m - float(from) * step_m;
    flashes.bolt_vertex[n++] = vec4(planet_at(xy + branch, altitude_m), 0.0f);
    for (int k = 1; k <= 6; ++k) {
      vec2 r = hash_cell(cell * ivec3(1, 1, 64) + ivec3(0, 0, 50 + 8 * b + k), seed).xy - 0.5f;
      branch += (0.6f * out_dir + r) * step_m;
      altitude_m -= 0.7f * step_m;
      vec3 v = planet_at(xy + branch, max(altitude_m, 0.0f));
      flashes.bolt_vertex[n++] = vec4(v, 0.3f * (1.0f - float(k) / 7.0f));
      lo = min(lo, v);
      hi = max(hi, v);
    }
  }
  for (int j = n; j < LIGHTNING_BOLT_VERTICES; ++j) flashes.bolt_vertex[j] = vec4(0.0f);
  flashes.bolt = vec4(flux_lm, length_m, 0.5f * length(hi - lo), float(n));
  flashes.bolt_centre = vec4(0.5f * (lo + hi), 0.0f);
}

void main() {
  int lane = int(gl_LocalInvocationID.x);
  for (int c = lane; c < 2 * PER_SLOT; c += 64) flux_of[c] = candidate_flux(c);
  barrier();
  if (lane != 0) return;
  // The flashes that light the view most: the brightest at the camera (flux over the squared
  // distance, within 10 km alike), in the candidates' order among equals.
  int chosen[LIGHTNING_MAX_FLASHES];
  float score[LIGHTNING_MAX_FLASHES];
  for (int k = 0; k < LIGHTNING_MAX_FLASHES; ++k) chosen[k] = -1, score[k] = 0.0f;
  vec2 eye_xy = frame.camera_pos_m.xy;
  for (int c = 0; c < 2 * PER_SLOT; ++c) {
    if (flux_of[c] <= 0.0f) continue;
    vec2 d = candidate_xy(c) - eye_xy;
    float s = flux_of[c] / max(dot(d, d), 1e8f);
    for (int k = 0; k < LIGHTNING_MAX_FLASHES; ++k) {
      if (s <= score[k]) continue;
      for (int m = LIGHTNING_MAX_FLASHES - 1; m > k; --m) chosen[m] = chosen[m - 1], score[m] = score[m - 1];
      chosen[k] = c;
      score[k] = s;
      break;
    }
  }
  int found = 0;
  bool bolt = false;
  flashes.bolt = vec4(0.0f);
  for (int k = 0; k < LIGHTNING_MAX_FLASHES && chosen[k] >= 0; ++k) {
    int c = chosen[k];
    float flux_lm = flux_of[c];
    bool to_ground = candidate_strikes(c);
    vec2 xy = candidate_xy(c);
    float base_m = lightning.cloud.x, top_m = lightning.cloud.y;
    float u = hash_cell(candidate_cell(c), uint(lightning.slot.y) + 31337u).x;
    // In the cloud: a stroke's light enters the cloud over the channel's top; an in-cloud
    // flash lies in the cell's middle third.
    float altitude_m = to_ground ? base_m + 300.0f : base_m + (0.3f + 0.4f * u) * (top_m - base_m);
    flashes.flash[found] = vec4(planet_at(xy, altitude_m), flux_lm);
    flashes.kind[found] = vec4(to_ground ? 1.0f : 0.0f, 0.0f, 0.0f, 0.0f);
    if (to_ground && !bolt) {
      write_bolt(c, xy, flux_lm);
      bolt = true;
    }
    ++found;
  }
  for (int k = found; k < LIGHTNING_MAX_FLASHES; ++k) {
    flashes.flash[k] = vec4(0.0f);
    flashes.kind[k] = vec4(0.0f);
  }
}

// The precipitation's particles near the camera, shared by their raster pass's shaders
// (precipitation_particles.vert and .frag; the medium puts what they draw in front,
// precipitation_medium.glsl).
//
// The particles live in a grid that falls with them (the block's near: the camera's place in
// it, from the time and their velocity, so a sequence and a re-render agree), one in each cell
// at a place hashed from the cell, standing for as many as the rate puts in a cell
// (precipitation_particles_per_m3). Each is drawn as the segment it sweeps over the shutter, a
// quad around it in the image; a pixel sees it by the share of its area and of the exposure it
// covers (precipitation_streak_opacity), fading with the distance from the segment over the
// larger of the particle's and the pixel's width.
#ifndef NEPHELE_PRECIPITATION_PARTICLES_INC
#define NEPHELE_PRECIPITATION_PARTICLES_INC

#include "common/math_inc.glsl"
#include "common/noise_inc.glsl"
#include "render/modules/precipitation/precipitation_field_inc.glsl"

// Where the particle of `cell` is at the shutter's close, relative to the eye (m).
vec3 precipitation_particle_now(ivec3 cell) {
  float cell_m = precipitation.near.w;
  vec3 streak = precipitation.streak.xyz;
  float d_m = precipitation.streak.w;
  float flutter_m = precipitation.particles.z;
  vec3 h = hash_cell(cell & 127, 7u);
  // Anywhere in its cell that keeps its streak, back to where it was when the shutter opened,
  // and its flutter inside.
  vec3 low = vec3(d_m + flutter_m) + max(streak, 0.0f);
  vec3 span = vec3(cell_m) - low - (vec3(d_m + flutter_m) + max(-streak, 0.0f));
  vec3 now = vec3(cell) * cell_m - precipitation.near.xyz + low + h * max(span, 0.0f);
  float phase = precipitation.particles.w + 6.2831853f * h.x;
  now.xy += flutter_m * vec2(sin(phase), cos(1.3f * phase));
  return now;
}

// The opacity at which the particle now at `now` (relative to the eye) is seen along `dir`
// (x), and where along it (y, m), for pixels spanning `pixel_rad`.
vec2 precipitation_particle_seen(vec3 now, vec3 dir, float pixel_rad) {
  float d_m = precipitation.streak.w;
  vec3 e = -precipitation.streak.xyz;  // back to where it was when the shutter opened
  vec3 closest = ray_segment_closest(dir, now, e);
  float t = closest.x;
  float footprint_m = pixel_rad * t;
  float width_m = max(d_m, footprint_m);
  float across_m = length(e - dir * dot(dir, e));  // the streak's length across the view
  float opacity = precipitation.particles.x * precipitation_streak_opacity(d_m, across_m, footprint_m) *
                  saturate(1.0f - closest.y / width_m);
  // Fading in from a hand's breadth (nothing sits on the lens) and out towards the range.
  float range_m = precipitation.particles.y;
  opacity *= smoothstep(0.2f, 0.5f, t) * (1.0f - smoothstep(0.6f * range_m, range_m, t));
  return vec2(min(opacity, 1.0f), t);
}

#endif

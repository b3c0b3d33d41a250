// The precipitation's particles near the camera as one of compose's translucent layers
// (cmake/module_registry.cmake): rain as streaks, snow and sleet as flakes, drawn one by one out
// to the block's range, where the froxels' medium (precipitation_medium.glsl) carries on.
//
// The particles live in a grid that falls with them (the block's near: the camera's place in
// it, from the time and their velocity, so a sequence and a re-render agree), one in each cell
// at a place hashed from the cell, standing for as many as the rate puts in a cell
// (precipitation_particles_per_m3). The view's ray walks the cells it crosses (Amanatides and
// Woo 1987) and meets each cell's particle as the segment it sweeps over the shutter; the pixel
// sees it by the share of its area and the exposure it covers (precipitation_streak_opacity),
// fading with the distance from the segment over the larger of the particle's and the pixel's
// width. A particle's light is the medium's in-scattered light where the camera is (it scatters
// what reaches it as the medium does, nearly without absorbing), under the clouds' shade, and
// the lightning's.
// GLSL only; the includer includes bindings_inc.glsl.
#ifndef NEPHELE_PRECIPITATION_LAYER
#define NEPHELE_PRECIPITATION_LAYER

#include "common/noise_inc.glsl"
#include "render/modules/precipitation/precipitation_field_inc.glsl"

// The cells a ray walks at most (the range over the smallest cells, across their diagonal).
const int PRECIPITATION_NEAR_CELLS = 64;

// The opacity at which a particle of `cell` (its lowest corner `origin_m`, relative to the
// eye) is seen along `dir`, and where (m along the ray).
vec2 precipitation_particle_seen(ivec3 cell, vec3 origin_m, vec3 dir, float pixel_rad) {
  float cell_m = precipitation.near.w;
  vec3 streak = precipitation.streak.xyz;
  float d_m = precipitation.streak.w;
  float flutter_m = precipitation.particles.z;
  vec3 h = hash_cell(cell & 127, 7u);
  // Where it is now: anywhere in its cell that keeps its streak, back to where it was when the
  // shutter opened, and its flutter inside.
  vec3 room = vec3(d_m + flutter_m) + max(streak, 0.0f);
  vec3 span = vec3(cell_m) - room - (vec3(d_m + flutter_m) + max(-streak, 0.0f));
  vec3 now = origin_m + room + h * max(span, 0.0f);
  float phase = precipitation.particles.w + 6.2831853f * h.x;
  now.xy += flutter_m * vec2(sin(phase), cos(1.3f * phase));
  // The closest approach of the ray (from the eye) and the segment now - u streak, u in [0, 1].
  vec3 e = -streak;
  vec3 closest = ray_segment_closest(dir, now, e);
  float t = closest.x, miss_m = closest.y;
  float footprint_m = pixel_rad * t;
  float width_m = max(d_m, footprint_m);
  float across_m = length(e - dir * dot(dir, e));  // the streak's length across the view
  float opacity = precipitation.particles.x *
                  precipitation_streak_opacity(d_m, across_m, footprint_m) *
                  saturate(1.0f - miss_m / width_m);
  // Fading in from a hand's breadth (nothing sits on the lens) and out towards the range.
  float range_m = precipitation.particles.y;
  opacity *= smoothstep(0.2f, 0.5f, t) * (1.0f - smoothstep(0.6f * range_m, range_m, t));
  return vec2(min(opacity, 1.0f), t);
}

vec4 precipitation_layer(vec2 uv, out float distance_m) {
  distance_m = 0.0f;
  float cell_m = precipitation.near.w;
  if (precipitation.fall.z <= 0.0f || cell_m <= 0.0f) return vec4(0.0f);
  vec3 eye = frame.camera_pos_m.xyz;
  float share = precipitation_share_at(eye).x;
  if (share <= 0.0f) return vec4(0.0f);
  vec2 image = vec2(frame.size.xy);
  vec2 pixel = uv * image - 0.5f;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, pixel.x, pixel.y, image.x,
                        image.y, vec2(frame.camera_right.w, frame.camera_up.w));
  float pixel_rad = 2.0f * frame.camera_pos_m.w / image.y;
  // The walk through the falling grid (in cells), from the camera's place in it.
  vec3 start = precipitation.near.xyz / cell_m;
  ivec3 cell = ivec3(floor(start));
  vec3 inv = 1.0f / max(abs(dir), vec3(1e-6f));
  ivec3 step_cell = ivec3(sign(dir));
  vec3 next = (vec3(cell) + step(0.0f, dir) - start) * sign(dir) * inv;  // cells to each wall
  float range_cells = precipitation.particles.y / cell_m;
  float transmittance = 1.0f, depth_m = 0.0f;
  for (int i = 0; i < PRECIPITATION_NEAR_CELLS; ++i) {
    vec2 seen = precipitation_particle_seen(cell, (vec3(cell) - start) * cell_m, dir, pixel_rad);
    float opacity = seen.x * share;
    depth_m += transmittance * opacity * seen.y;
    transmittance *= 1.0f - opacity;
    float wall = min(next.x, min(next.y, next.z));
    if (wall > range_cells) break;
    bvec3 crossed = lessThanEqual(next, vec3(wall));
    cell += ivec3(crossed) * step_cell;
    next += vec3(crossed) * inv;
  }
  float alpha = 1.0f - transmittance;
  if (alpha <= 0.0f) return vec4(0.0f);
  distance_m = depth_m / alpha;
  // The light of a particle where the camera is: the medium's (per unit of sigma_s and of the
  // key light), under the clouds' mean shade.
  vec3 light = precipitation_at(eye).rgb * texelFetch(ground_light, ivec2(0), 0).r *
               frame.sun_illuminance.rgb;
#ifdef NEPHELE_LIGHTNING_LAYER
  // And the flashes' (lightning_layer.glsl, included before it), scattered evenly.
  light += LIGHTNING_RGB * lightning_illuminance_lx(eye, vec3(0.0f)) / (4.0f * PI);
#endif
  return vec4(alpha * light, alpha);
}

#endif

// Nishita and Nakamae's voxel grid (render/modules/metaball_clouds/metaball_clouds.h): lookups into the three
// volumes stacked in nishita_volume (NISHITA_SLABS of classic_nishita_grid.z voxels each), on a
// flat earth in ENU metres. GLSL only.
#ifndef NEPHELE_NISHITA_VOLUME_INC
#define NEPHELE_NISHITA_VOLUME_INC

#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/noise_inc.glsl"
#include "common/classic_inc.glsl"

vec3 nishita_corner() { return frame.classic_nishita.xyz; }
float nishita_voxel_m() { return frame.classic_nishita.w; }
ivec3 nishita_dims() { return ivec3(frame.classic_nishita_grid.xyz); }

// Volume `slab` at the ENU point p, trilinear; nothing outside the grid (the filter clamps
// within the slab, so slabs never bleed into each other).
vec4 nishita_sample(int slab, vec3 p) {
  vec3 dims = vec3(nishita_dims());
  vec3 g = (p - nishita_corner()) / nishita_voxel_m();
  if (any(lessThan(g, vec3(0.0f))) || any(greaterThan(g, dims))) return vec4(0.0f);
  g = clamp(g, vec3(0.5f), dims - 0.5f);
  g.z += float(slab) * dims.z;
  return textureLod(nishita_volume, g / vec3(dims.xy, dims.z * float(NISHITA_SLABS)), 0.0f);
}

vec4 nishita_texel(int slab, ivec3 v) {
  return texelFetch(nishita_volume, ivec3(v.x, v.y, v.z + slab * nishita_dims().z), 0);
}

// The ray o + t d (d unit) in the grid's box: (t_enter, t_exit), t_exit <= t_enter when it
// misses.
vec2 nishita_box(vec3 o, vec3 d) {
  vec3 lo = nishita_corner(), hi = lo + vec3(nishita_dims()) * nishita_voxel_m();
  vec3 inv = 1.0f / mix(d, vec3(1e-12f), lessThan(abs(d), vec3(1e-12f)));
  vec3 t0 = (lo - o) * inv, t1 = (hi - o) * inv;
  vec3 near = min(t0, t1), far = max(t0, t1);
  return vec2(max(max(near.x, near.y), near.z), min(min(far.x, far.y), far.z));
}

// sigma_t integrated from p along d (unit) to where it leaves the grid, in steps of step_m.
float nishita_optical_depth(vec3 p, vec3 d, float step_m) {
  float t_exit = nishita_box(p, d).y;
  int steps = min(int(ceil(max(t_exit, 0.0f) / step_m)), 256);
  float dt = max(t_exit, 0.0f) / float(max(steps, 1));
  float depth = 0.0f;
  for (int i = 0; i < steps; ++i) depth += nishita_sample(0, p + d * ((float(i) + 0.5f) * dt)).r;
  return depth * dt * frame.classic_nishita_light.x;
}

#endif

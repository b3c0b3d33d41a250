// The reference path tracer (issue 21), included by path_trace.comp (CPU devices) and
// path_trace_gpu.comp (GPUs). Unbiased: delta tracking samples collisions, ratio tracking
// estimates each light's transmittance (next-event estimation at every collision),
// the phase functions are sampled exactly or with their ratio to a sampled one as a weight
// (common/path_inc.glsl). Each path carries the three colour channels, its events decided by
// one of them in turn (path_spectral_inc.glsl). Paths advance an iteration at a time and carry
// over from one dispatch to the next (PtPath, main below); each finished sample is added to its
// pixel's sums in path_sum and path_squares. Two scenes (PLANET, a specialization constant):
//  0 the lab: voxel cloud 0's density grid in vacuum (no planet, no air, black background)
//    with sigma_t = grid density x path_medium.x, lit by a distant sun of irradiance
//    path_light.w;
//  1 the planet: what the fast mode renders (the atmosphere's Rayleigh, Mie and ozone, the
//    noise and voxel clouds' density field and phase function (cloud_phase_function: the
//    seed's lobes or the droplets' Mie fit), a Lambertian ground), lit by
//    the key light and the second light (sun and moon, FrameParams::sun_dir, second_light),
//    the sun's disk seen directly.
layout(constant_id = 0) const int PLANET = 0;
// The cloud field's variant (cloud_field_inc.glsl): the scene's march mode, as the fast mode
// renders it.
layout(constant_id = 1) const int MARCH_MODE = 0;

#include "common/bindings_inc.glsl"
#include "dispatch_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/sun_disk_inc.glsl"
#include "cloud_field_inc.glsl"
#include "frame_atmosphere_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// The lab works in its own frame (FrameParams::path_eye_m): grid coordinates of a point there.
vec3 lab_grid_coord(VoxelCloudGpu c, vec3 p) {
  return vec3(dot(c.to_grid_x.xyz, p) + c.to_grid_x.w, dot(c.to_grid_y.xyz, p) + c.to_grid_y.w,
              dot(c.to_grid_z.xyz, p) + c.to_grid_z.w);
}

vec3 lab_grid_dir(VoxelCloudGpu c, vec3 d) {
  return vec3(dot(c.to_grid_x.xyz, d), dot(c.to_grid_y.xyz, d), dot(c.to_grid_z.xyz, d));
}

// The medium for path_inc.glsl: the grid's box and its trilinear density, as the fast mode
// samples them (voxel_lookup), without the surface erosion the clouds pass adds.
float lab_sigma_t(vec3 p) {
  VoxelCloudGpu c = frame.voxel_clouds[0];
  vec3 u = lab_grid_coord(c, p);
  if (voxel_box_distance(u, c.dims.xyz) > 0.0f) return 0.0f;
  return voxel_lookup(c, u).x * c.anchor_m.w * frame.path_medium.x;
}

// Where the ray (o, d) is inside the grid's box: slabs in grid coordinates (voxels, the map
// being a rotation and a scale, t stays in metres).
vec2 lab_bounds(vec3 o, vec3 d) {
  VoxelCloudGpu c = frame.voxel_clouds[0];
  vec3 u = lab_grid_coord(c, o);
  vec3 du = lab_grid_dir(c, d);
  vec3 inv = 1.0f / mix(vec3(1e-30f), du, greaterThan(abs(du), vec3(1e-30f)));
  vec3 t0 = -u * inv, t1 = (c.dims.xyz - u) * inv;
  vec3 near = min(t0, t1), far = max(t0, t1);
  return vec2(max(max(near.x, near.y), max(near.z, 0.0f)), min(far.x, min(far.y, far.z)));
}

// The majorant grid: the grid's bricks (VOXEL_BRICK^3 voxels, as voxel_lookup cuts them: brick
// b spans grid coordinates [8 b + 1/2, 8 b + 8 1/2)). An empty brick (not stored: no density
// within it or its filter's reach) has majorant 0 and is crossed in one step; a stored one its
// own largest extinction (path_majorant: lab_brick_majorants, render/path_majorant.h). Along
// the line u(o) + t du, so that successive calls agree on where a boundary is. Without the
// grid (path_eye_m.w = 0), one segment at the grid's largest extinction (path_medium.w).
vec2 lab_majorant_segment(vec3 o, vec3 d, float t) {
  if (frame.path_eye_m.w == 0.0f) return vec2(frame.path_medium.w, 1e30f);
  VoxelCloudGpu c = frame.voxel_clouds[0];
  vec3 du = lab_grid_dir(c, d);
  vec3 u = lab_grid_coord(c, o) + du * t;
  // The brick a thousandth of a voxel ahead: a point on a boundary belongs to the next one.
  vec3 ahead = clamp(u + du * (1e-3f * c.dims.w), vec3(0.5f), c.dims.xyz - 0.5f);
  ivec3 b = min(ivec3(floor((ahead - 0.5f) / float(VOXEL_BRICK))), c.bricks.xyz - 1);
  float page = texelFetch(voxel_pages, ivec3(b.xy, b.z + c.bricks.w), 0).r;
  vec3 lo = vec3(b * VOXEL_BRICK) + 0.5f;
  vec3 boundary = mix(lo, lo + float(VOXEL_BRICK), greaterThan(du, vec3(0.0f)));
  vec3 to_boundary = (boundary - u) / mix(vec3(1e-30f), du, greaterThan(abs(du), vec3(1e-30f)));
  // Boundaries behind (the outer bricks reach the box's faces) do not end the segment.
  to_boundary = mix(vec3(1e30f), to_boundary, greaterThan(to_boundary, vec3(0.0f)));
  float end = t + max(min(to_boundary.x, min(to_boundary.y, to_boundary.z)), 1e-3f * c.dims.w);
  return vec2(page < 0.0f ? 0.0f : texelFetch(path_majorant, b, 0).r, end);
}

// The clouds' extinction at the last point planet_sigma_t3 evaluated (1/m): where delta
// tracking stops, the collision's, which the path then scatters by.
float pt_cloud_sigma_t = 0.0f;
// Tentative collisions where sigma_t exceeded its majorant in this sample (PT_NOTE_MAJORANT):
// never, if the majorants are right; counted in path_squares' alpha.
float pt_violations = 0.0f;
void pt_note_majorant(float sigma, float majorant) {
  if (sigma > majorant * 1.0001f + 1e-9f) pt_violations += 1.0f;
}
#define PT_NOTE_MAJORANT(sigma, majorant) pt_note_majorant(sigma, majorant)
// Tracking loops cut at PT_MAX_COLLISIONS (PT_NOTE_CUT): counted in path_cut.
float pt_cuts = 0.0f;
#define PT_NOTE_CUT() pt_cuts += 1.0f

// The shell (radii, m) where layer l's clouds can be, padded by PATH_SHELL_PAD_M (a layer that
// is off lies beyond the atmosphere); the voxel clouds' boxes lie between path_voxels.y and .z.
vec2 planet_layer_shell(int l) {
  return frame.cloud_layers[l].radii_m.xy + vec2(-PATH_SHELL_PAD_M, PATH_SHELL_PAD_M);
}

// A bound on a layer's density field (shape: CloudLayerGpu::shape): twice its density (the
// weather map's density channel doubles it), none without coverage or precipitation (a storm
// cell's coverage and its anvil come from the precipitation).
float planet_layer_bound(vec4 shape) {
  return shape.x > 0.0f || shape.w > 0.0f ? 2.0f * shape.y : 0.0f;
}

// The majorant grid's cell at xy (planet frame), or (-1, -1) outside it or without it.
ivec2 planet_grid_cell(vec2 xy) {
  vec2 g = floor((xy - frame.path_grid.xy) / frame.path_grid.z);
  bool inside = frame.path_grid.w > 0.0f && all(greaterThanEqual(g, vec2(0.0f))) &&
                all(lessThan(g, vec2(float(PATH_GRID_XY))));
  return inside ? ivec2(g) : ivec2(-1);
}

// The bin of radius r in a layer's padded shell `shell` (its lowest and highest radius).
int planet_grid_bin(float r, vec2 shell) {
  return clamp(int(floor((r - shell.x) / (shell.y - shell.x) * float(PATH_GRID_BINS))), 0,
               PATH_GRID_BINS - 1);
}

// The bound on the clouds' extinction (1/m) at q (0 where no cloud can be): per noise layer
// whose padded shell holds q, its majorant grid's cell where the grid reaches, else twice the
// layer's density; plus the voxel clouds' where their shell holds q.
float planet_cloud_bound(vec3 q) {
  float r = length(q);
  ivec2 cell = planet_grid_cell(q.xy);
  float bound = 0.0f;
  for (int l = 0; l < CLOUD_LAYERS; ++l) {
    vec2 shell = planet_layer_shell(l);
    if (r <= shell.x || r >= shell.y) continue;
    bound += cell.x >= 0
                 ? texelFetch(path_majorant, ivec3(cell, l * PATH_GRID_BINS + planet_grid_bin(r, shell)), 0).r
                 : planet_layer_bound(frame.cloud_layers[l].shape) * frame.cloud_shape.z;
  }
  if (r > frame.path_voxels.y && r < frame.path_voxels.z) bound += frame.path_voxels.x;
  return bound;
}

// The planet's medium per colour channel: the air, plus the clouds inside their shells.
vec3 planet_sigma_t3(vec3 p) {
  float r = length(p);
  vec3 air = atmosphere_sigma_t(frame_atmosphere(), r - frame.radii_m.x);
  float cloud = 0.0f;
  // A branch, not a loop of one trip (which a CPU device would skip when no lane is in a
  // shell): lavapipe ends every loop of an invocation once all its loops together have run
  // 65535 iterations, and tracking through clouds runs thousands.
  if (planet_cloud_bound(p) > 0.0f) cloud = cloud_density(p, true) * frame.cloud_shape.z;
  pt_cloud_sigma_t = cloud;
  return air + cloud;
}

// Where the ray is in the air: from where it enters the atmosphere (or its origin) to where it
// leaves it or meets the ground.
vec2 planet_bounds(vec3 o, vec3 d) {
  vec2 top = ray_sphere(o, d, frame.radii_m.y);
  if (top.y <= 0.0f) return vec2(0.0f, -1.0f);
  vec2 ground = ray_sphere(o, d, frame.radii_m.x);
  return vec2(max(top.x, 0.0f), ground.x > 0.0f ? min(ground.x, top.y) : top.y);
}

// The air's largest extinction in any channel between altitudes h_lo and h_hi (m): Rayleigh
// and Mie at h_lo (they fall with height), the ozone where nearest its peak.
float planet_air_majorant(float h_lo, float h_hi) {
  Atmosphere a = frame_atmosphere();
  float h = max(h_lo, 0.0f);
  float ozone = a.ozone_half_width_m > 0.0f
                    ? max(1.0f - abs(clamp(a.ozone_center_m, h, max(h_hi, h)) - a.ozone_center_m) /
                                     a.ozone_half_width_m, 0.0f)
                    : 0.0f;
  vec3 air = a.rayleigh_sigma_s * exp(-h / a.rayleigh_height_m) +
             a.mie_sigma_t * exp(-h / a.mie_height_m) + a.ozone_sigma_a * ozone;
  return max(air.x, max(air.y, air.z)) * 1.0001f;
}

// The air's majorant is taken per band between these altitudes (m), where the segments end, so
// a path high in the sky or crossing it is not tracked at the sea level's rate.
const int AIR_BANDS = 6;
const float AIR_BAND_M[AIR_BANDS] = float[](1000.0f, 2000.0f, 4000.0f, 8000.0f, 16000.0f, 32000.0f);

// The next crossing of the sphere of radius `radius` by the ray from p along d, beyond `near`
// (1e30: none).
float planet_next_sphere(vec3 p, vec3 d, float radius, float near) {
  vec2 hit = ray_sphere(p, d, radius);
  return hit.x > near ? hit.x : (hit.y > near ? hit.y : 1e30f);
}

// The majorant grid along the ray: spherical shells (each cloud layer's padded shell cut into
// PATH_GRID_BINS, the voxel clouds'), and the grid's cells horizontally. From o + d t to the
// next crossing of a shell's sphere, an air band's (AIR_BAND_M) or a cell's wall, the air's
// majorant over the segment's altitudes plus the clouds' bound (planet_cloud_bound) there, the
// larger of the segment's start and middle: a sphere
// closer than a metre is not ended at (the planet frame's floats are half a metre apart out
// there), so a segment may begin just before one.
vec2 planet_majorant_segment(vec3 o, vec3 d, float t) {
  vec3 p = o + d * t;
  float end = min(planet_next_sphere(p, d, frame.path_voxels.y, 1.0f),
                  planet_next_sphere(p, d, frame.path_voxels.z, 1.0f));
  float r = length(p);
  for (int l = 0; l < CLOUD_LAYERS; ++l) {
    // A layer that is off (the same for every lane) has no spheres to stop at.
    if (planet_layer_bound(frame.cloud_layers[l].shape) == 0.0f) continue;
    vec2 shell = planet_layer_shell(l);
    // Inside the shell, the spheres of the bin the ray is in; outside, the shell's own. And
    // a bin further on each side: a sphere within a metre is passed over, and the segment
    // must then end at the next one, not run on across bins its two points do not see.
    float bin_m = frame.path_grid.w > 0.0f ? (shell.y - shell.x) / float(PATH_GRID_BINS) : 0.0f;
    bool in_shell = r > shell.x && r < shell.y && frame.path_grid.w > 0.0f;
    float lo = in_shell ? shell.x + bin_m * float(planet_grid_bin(r, shell)) : shell.x;
    float hi = in_shell ? lo + bin_m : shell.y;
    end = min(end, min(planet_next_sphere(p, d, lo, 1.0f), planet_next_sphere(p, d, hi, 1.0f)));
    end = min(end, min(planet_next_sphere(p, d, lo - bin_m, 1.0f), planet_next_sphere(p, d, lo + bin_m, 1.0f)));
    end = min(end, min(planet_next_sphere(p, d, hi - bin_m, 1.0f), planet_next_sphere(p, d, hi + bin_m, 1.0f)));
  }
  if (frame.path_grid.w > 0.0f) {
    // The next wall of the grid's lattice ahead on each axis, within the grid: strictly ahead
    // of p (by 1e-4 of a cell, which floats resolve here), so that a segment never ends where
    // it starts however steep the ray.
    vec2 g = (p.xy - frame.path_grid.xy) / frame.path_grid.z;
    for (int a = 0; a < 2; ++a) {
      if (abs(d[a]) < 1e-12f) continue;
      float wall = d[a] > 0.0f ? max(floor(g[a] + 1e-4f) + 1.0f, 0.0f)
                               : min(ceil(g[a] - 1e-4f) - 1.0f, float(PATH_GRID_XY));
      if (wall < 0.0f || wall > float(PATH_GRID_XY)) continue;
      end = min(end, (frame.path_grid[a] + wall * frame.path_grid.z - p[a]) / d[a]);
    }
  }
  // The air's bands: the next crossing of a band's sphere.
  for (int b = 0; b < AIR_BANDS; ++b)
    end = min(end, planet_next_sphere(p, d, frame.radii_m.x + AIR_BAND_M[b], 1.0f));
  end = t + clamp(end, 1e-3f, 1e7f);
  float bound = max(planet_cloud_bound(p + d * 1e-3f), planet_cloud_bound(o + d * (0.5f * (t + end))));
  // The air's over the segment's altitudes: lowest at its ends or where the line passes
  // closest to the planet's centre, highest at an end.
  float t_low = clamp(-dot(o, d), t, end);
  float r_end = length(o + d * end);
  float r_low = min(length(o + d * t_low), min(length(p), r_end));
  float r_high = max(length(p), r_end);
  return vec2(planet_air_majorant(r_low - frame.radii_m.x, r_high - frame.radii_m.x) + bound, end);
}

// The paths track three channels (path_spectral_inc.glsl); the lab's medium is grey.
float pt_sigma_t(vec3 p) { return lab_sigma_t(p); }
vec3 pt_sigma_t3(vec3 p) { return PLANET == 1 ? planet_sigma_t3(p) : vec3(lab_sigma_t(p)); }
vec2 pt_bounds(vec3 o, vec3 d) { return PLANET == 1 ? planet_bounds(o, d) : lab_bounds(o, d); }
vec2 pt_majorant_segment(vec3 o, vec3 d, float t) {
  return PLANET == 1 ? planet_majorant_segment(o, d, t) : lab_majorant_segment(o, d, t);
}

#include "common/path_inc.glsl"
#include "common/path_spectral_inc.glsl"

// A unit direction with density cos(angle to n) / pi (Malley's method).
vec3 pt_sample_cosine(vec3 n, float u1, float u2) {
  float r = sqrt(u1);
  float phi = 2.0f * PI * u2;
  vec3 t1 = normalize(abs(n.z) < 0.9f ? cross(n, vec3(0.0f, 0.0f, 1.0f)) : cross(n, vec3(1.0f, 0.0f, 0.0f)));
  vec3 t2 = cross(n, t1);
  return normalize(r * cos(phi) * t1 + r * sin(phi) * t2 + sqrt(max(1.0f - u1, 0.0f)) * n);
}

// The lights of the planet: towards it, and its illuminance at the top of the atmosphere per
// channel (0: none).
vec3 planet_light_dir(int i) { return i == 0 ? frame.sun_dir.xyz : frame.second_light.xyz; }
vec3 planet_light_rgb(int i) {
  return frame.sun_illuminance.rgb * (i == 0 ? 1.0f : frame.second_light.w);
}

// A path in progress: what it has gathered, where it is, and what it does next (stage). Paths
// advance one tentative collision an iteration and carry over from one dispatch to the next in
// path_state (PATH_STATE_TEXELS texels a path; path_state_load, path_state_store): lavapipe
// ends an invocation's loops once all of them have run 65535 iterations, and cut that way a
// path through thick cloud was biased, its tracking ended early. A dispatch runs at most
// dispatch.values.y iterations an invocation, and where the limit ends it sooner, the
// iteration it cut is undone and done again in the next (main).
const int PT_IDLE = 0;     // between samples: the next one starts
const int PT_FLIGHT = 1;   // delta tracking to the next collision (track)
const int PT_SHADOW = 2;   // ratio tracking towards light `light` (track)
const int PT_LIGHTS = 3;   // next-event estimation from light `light` or the next
const int PT_SCATTER = 4;  // a new direction after the lights
const int PT_BOUNCE = 5;   // the flight from x along d begins
const int PT_DONE = 6;     // the sample's radiance is known

struct PtPath {
  vec3 x;             // where the path is
  int bounce;
  vec3 d;             // its direction (until PT_SCATTER: the one it came along)
  int stage;
  vec3 weight;        // each channel's albedos and phase ratios so far
  int hero;           // the channel deciding its events
  vec3 ratio;         // each channel's probability of the path's events / the hero's
  int light;          // the next light's turn (in PT_SHADOW, the one after the light tracked)
  vec3 radiance;      // gathered so far
  int started;        // samples this invocation's slot has begun
  vec3 pending;       // PT_SHADOW: the light's contribution before its transmittance
  float cloud_sigma;  // the clouds' sigma_t at the collision (1/m)
  bool at_ground;     // the collision is the ground's
  uint stream;        // the sample's random stream
  PtTrack track;
};

// Floats keep integers exactly below 2^24: a stream in two halves.
vec2 path_split(uint v) { return vec2(float(v & 0xffffu), float(v >> 16u)); }
uint path_join(vec2 v) { return uint(v.x) | (uint(v.y) << 16u); }

ivec2 path_state_texel(ivec2 texel, int k) {
  return texel + ivec2(0, k * imageSize(path_sum).y);
}

// (Written out, not looped: after lavapipe's loop limit has ended a pass early, a loop would
// run once.)
PtPath path_state_load(ivec2 texel) {
  vec4 v0 = imageLoad(path_state, path_state_texel(texel, 0));
  vec4 v1 = imageLoad(path_state, path_state_texel(texel, 1));
  vec4 v2 = imageLoad(path_state, path_state_texel(texel, 2));
  vec4 v3 = imageLoad(path_state, path_state_texel(texel, 3));
  vec4 v4 = imageLoad(path_state, path_state_texel(texel, 4));
  vec4 v5 = imageLoad(path_state, path_state_texel(texel, 5));
  vec4 v6 = imageLoad(path_state, path_state_texel(texel, 6));
  vec4 v7 = imageLoad(path_state, path_state_texel(texel, 7));
  vec4 v8 = imageLoad(path_state, path_state_texel(texel, 8));
  vec4 v9 = imageLoad(path_state, path_state_texel(texel, 9));
  vec4 v10 = imageLoad(path_state, path_state_texel(texel, 10));
  vec4 v11 = imageLoad(path_state, path_state_texel(texel, 11));
  PtPath p;
  p.x = v0.xyz;
  p.bounce = int(v0.w);
  p.d = v1.xyz;
  p.stage = int(v1.w);
  p.weight = v2.xyz;
  p.hero = int(v2.w);
  p.ratio = v3.xyz;
  p.light = int(v3.w);
  p.radiance = v4.xyz;
  p.started = int(v4.w);
  p.pending = v5.xyz;
  p.cloud_sigma = v5.w;
  p.track.o = v6.xyz;
  p.track.t_max = v6.w;
  p.track.d = v7.xyz;
  p.track.i = int(v7.w);
  p.track.walk = v8;
  p.track.value = v9.xyz;
  p.track.t = v9.w;
  p.stream = path_join(v10.xy);
  p.track.stream = path_join(v10.zw);
  p.track.hero = int(v11.x);
  p.track.done = v11.y > 0.5f;
  p.at_ground = v11.z > 0.5f;
  return p;
}

void path_state_store(ivec2 texel, PtPath p) {
  vec4 v0 = vec4(p.x, float(p.bounce));
  vec4 v1 = vec4(p.d, float(p.stage));
  vec4 v2 = vec4(p.weight, float(p.hero));
  vec4 v3 = vec4(p.ratio, float(p.light));
  vec4 v4 = vec4(p.radiance, float(p.started));
  vec4 v5 = vec4(p.pending, p.cloud_sigma);
  vec4 v6 = vec4(p.track.o, p.track.t_max);
  vec4 v7 = vec4(p.track.d, float(p.track.i));
  vec4 v8 = p.track.walk;
  vec4 v9 = vec4(p.track.value, p.track.t);
  vec4 v10 = vec4(path_split(p.stream), path_split(p.track.stream));
  vec4 v11 = vec4(float(p.track.hero), p.track.done ? 1.0f : 0.0f, p.at_ground ? 1.0f : 0.0f, 0.0f);
  imageStore(path_state, path_state_texel(texel, 0), v0);
  imageStore(path_state, path_state_texel(texel, 1), v1);
  imageStore(path_state, path_state_texel(texel, 2), v2);
  imageStore(path_state, path_state_texel(texel, 3), v3);
  imageStore(path_state, path_state_texel(texel, 4), v4);
  imageStore(path_state, path_state_texel(texel, 5), v5);
  imageStore(path_state, path_state_texel(texel, 6), v6);
  imageStore(path_state, path_state_texel(texel, 7), v7);
  imageStore(path_state, path_state_texel(texel, 8), v8);
  imageStore(path_state, path_state_texel(texel, 9), v9);
  imageStore(path_state, path_state_texel(texel, 10), v10);
  imageStore(path_state, path_state_texel(texel, 11), v11);
}

// The stream of the path's current bounce.
uint path_bounce_stream(PtPath p) { return pt_hash(p.stream ^ pt_hash(uint(p.bounce))); }

// Each channel's estimate of what reaches the eye by the path so far: its weight times the
// balance heuristic's share of the path (pt_hero_weights).
vec3 path_estimate(PtPath p) { return p.weight * pt_hero_weights(p.ratio); }

// The sun's disk met by a path leaving the air along d, seen directly by the camera (a point
// light for the paths that scatter, as for the fast mode).
vec3 path_sun_met(PtPath p) {
  if (PLANET == 0 || p.bounce > 0 || frame.sun_illuminance.w != 0.0f) return vec3(0.0f);
  return path_estimate(p) * planet_light_rgb(0) * sun_disk(p.d, frame.sun_dir.xyz, frame.sun_dir.w);
}

// PT_BOUNCE: the flight from x along d through the medium, or, where the ray misses it, the
// path's end (space is black but for the sun's disk seen directly; the lab's background black).
PtPath path_begin_bounce(PtPath p) {
  vec2 bounds = pt_bounds(p.x, p.d);
  if (bounds.y > bounds.x) {
    p.track = pt_track_begin(p.x + p.d * bounds.x, p.d, bounds.y - bounds.x,
                             pt_hash(path_bounce_stream(p) ^ 1u), p.hero);
    p.stage = PT_FLIGHT;
    return p;
  }
  p.radiance += path_sun_met(p);
  p.stage = PT_DONE;
  return p;
}

// The flight ended: at a collision in the medium, at the ground (a Lambertian surface of albedo
// sky_model.y), or out of the medium (as path_begin_bounce's miss).
PtPath path_flight_ended(PtPath p) {
  p.ratio *= p.track.value;
  bool collided = p.track.t <= p.track.t_max;
  if (PLANET == 0) {
    if (!collided) {
      p.stage = PT_DONE;
      return p;
    }
    p.x = p.track.o + p.track.d * p.track.t;
    p.weight *= frame.path_medium.y;  // sigma_s / sigma_t at a collision sampled by sigma_t T
  } else {
    bool ground = !collided && ray_sphere(p.x, p.d, frame.radii_m.x).x > 0.0f;
    if (!collided && !ground) {
      p.radiance += path_sun_met(p);
      p.stage = PT_DONE;
      return p;
    }
    p.at_ground = ground;
    if (ground) {  // lifted a metre, clear of its own sphere
      p.x = normalize(p.track.o + p.track.d * p.track.t_max) * (frame.radii_m.x + 1.0f);
    } else {
      p.x = p.track.o + p.track.d * p.track.t;
      p.cloud_sigma = pt_cloud_sigma_t;  // the collision's: the last point tracked
    }
  }
  p.light = 0;
  p.stage = PT_LIGHTS;
  return p;
}

// Whether the planet's light i lights the collision: it shines, and it is above the
// collision's horizon.
bool planet_light_up(PtPath p, int i) {
  return pt_max3(planet_light_rgb(i)) > 0.0f &&
         ray_sphere(p.x, planet_light_dir(i), frame.radii_m.x).x <= 0.0f;
}

// PT_LIGHTS: the contribution at the collision of light `light`, or of the next one that lights
// it. Where the medium lies between, its transmittance is tracked (PT_SHADOW) and the
// contribution waits in `pending`; else it is added at once. Then PT_LIGHTS again while a light
// is left that lights the collision (its turn comes in the next iteration, or as its shadow
// ends), else PT_SCATTER. The planet's lights are the sun and the moon (each channel's
// sigma_s-weighted phase over sigma_t at a collision, Lambert's cosine over pi at the ground),
// the lab's its one light (albedo and Henyey-Greenstein). One light an iteration, in one copy
// of this code: lavapipe runs a branch for every lane of a SIMD batch when one lane takes it,
// and the three calls an iteration there were before (stop 73) made every iteration pay for
// three lights' phase functions and atmosphere (1.3 times the samples a second since).
PtPath path_next_light(PtPath p) {
  // Which lights light the collision (the lab's one light always; it has no second).
  bool up0 = PLANET == 0 || planet_light_up(p, 0);
  bool up1 = PLANET == 1 && planet_light_up(p, 1);
  int i = p.light == 0 && !up0 ? 1 : p.light;
  p.stage = PT_SCATTER;
  if (i > 1 || !(i == 0 ? up0 : up1)) return p;
  p.light = i + 1;
  bool another = i == 0 && up1;
  vec3 to_light;
  vec3 contribution;
  if (PLANET == 1) {
    to_light = planet_light_dir(i);
    vec3 estimate = path_estimate(p) * planet_light_rgb(i);
    if (p.at_ground) {
      contribution = estimate * frame.sky_model.y / PI * max(dot(normalize(p.x), to_light), 0.0f);
    } else {
      Atmosphere atmo = frame_atmosphere();
      AtmosphereMedium air = atmosphere_medium(atmo, length(p.x) - frame.radii_m.x);
      float mu = dot(p.d, to_light);
      vec3 phase = air.scattering_r * rayleigh_phase(mu) +
                   air.scattering_m * cornette_shanks_phase(atmo.mie_g, mu) +
                   p.cloud_sigma * frame.cloud_shape.w * cloud_phase_function(mu, 1.0f);
      contribution = estimate * phase / (air.extinction + p.cloud_sigma);
    }
  } else {
    to_light = frame.path_light.xyz;
    contribution = vec3(p.weight.x * frame.path_light.w *
                        henyey_greenstein(frame.path_medium.z, dot(p.d, to_light)));
  }
  if (another) p.stage = PT_LIGHTS;
  if (pt_max3(contribution) <= 0.0f) return p;
  vec2 bounds = pt_bounds(p.x, to_light);
  if (bounds.y <= bounds.x) {
    p.radiance += contribution;
    return p;
  }
  p.pending = contribution;
  p.track = pt_track_begin(p.x + to_light * bounds.x, to_light, bounds.y - bounds.x,
                           pt_hash(path_bounce_stream(p) ^ (2u + uint(i))), -1);
  p.stage = PT_SHADOW;
  return p;
}

// PT_SCATTER: the path's new direction. On the planet, at a collision in the medium, one of the
// scatterers (Rayleigh, Mie, the clouds) chosen in proportion to the hero's sigma_s, with each
// channel's albedo sigma_s / sigma_t as its weight; Rayleigh sampled uniformly and Mie
// (Cornette-Shanks) as Henyey-Greenstein, each weighted by its phase's ratio to the density
// sampled (at most 1.5); at the ground, Lambert's cosine. Russian roulette then ends paths whose
// largest estimate falls under 1. In the lab, Henyey-Greenstein. After max_bounces, the end.
PtPath path_scatter(PtPath p, int max_bounces) {
  uint s = path_bounce_stream(p);
  if (PLANET == 0) {
    p.d = pt_sample_hg(p.d, frame.path_medium.z, pt_uniform(s, 3u), pt_uniform(s, 4u));
  } else if (p.at_ground) {
    p.weight *= frame.sky_model.y;
    p.d = pt_sample_cosine(normalize(p.x), pt_uniform(s, 3u), pt_uniform(s, 4u));
  } else {
    Atmosphere atmo = frame_atmosphere();
    AtmosphereMedium air = atmosphere_medium(atmo, length(p.x) - frame.radii_m.x);
    vec3 sigma_r = air.scattering_r;
    float sigma_m = air.scattering_m;
    float sigma_c = p.cloud_sigma * frame.cloud_shape.w;
    vec3 sigma_s = sigma_r + sigma_m + sigma_c;
    p.weight *= sigma_s / (air.extinction + p.cloud_sigma);
    float pick = pt_uniform(s, 5u) * sigma_s[p.hero];
    vec3 next;
    vec3 chosen;  // the chosen scatterer's sigma_s per channel
    if (pick < sigma_c) {
      chosen = vec3(sigma_c);
      // The clouds' two lobes, each drawn in proportion to its weight and exactly: the seed's
      // two Henyey-Greenstein lobes; the droplets' Mie fit's Henyey-Greenstein lobe and its
      // Draine lobe (pt_sample_draine_cos: by rejection, weight 1 but in 3e-5 of draws).
      bool mie = frame.cloud_droplets.y > 0.5f;
      float u = pt_uniform(s, 3u);
      vec2 c;
      if (mie) {
        c = pt_uniform(s, 6u) < frame.cloud_mie.w
                ? pt_sample_draine_cos(frame.cloud_mie.y, frame.cloud_mie.z, pt_hash(s ^ 0x2545f491u))
                : vec2(pt_sample_hg_cos(frame.cloud_mie.x, u), 1.0f);
      } else {
        bool first = pt_uniform(s, 6u) < frame.cloud_phase.z;
        c = vec2(pt_sample_hg_cos(first ? frame.cloud_phase.x : frame.cloud_phase.y, u), 1.0f);
      }
      next = pt_direction_at(p.d, c.x, pt_uniform(s, 4u));
      p.weight *= c.y;
    } else if (pick < sigma_c + sigma_m) {
      chosen = vec3(sigma_m);
      next = pt_sample_hg(p.d, atmo.mie_g, pt_uniform(s, 3u), pt_uniform(s, 4u));
      float mu = dot(p.d, next);
      p.weight *= cornette_shanks_phase(atmo.mie_g, mu) / henyey_greenstein(atmo.mie_g, mu);
    } else {
      chosen = sigma_r;
      next = pt_sample_hg(p.d, 0.0f, pt_uniform(s, 3u), pt_uniform(s, 4u));
      p.weight *= rayleigh_phase(dot(p.d, next)) * (4.0f * PI);
    }
    // Each channel's probability of this choice, chosen / sigma_s, joins its events'; its
    // estimate keeps its albedo (f_k / p_k = sigma_s / sigma_t whatever the choice).
    vec3 choice = chosen / max(sigma_s, vec3(1e-30f));
    p.ratio *= choice / choice[p.hero];
    p.d = next;
  }
  if (PLANET == 1) {
    float most = pt_max3(path_estimate(p));
    if (p.bounce >= 2 && most < 1.0f) {  // Russian roulette
      if (pt_uniform(s, 7u) >= most) {
        p.stage = PT_DONE;
        return p;
      }
      p.weight /= most;
    }
  }
  p.bounce += 1;
  p.stage = p.bounce > max_bounces ? PT_DONE : PT_BOUNCE;
  return p;
}

// PT_IDLE: the slot's next sample, through a random point of the pixel (box filter). Slot z of
// S takes samples z, z + S, z + 2 S, ...
PtPath path_start_sample(PtPath p, ivec2 pixel, ivec2 size, uint index) {
  uint stream = pt_stream(uint(pixel.y * size.x + pixel.x), index, uint(dispatch.values.z));
  float jx = pt_uniform(stream, 0u), jy = pt_uniform(stream, 1u);
  p.d = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                   frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x) + jx - 0.5f,
                   float(pixel.y) + jy - 0.5f, float(size.x), float(size.y),
                   vec2(frame.camera_right.w, frame.camera_up.w));
  p.x = PLANET == 1 ? frame.camera_pos_m.xyz : frame.path_eye_m.xyz;
  p.stream = pt_hash(stream ^ 0x68bc21ebu);
  p.hero = PLANET == 1 ? path_hero(index) : 0;
  p.weight = vec3(1.0f);
  p.ratio = vec3(1.0f);
  p.radiance = vec3(0.0f);
  p.bounce = 0;
  p.started += 1;
  p.stage = PT_BOUNCE;
  return p;
}

// Each invocation runs one path at a time of its pixel's slot (gl_GlobalInvocationID.z of
// gl_NumWorkGroups.z, PathTracerModule::resize), for dispatch.values.y iterations or until the
// slot has begun every sample numbered under dispatch.values.x and finished them (0: stopping
// early, until it has finished the sample it is on and taken a multiple of three), adding each
// finished sample to its rows of path_sum and path_squares (sum a: the samples) and to
// path_finished; one that has not is counted in path_running. Iterations: one tentative collision of a flight or of a light's shadow, and the
// events that follow it (a collision's lights without medium between, its scattering, the
// next flight's start), so that lanes of one SIMD batch stay in step whatever their paths do.
void main() {
  int slots = int(gl_NumWorkGroups.z);
  ivec2 size = ivec2(imageSize(path_sum).x, imageSize(path_sum).y / slots);
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  int slot = int(gl_GlobalInvocationID.z);
  ivec2 texel = pixel + ivec2(0, slot * size.y);
  PtPath p = path_state_load(texel);
  vec4 sum = imageLoad(path_sum, texel);
  vec4 squares = imageLoad(path_squares, texel);
  uint target = uint(dispatch.values.x);
  uint finished = 0u;
  bool slot_done = false;
  // The state before this iteration, kept in case lavapipe's loop limit cuts it short.
  PtPath before = p;
  vec4 sum_before = sum, squares_before = squares;
  uint finished_before = finished;
  int it = 0;
  for (; it < dispatch.values.y; ++it) {
    before = p;
    sum_before = sum;
    squares_before = squares;
    finished_before = finished;
    if (p.stage == PT_IDLE) {
      uint index = uint(slot + p.started * slots);
      if (target == 0u ? p.started % 3 == 0 : index >= target) {
        slot_done = true;
        break;
      }
      p = path_start_sample(p, pixel, size, index);
    } else if (p.stage == PT_FLIGHT || p.stage == PT_SHADOW) {
      p.track = pt_track_step(p.track);
      if (!p.track.done) continue;
      if (p.stage == PT_FLIGHT) {
        p = path_flight_ended(p);
      } else {
        p.radiance += p.pending * p.track.value;
        p.stage = PT_LIGHTS;
      }
    }
    if (p.stage == PT_LIGHTS) p = path_next_light(p);
    if (p.stage == PT_SCATTER) p = path_scatter(p, dispatch.values.w);
    if (p.stage == PT_BOUNCE) p = path_begin_bounce(p);
    if (p.stage == PT_DONE) {
      sum += vec4(p.radiance, 1.0f);
      squares += vec4(p.radiance * p.radiance, 0.0f);
      finished += 1u;
      p.stage = PT_IDLE;
    }
  }
  // The loop ended early, neither at its count nor with the slot's samples done: lavapipe's loop
  // limit ended it, and may have cut short what the last iteration did (every loop after the
  // limit runs once), so that iteration is undone. The host then runs shorter passes.
  // (PT_UNDO_CUT_ITERATION 0, path_trace_gpu.comp: a device without the limit never cuts one.)
#if PT_UNDO_CUT_ITERATION
  if (it < dispatch.values.y && !slot_done) {
    p = before;
    sum = sum_before;
    squares = squares_before;
    finished = finished_before;
    atomicAdd(path_limited, 1u);
  }
#endif
  if (!slot_done) atomicAdd(path_running, 1u);
  if (pt_cuts > 0.0f) atomicAdd(path_cut, uint(pt_cuts));
  if (pt_violations > 0.0f) atomicAdd(path_violations, uint(pt_violations));
  if (finished > 0u) atomicAdd(path_finished, finished);
  path_state_store(texel, p);
  imageStore(path_sum, texel, sum);
  imageStore(path_squares, texel, squares);
}

#version 450
// Pass: ground light, over the ground around the camera (GROUND_LIGHT_HALF_M each way).
// r: the clouds' mean diffuse transmittance straight down: the share of the sky's light that
// the gaps and the clouds together pass to the ground there. Compose lights the ground's
// sky-lit part by it and by the cloud towards the sun (cloud_ground_sky_share), so a broken
// field's shadows keep the light of its gaps while a closed deck's ground is grey.
// gba: the sunlight the clouds scatter down onto the ground, as the radiance a white ground
// reflects (the irradiance / pi, per unit of the key light's illuminance): the mean over
// cosine-weighted directions of the clouds' radiance seen from the ground, lit as the fast
// mode lights them (cloud_sun_light). Under a fair-weather cumulus field the path tracer's
// sunlit ground is 14% brighter than under a clear sky (noon, ground albedo 0.1): the clouds'
// sunlit sides and bases are brighter than the blue sky they hide.
// Texel 1, the layer seen from above (the air above it is lit by it, compose.comp): r the mean
// transmittance of cosine-weighted rays down from the layer's top (the ground seen through
// it), gba the clouds' mean light along them. One workgroup: each invocation marches 2 x 2 of
// the GRID^2 columns, two slanted rays up and two down, then they sum in shared memory.
#extension GL_GOOGLE_include_directive : require

layout(constant_id = 0) const int MARCH_MODE = 0;

// The detail noise over the grid's own cell (set in main), whatever the view.
float grid_footprint_m = 0.0f;
#define NOISE_DETAIL_FOOTPRINT_M(pos) grid_footprint_m
#include "cloud_field_inc.glsl"
#include "render/modules/cloud_diffusion/cloud_diffusion_inc.glsl"

const float GROUND_LIGHT_HALF_M = 16000.0f;  // the region's half extent
const int GROUP_SIZE = 16;                   // invocations per side of the workgroup
const int GRID = 2 * GROUP_SIZE;             // columns per side: 2 x 2 per invocation
const int COLUMN_SAMPLES = 16;               // density samples up each column
const int RAYS = GRID * GRID / 2;            // slanted rays
const int RAY_SAMPLES = 16;                  // samples along each slanted ray
const float RAY_MAX_M = 60000.0f;            // the slanted rays' reach through the layer

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

shared vec4 partial[GROUP_SIZE * GROUP_SIZE];
shared vec4 partial_above[GROUP_SIZE * GROUP_SIZE];

// Diffuse transmittance of the clouds straight up from the shell's bottom at horizontal
// position xy (planet frame).
float column_transmittance(vec2 xy) {
  float bottom = frame.radii_m.z, top = frame.radii_m.w;
  float ds = (top - bottom) / float(COLUMN_SAMPLES);
  float depth = 0.0f;
  for (int i = 0; i < COLUMN_SAMPLES; ++i) {
    float r = bottom + (float(i) + 0.5f) * ds;
    depth += cloud_density(point_at_radius(xy, r), true) * ds;
  }
  return light_transmittance(depth);
}

// The sunlight the clouds scatter along a ray from `origin` (planet frame) in direction `dir`,
// back towards the origin, over [t0, t1] (m) of it, per unit of the key light's illuminance (as
// the sky-view table's radiance): RAY_SAMPLES midpoint samples, lit as the fast mode lights
// them; a: the ray's transmittance. The air between is left out. `with_sky`: the sky's light
// through the cloud towards the sun as well (as clouds.comp lights a cloud seen from above).
vec4 cloud_light_span(vec3 origin, vec3 dir, float t0, float t1, bool with_sky) {
  if (t1 <= t0) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  vec3 sun = frame.sun_dir.xyz;
  float sigma_scale = frame.cloud_shape.z * frame.cloud_light.x;
  float light_scale = frame.cloud_shape.z * frame.cloud_light.y;
  float albedo = frame.cloud_shape.w, g1 = frame.cloud_droplets.z;
  float mu = dot(dir, sun);
  bool two_stream = frame.cloud_phase.w > 0.5f;
  bool diffusion = frame.cloud_phase.w > 1.5f;
  vec4 phases = octave_phases(mu);
  float ds = (t1 - t0) / float(RAY_SAMPLES);
  // The ground's light that the clouds reflect back down (as clouds.comp lights their bases):
  // the ground around where the ray enters them, itself under their shadow.
  vec3 entry = origin + dir * t0;
  vec3 below = frame.ambient_below_clouds.rgb * frame.cloud_light.w *
               below_light_share(entry, length(entry) - frame.radii_m.x);
  vec3 above = with_sky ? frame.ambient_at_clouds.rgb * frame.cloud_light.w : vec3(0.0f);
  vec3 sun_light = frame.sun_at_clouds.rgb;
  float transmittance = 1.0f;
  vec3 light = vec3(0.0f);
  for (int i = 0; i < RAY_SAMPLES; ++i) {
    vec3 pos = origin + dir * (t0 + (float(i) + 0.5f) * ds);
    float density = cloud_density(pos, true);
    if (density <= 0.0f) continue;
    bool covered = light_volume_covers(pos);
    float tau_light = depth_towards_sun(pos, sun, covered, frame.steps.y) * light_scale;
    vec3 sunlit = cloud_light(diffusion, pos, dir, sun, tau_light, light_scale, mu, two_stream,
                              phases, frame.cloud_light.z, albedo, g1);
    float step_t = exp(-density * sigma_scale * ds);
    float h = saturate(layer_fraction(pos));
    light += transmittance * albedo *
             (sun_light * (sunlit.x + sunlit.y) + above * sunlit.z + below * (1.0f - h)) *
             (1.0f - step_t);
    transmittance *= step_t;
  }
  return vec4(light / max(frame.sun_illuminance.rgb, vec3(1e-30f)), transmittance);
}

// The clouds' light towards a ground point `base` seen along `dir` (upwards).
vec3 cloud_light_along(vec3 base, vec3 dir) {
  vec2 inner = ray_sphere(base, dir, frame.radii_m.z);
  vec2 outer = ray_sphere(base, dir, frame.radii_m.w);
  float t0 = max(inner.y, 0.0f);
  return cloud_light_span(base, dir, t0, min(outer.y, t0 + RAY_MAX_M), false).rgb;
}

// The layer seen from `top`, a point on its top, along `dir` (downwards): the clouds' light
// (rgb) and the transmittance (a) down to the base, or out through the top again.
vec4 cloud_light_from_above(vec3 top, vec3 dir) {
  vec2 inner = ray_sphere(top, dir, frame.radii_m.z);
  vec2 outer = ray_sphere(top, dir, frame.radii_m.w);
  float t1 = inner.x > 0.0f ? inner.x : outer.y;
  return cloud_light_span(top, dir, 0.0f, min(t1, RAY_MAX_M), true);
}

// The k-th of n directions (n a power of two), cosine-weighted about the local vertical `up`:
// a Hammersley set.
vec3 cosine_direction(int k, int n, vec3 up) {
  float u = (float(k) + 0.5f) / float(n);
  float v = float(bitfieldReverse(uint(k))) * 2.3283064e-10f;
  vec3 east = normalize(vec3(up.z, 0.0f, -up.x));
  vec3 north = cross(up, east);
  float s = sqrt(u), phi = 2.0f * PI * v;
  return normalize(s * cos(phi) * east + s * sin(phi) * north + sqrt(max(1.0f - u, 0.0f)) * up);
}

void main() {
  uint id = gl_LocalInvocationIndex;
  const float cell_m = 2.0f * GROUND_LIGHT_HALF_M / float(GRID);
  grid_footprint_m = cell_m;
  vec4 sum = vec4(0.0f), from_above = vec4(0.0f);
  for (int k = 0; k < 4; ++k) {
    ivec2 cell = 2 * ivec2(gl_LocalInvocationID.xy) + ivec2(k & 1, k >> 1);
    vec2 xy = frame.camera_pos_m.xy + (vec2(cell) + 0.5f) * cell_m - GROUND_LIGHT_HALF_M;
    sum.x += column_transmittance(xy);
    // A slanted ray from two of the four cells (k = 0, 3: a chequerboard), the directions
    // shuffled over them (617 is odd: a permutation of 0 .. RAYS - 1), so that a direction's
    // elevation does not follow the cell's row. 512 rays: 25 ms on lavapipe with a ray from
    // every cell. From the other two (k = 1, 2), a ray down from the layer's top.
    int ray = ((int(id) * 2 + (k >> 1)) * 617) & (RAYS - 1);
    if (k == 1 || k == 2) {
      vec3 top = point_at_radius(xy, frame.radii_m.w);
      vec4 seen = cloud_light_from_above(top, cosine_direction(ray, RAYS, -normalize(top)));
      from_above += vec4(seen.a, seen.rgb);
      continue;
    }
    vec3 ground = point_at_radius(xy, frame.radii_m.x);
    sum.yzw += cloud_light_along(ground, cosine_direction(ray, RAYS, normalize(ground)));
  }
  partial[id] = sum;
  partial_above[id] = from_above;
  barrier();
  for (uint n = uint(GROUP_SIZE * GROUP_SIZE) / 2u; n > 0u; n >>= 1) {
    if (id < n) {
      partial[id] += partial[id + n];
      partial_above[id] += partial_above[id + n];
    }
    barrier();
  }
  if (id == 0u) {
    imageStore(ground_light_out, ivec2(0),
               partial[0] / vec4(float(GRID * GRID), vec3(float(RAYS))));
    imageStore(ground_light_out, ivec2(1, 0), partial_above[0] / float(RAYS));
  }
}

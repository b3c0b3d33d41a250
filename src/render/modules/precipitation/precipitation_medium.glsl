// Rain and snow as a medium of compose.comp (media_inc.glsl, generated from the modules'
// folders): what the precipitation between the eye and a layer at `distance_m` along `dir`
// does to the layer's light. Its extinction, profile and shafts are
// common/precipitation_inc.glsl's; its light slab_medium_light's, the column above a point
// taken as the shaft's own over it. The shafts vary across the ray, so it is marched: a few
// steps, closer together near the eye.
#ifndef NEPHELE_PRECIPITATION_MEDIUM
#define NEPHELE_PRECIPITATION_MEDIUM

#include "common/clouds_inc.glsl"
#include "common/math_inc.glsl"
#include "common/precipitation_inc.glsl"
#include "common/slab_light_inc.glsl"
#include "render/modules/precipitation/precipitation_gpu_inc.glsl"

layout(std140, set = 1, binding = 1) uniform PrecipitationBlock { PrecipitationGpu precipitation; };

const int PRECIPITATION_STEPS = 24;
// A storm's shafts stand out from 100 km away and more; beyond, the haze has taken them.
const float PRECIPITATION_MAX_RANGE_M = 150000.0f;

// Where it falls at `pos` (planet frame, m): x its share, 0 to 1, y how far it falls from a
// storm's core (precipitation_shaft_share): the shafts under the low layer's precipitating
// clouds, read from its weather map where the layer's base lies over pos, moved by the wind as
// the clouds' bases are (clouds.comp); (1, 0) for an even curtain.
vec2 precipitation_share_at(vec3 pos) {
  if (precipitation.sky.w == 0.0f) return vec2(1.0f, 0.0f);
  CloudLayerGpu layer = frame.cloud_layers[0];
  vec2 ground_xy = vec2(pos) - vec2(layer.wind);
  vec4 weather = textureLod(weather_map, ground_xy * frame.cloud_noise.z + vec2(layer.radii_m.z, layer.radii_m.w) + 0.5f, 0.0f);
  return precipitation_shaft_share(weather.r, weather.g, layer.shape.x, layer.shape.w);
}

// The optical depth from `altitude_m` up to the cloud base through a shaft of share `share`.
float precipitation_tau_above(float share, float altitude_m) {
  float bottom_m = precipitation.fall.x, top_m = precipitation.fall.y;
  return precipitation.fall.z * share *
         (precipitation_column_m(top_m, bottom_m, top_m) - precipitation_column_m(altitude_m, bottom_m, top_m));
}

// The medium at `pos` (planet frame, m): rgb the light it scatters towards the eye per unit
// of sigma_s (`phase` the phase function's value towards it), a its sigma_t (1/m).
vec4 precipitation_at(vec3 pos, float phase) {
  float bottom_m = precipitation.fall.x, top_m = precipitation.fall.y;
  // The samples lie on the ray's stretch under the base; the ends on the base's sphere may
  // come out a little above it in float (half a metre at the planet's radius).
  float altitude_m = min(length(pos) - frame.radii_m.x, top_m);
  vec2 shaft = precipitation_share_at(pos);
  float sigma = precipitation.fall.z * shaft.x * precipitation_profile(altitude_m, bottom_m, top_m);
  float tau_up = precipitation_tau_above(shaft.x, altitude_m);
  float tau_below = precipitation.fall.z * shaft.x * precipitation_column_m(altitude_m, bottom_m, top_m);
  float mu_sun = precipitation.sun.w;
  vec3 scattered = slab_medium_light(precipitation.sun.rgb, mu_sun, precipitation.sky.rgb, phase,
                                     precipitation.fall.w, tau_up / max(mu_sun, 0.05f), tau_below, tau_up);
  return vec4(precipitation_core_light(shaft.y) * scattered, sigma);
}

vec4 precipitation_medium(vec3 eye, vec3 dir, float distance_m, float cloud_light, out float depth_m) {
  depth_m = 0.0f;
  if (precipitation.fall.z <= 0.0f) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  // The stretch of the ray under the base's sphere, up to the layer behind.
  vec2 base = ray_sphere(eye, dir, frame.radii_m.x + precipitation.fall.y);
  float t0 = max(base.x, 0.0f);
  float t1 = min(base.y, PRECIPITATION_MAX_RANGE_M);
  if (distance_m > 0.0f) t1 = min(t1, distance_m);
  if (base.y <= 0.0f || t1 <= t0) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  // It falls from the clouds, under them: the sun's beam reaches it through them as diffuse
  // light, scattered evenly (1 / 4 pi), not by the particles' forward peak.
  float phase = 1.0f / (4.0f * PI);
  // The samples lie on fixed horizontal distances from the eye, r_k = range (k / n)^2, so that
  // every pixel of a column of the image samples the same vertical shafts at the same places
  // and they stand as columns (fractions of each ray's own stretch gave each row its own
  // places: a moire across the shafts). Along a ray the medium is taken linear between them
  // (the trapezoid rule), so that a shaft's edge moves smoothly from one pixel to the next.
  // Those outside the ray's stretch fall on its ends: a short ray up through the shafts is
  // taken in one step.
  vec3 up = normalize(eye);
  float horizontal = max(length(dir - dot(dir, up) * up), 1e-4f);
  vec3 light = vec3(0.0f);
  float transmittance = 1.0f;
  float t_prev = t0;
  vec4 prev = precipitation_at(eye + dir * t0, phase);
  for (int i = 1; i <= PRECIPITATION_STEPS; ++i) {
    float u = float(i) / float(PRECIPITATION_STEPS);
    float t_next = i == PRECIPITATION_STEPS
                       ? t1
                       : clamp(PRECIPITATION_MAX_RANGE_M * u * u / horizontal, t0, t1);
    vec4 next = precipitation_at(eye + dir * t_next, phase);
    float d_tau = 0.5f * (prev.a + next.a) * (t_next - t_prev);
    float step_transmittance = exp(-d_tau);
    vec3 scattered = (prev.a + next.a) > 0.0f
                         ? (prev.rgb * prev.a + next.rgb * next.a) / (prev.a + next.a)
                         : vec3(0.0f);
    float weight = transmittance * (1.0f - step_transmittance);
    light += weight * scattered;
    depth_m += weight * 0.5f * (t_prev + t_next);
    transmittance *= step_transmittance;
    t_prev = t_next;
    prev = next;
  }
  depth_m = transmittance < 1.0f ? depth_m / (1.0f - transmittance) : 0.0f;
  return vec4(cloud_light * light, transmittance);
}

// The share of the sun's (x) and the sky's (y) light that reaches a surface at `pos` through
// the precipitation above it: both as diffuse light through the shaft's column (the particles
// scatter forward).
vec2 precipitation_surface_light(vec3 pos) {
  if (precipitation.fall.z <= 0.0f) return vec2(1.0f);
  float altitude_m = length(pos) - frame.radii_m.x;
  float tau_up = precipitation_tau_above(precipitation_share_at(pos).x, altitude_m);
  float g = precipitation.fall.w;
  float mu_sun = max(precipitation.sun.w, 0.05f);
  return vec2(cloud_diffuse_transmittance(tau_up / mu_sun, g), cloud_diffuse_transmittance(tau_up, g));
}

#endif

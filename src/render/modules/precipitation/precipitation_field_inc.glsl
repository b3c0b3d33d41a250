// The precipitation as a field along the view's rays, shared by its pass (precipitation.comp,
// which marches it into the froxels) and its medium (precipitation_medium.glsl, which reads
// them; the surface light, which reads the field): its block, where it falls, its density and
// light at a point, and the places of the march's samples. Its extinction, profile and shafts
// are common/precipitation_inc.glsl's; its light slab_medium_light's, the column above a point
// taken as the shaft's own over it.
#ifndef NEPHELE_PRECIPITATION_FIELD_INC
#define NEPHELE_PRECIPITATION_FIELD_INC

#include "common/math_inc.glsl"
#include "common/clouds_inc.glsl"
#include "common/precipitation_inc.glsl"
#include "common/slab_light_inc.glsl"
#include "forecast_inc.glsl"
#include "weather_map_inc.glsl"
#include "render/modules/precipitation/precipitation_gpu_inc.glsl"

layout(std140, set = 1, binding = 1) uniform PrecipitationBlock { PrecipitationGpu precipitation; };

// Where it falls at `pos` (planet frame, m): x its share, 0 to 1, y how far it falls from a
// storm's core (precipitation_shaft_share): the shafts under the low layer's precipitating
// clouds, read from its weather map where the layer's base was over the particles at pos when
// they left it (upwind, by the drift over their fall), moved by the wind as the clouds' bases
// are (clouds.comp); (1, 0) for an even curtain.
vec2 precipitation_share_at(vec3 pos) {
  if (precipitation.sky.w == 0.0f) return vec2(1.0f, 0.0f);
  CloudLayerGpu layer = frame.cloud_layers[0];
  float fallen_m = max(precipitation.fall.y - (length(pos) - frame.radii_m.x), 0.0f);
  vec2 left_xy = vec2(pos) - vec2(precipitation.drift) * fallen_m;
  vec2 ground_xy = left_xy - vec2(layer.wind);
  vec4 weather = weather_map_at(layer, ground_xy);
  return precipitation_shaft_share(weather.r, weather.g, layer.shape.x * forecast_share(left_xy).x,
                                   layer.shape.w);
}

// The optical depth from `altitude_m` up to the cloud base through a shaft of share `share`.
float precipitation_tau_above(float share, float altitude_m) {
  float bottom_m = precipitation.fall.x, top_m = precipitation.fall.y;
  return precipitation.fall.z * share *
         (precipitation_column_m(top_m, bottom_m, top_m) - precipitation_column_m(altitude_m, bottom_m, top_m));
}

// The medium at `pos` (planet frame, m): rgb the light it scatters towards the eye per unit
// of sigma_s and of the key light's illuminance, before the clouds' shade (the medium's
// caller multiplies by it); a its sigma_t (1/m). It falls from the clouds, under them: the
// sun's beam reaches it through them as diffuse light, scattered evenly (1 / 4 pi), not by
// the particles' forward peak.
vec4 precipitation_at(vec3 pos) {
  float bottom_m = precipitation.fall.x, top_m = precipitation.fall.y;
  // The samples lie on the ray's stretch under the base; the ends on the base's sphere may
  // come out a little above it in float (half a metre at the planet's radius). Under the
  // ground it is taken as at the ground: a froxel's ray that meets the ground before a pixel's
  // beside it does goes on through the same rain, so that the pixel reads its own distance's.
  float altitude_m = clamp(length(pos) - frame.radii_m.x, 0.0f, top_m);
  vec2 shaft = precipitation_share_at(pos);
  float sigma = precipitation.fall.z * shaft.x * precipitation_profile(altitude_m, bottom_m, top_m);
  float tau_up = precipitation_tau_above(shaft.x, altitude_m);
  float tau_below = precipitation.fall.z * shaft.x * precipitation_column_m(altitude_m, bottom_m, top_m);
  float mu_sun = precipitation.sun.w;
  vec3 scattered = slab_medium_light(precipitation.sun.rgb, mu_sun, precipitation.sky.rgb, 1.0f / (4.0f * PI),
                                     precipitation.fall.w, tau_up / max(mu_sun, 0.05f), tau_below, tau_up);
  return vec4(precipitation_core_light(shaft.y) * scattered, sigma);
}

// The stretch of a ray under the base's sphere, [x, y] (m; empty where y <= x), within the
// march's range.
vec2 precipitation_stretch(vec3 eye, vec3 dir) {
  vec2 base = ray_sphere(eye, dir, frame.radii_m.x + precipitation.fall.y);
  if (base.y <= 0.0f) return vec2(0.0f);
  return vec2(max(base.x, 0.0f), min(base.y, PRECIPITATION_MAX_RANGE_M));
}

// The share of a ray's length that is horizontal (at the eye; at least 1e-4).
float precipitation_horizontal(vec3 eye, vec3 dir) {
  vec3 up = normalize(eye);
  return max(length(dir - dot(dir, up) * up), 1e-4f);
}

#endif

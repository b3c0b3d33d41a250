// The ground fog as a medium of compose.comp (media_inc.glsl, generated from the modules'
// folders): what the fog between the eye and a layer at `distance_m` along `dir` does to the
// layer's light. The layer and the fog are those of GroundFogModule (ground_fog.h); the fog's
// shape and optical depth are common/ground_fog_inc.glsl's closed forms.
#ifndef NEPHELE_GROUND_FOG_MEDIUM
#define NEPHELE_GROUND_FOG_MEDIUM

#include "common/clouds_inc.glsl"
#include "common/ground_fog_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/slab_light_inc.glsl"
#include "render/modules/ground_fog/ground_fog_gpu_inc.glsl"

layout(std140, set = 1, binding = 0) uniform GroundFogBlock { GroundFogGpu ground_fog; };

// The layer of the block (GroundFogModule::prepare).
GroundFog ground_fog_from_block() {
  GroundFog f;
  f.base_m = ground_fog.layer.x;
  f.top_m = ground_fog.layer.y;
  f.soft_m = ground_fog.layer.z;
  f.sigma_t_per_m = ground_fog.layer.w;
  f.albedo = 1.0f;
  return f;
}

// The light scattered towards the eye per unit of sigma_s inside the fog at altitude z, per
// unit of the key light's illuminance (slab_medium_light; the fog's droplets scatter the sun
// forward), dimmed by the clouds' mean diffuse transmittance over the ground around
// (`cloud_light`).
vec3 ground_fog_light(GroundFog f, float altitude_m, float mu, float cloud_light) {
  float tau_sun = ground_fog_sun_optical_depth(f, altitude_m, ground_fog.sun.w, frame.radii_m.x);
  float tau_below = f.sigma_t_per_m * ground_fog_cumulative_m(f, altitude_m);
  float tau_up = f.sigma_t_per_m * ground_fog_column_above_m(f, altitude_m);
  float phase = cornette_shanks_phase(ground_fog.sky.w, mu);
  return cloud_light * slab_medium_light(ground_fog.sun.rgb, ground_fog.sun.w, ground_fog.sky.rgb,
                                         phase, CLOUD_DROPLET_G, tau_sun, tau_below, tau_up);
}

// The fog layer in front of a layer at `distance_m` (0: nothing there, the sky: the ray to
// where it leaves the fog's top): rgb the light it adds per unit of the key light's
// illuminance, a its transmittance. `cloud_light`: the clouds' mean diffuse transmittance to
// the ground.
vec4 ground_fog_layer_medium(vec3 eye, vec3 dir, float distance_m, float cloud_light,
                             out float depth_m) {
  depth_m = 0.0f;
  if (ground_fog.layer.w <= 0.0f) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  float radius_m = frame.radii_m.x;
  GroundFog f = ground_fog_from_block();
  float length_m = distance_m;
  if (length_m <= 0.0f) {  // the sky: up to where the ray leaves the top's sphere
    vec2 top = ray_sphere(eye, dir, radius_m + f.top_m);
    length_m = max(top.y, 0.0f);
  }
  if (length_m <= 0.0f) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  float z0 = length(eye) - radius_m;
  float z1 = length(eye + dir * length_m) - radius_m;
  float tau = ground_fog_optical_depth(f, z0, z1, length_m);
  float transmittance = exp(-tau);
  // Lit as where the light it scatters to the eye comes from: the centroid of sigma_s T along
  // the segment's part in the layer (its density taken even; altitude linear along it), at half
  // its length when it is thin and 1 / sigma_t from the eye when it is thick, so that a layer
  // behind an opaque fog, or above it, sees the same fog as the sky does.
  float share = tau < 1e-3f ? 0.5f
                               : (1.0f - (1.0f + tau) * transmittance) /
                                     (tau * max(1.0f - transmittance, 1e-30f));
  float z_lit = mix(clamp(z0, f.base_m, f.top_m), clamp(z1, f.base_m, f.top_m), share);
  vec3 light = ground_fog_light(f, z_lit, dot(dir, frame.sun_dir.xyz), cloud_light);
  depth_m = share * length_m;
  return vec4(f.albedo * (1.0f - transmittance) * light, transmittance);
}

// The time-of-day keyframes' fog (seed 003) in front of a layer at `distance_m`: its colour
// mixed in linearly, none up to the near distance, whole from the far one on; the sky
// (`distance_m` 0) is fogged by the keyframes' sky fog instead, by elevation (compose.comp).
vec4 ground_fog_keyframes_medium(float distance_m) {
  if (ground_fog.keyframes.w == 0.0f || distance_m <= 0.0f) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  float near_m = ground_fog.keyframes_range_m.x;
  float far_m = ground_fog.keyframes_range_m.y;
  float mixed = saturate((distance_m - near_m) / max(far_m - near_m, 1e-3f));
  return vec4(ground_fog.keyframes.rgb * mixed, 1.0f - mixed);
}

// The share of the sun's (x) and the sky's (y) light that reaches a surface at `pos` (planet
// frame) through the fog above it: the sun's beam scattered on (the fog's droplets scatter
// forward: a two-stream slab lets through what it does not reflect), the sky's light as a
// diffuse light through the column above. 1 above the fog and without it.
vec2 ground_fog_surface_light(vec3 pos) {
  if (ground_fog.layer.w <= 0.0f) return vec2(1.0f);
  GroundFog f = ground_fog_from_block();
  float radius_m = frame.radii_m.x;
  float z = length(pos) - radius_m;
  float tau_sun = ground_fog_sun_optical_depth(f, z, ground_fog.sun.w, radius_m);
  float tau_up = f.sigma_t_per_m * ground_fog_column_above_m(f, z);
  return vec2(cloud_diffuse_transmittance(tau_sun), cloud_diffuse_transmittance(tau_up));
}

// The ground fog in front of a layer at `distance_m` (0: the sky): the fog layer in front of
// the keyframes' fog, each as above; depth_m the fog layer's (the keyframes' fog stands for the
// air, in front of it).
vec4 ground_fog_medium(vec3 eye, vec3 dir, float distance_m, float cloud_light, out float depth_m) {
  vec4 front = ground_fog_layer_medium(eye, dir, distance_m, cloud_light, depth_m);
  vec4 behind = ground_fog_keyframes_medium(distance_m);
  return vec4(front.rgb + front.a * behind.rgb, front.a * behind.a);
}

#endif

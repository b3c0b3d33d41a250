// Volumetric light shafts (quality.light_shafts = "volumetric", the default): the share of the
// air's light towards the eye that the clouds' shadows take from the sun. The sky-view table
// and the aerial perspective hold the air's light as if no cloud stood between it and the sun;
// dimming it by that share leaves beams of lit air between shadowed air below broken clouds
// (crepuscular rays), a darker air under a closed deck, and nothing changed under a clear sky:
// no light is ever added to the sky model's, and none taken beyond it. GLSL only; the includer
// defines MARCH_MODE (cloud_field_inc.glsl) and includes frame_atmosphere_inc.glsl.
#ifndef NEPHELE_LIGHT_SHAFTS_INC
#define NEPHELE_LIGHT_SHAFTS_INC

#extension GL_GOOGLE_include_directive : require
#include "cloud_field_inc.glsl"

const int SHAFT_STEPS = 32;
const float SHAFT_FAR_M = 300000.0f;  // the longest stretch of air marched

// The clouds' transmittance towards the sun from p (cloud_field_inc.glsl's light transmittance,
// as the ground's shadow has it): from the light volume, where the sun's ray from p leaves the
// cloud shell's bottom, or p itself within the shell; 1 above the shell. Beyond the volume,
// the clouds' mean transmittance about the camera (ground_light.comp): the weather there taken
// to be like the weather here, so a deck does not end in a band of lit air at the horizon.
float shaft_visibility(vec3 p, vec3 sun) {
  float r = length(p);
  if (r >= frame.radii_m.w) return 1.0f;
  vec3 base = p;
  if (r < frame.radii_m.z) {
    vec2 inner = ray_sphere(p, sun, frame.radii_m.z);
    if (inner.y <= 0.0f) return 1.0f;
    base = p + sun * inner.y;
  }
  if (!light_volume_covers(base)) return texelFetch(ground_light, ivec2(0), 0).r;
  return light_transmittance(light_volume_lookup(base));
}

// The air's single scattering of the key light along the view ray, per unit illuminance, the
// part of it the clouds shadow and the air's multiple scattering (Hillaire's Psi_ms, which the
// shadows leave: the whole sky lights it), in front of the clouds (t < cloud_m) and behind
// them, to the ground or the atmosphere's top (at most SHAFT_FAR_M and end_limit_m: the
// terrain): SHAFT_STEPS steps spaced as the sky's (t ~ (i / n)^2), offset by `jitter` in
// [0, 1).
struct ShaftLight {
  vec3 single_front, lost_front, single_behind, lost_behind;
  vec3 multiple_front, multiple_behind;  // the air's multiple scattering (Psi_ms, isotropic)
};

ShaftLight light_shaft_light(vec3 eye, vec3 dir, float cloud_m, float end_limit_m, float jitter) {
  ShaftLight s;
  s.single_front = s.lost_front = s.single_behind = s.lost_behind = vec3(0.0f);
  s.multiple_front = s.multiple_behind = vec3(0.0f);
  Atmosphere a = frame_atmosphere();
  vec3 sun = frame.sun_dir.xyz;
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  vec2 top = ray_sphere(eye, dir, a.top_radius_m);
  float end_m = min(min(ground.x > 0.0f ? ground.x : max(top.y, 0.0f), SHAFT_FAR_M), end_limit_m);
  if (end_m <= 0.0f || frame.light_volume.w < 0.5f) return s;
  float mu = dot(dir, sun);
  float phase_r = rayleigh_phase(mu), phase_m = cornette_shanks_phase(a.mie_g, mu);
  vec3 optical_depth = vec3(0.0f);
  float previous_t = 0.0f;
  for (int i = 0; i < SHAFT_STEPS; ++i) {
    float u = (float(i) + jitter) / float(SHAFT_STEPS);
    float t = end_m * u * u;
    vec3 p = eye + dir * t;
    AtmosphereMedium m = atmosphere_medium(a, length(p) - a.planet_radius_m);
    optical_depth += m.extinction * (t - previous_t);
    previous_t = t;
    vec3 t_sun = transmittance_to_light(a, transmittance_lut, false, p, sun);
    vec3 seen = exp(-optical_depth) * (end_m * 2.0f * u / float(SHAFT_STEPS));  // dt/du du
    vec3 single =
        seen * (m.scattering_r * phase_r + vec3(m.scattering_m * phase_m)) * t_sun;
    vec3 lost = single * (1.0f - shaft_visibility(p, sun));
    vec3 psi = multiple_scattering_at(a, transmittance_lut, ms_lut, false, p, sun, frame.sky_model.y);
    vec3 multiple = seen * (m.scattering_r + vec3(m.scattering_m)) * psi;
    if (t < cloud_m) {
      s.single_front += single;
      s.lost_front += lost;
      s.multiple_front += multiple;
    } else {
      s.single_behind += single;
      s.lost_behind += lost;
      s.multiple_behind += multiple;
    }
  }
  return s;
}

#endif

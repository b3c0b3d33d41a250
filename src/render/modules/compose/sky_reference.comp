#version 450
// Reference sky, pass 2 of 2: per pixel of the tile, the view ray integrated as sky_hillaire
// does (common/atmosphere_lut_inc.glsl) but with no table: the sun's transmittance integrated
// in place at every step and Psi_ms from pass 1. compose.comp reads the result.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "dispatch_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "frame_atmosphere_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (id.x >= REFERENCE_TILE || id.y >= REFERENCE_TILE) return;
  ivec2 pixel = dispatch.values.xy + id;
  if (pixel.x >= frame.size.x || pixel.y >= frame.size.y) return;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x),
                        float(pixel.y), float(frame.size.x), float(frame.size.y),
                        vec2(frame.camera_right.w, frame.camera_up.w));
  Atmosphere a = frame_atmosphere();
  vec3 sun = frame.sun_dir.xyz;
  float albedo = frame.sky_model.y;
  SkyRay ray = sky_ray(a, frame.camera_pos_m.xyz, dir);
  SkySample result = sky_sample_start();
  float mu = dot(dir, sun);
  float phase_r = rayleigh_phase(mu);
  float phase_m = cornette_shanks_phase(a.mie_g, mu);
  int n = ray.length_m < 0.0f ? 0 : REFERENCE_SAMPLES;
  for (int i = 0; i < n; ++i) {
    vec2 t = sky_step(ray.length_m, i, REFERENCE_SAMPLES);
    vec3 x = ray.origin + dir * (0.5f * (t.x + t.y));
    AtmosphereMedium m = atmosphere_medium(a, length(x) - a.planet_radius_m);
    vec3 t_sun = transmittance_to_light(a, transmittance_lut, true, x, sun);
    vec3 psi = texelFetch(reference_psi, ivec3(id, i), 0).rgb;
    result = sky_accumulate(result, m.extinction, t.y - t.x,
                            sky_source(m, phase_r, phase_m, t_sun, ms_isotropic(psi)));
  }
  if (ray.hits_ground && n > 0)
    result = sky_add_ground(a, transmittance_lut, true, result, ray.origin + dir * ray.length_m,
                            sun, albedo, frame_ground_sky());
  imageStore(reference_sky_out, pixel, vec4(result.radiance, 1.0f));
  imageStore(reference_sky_out, ivec2(pixel.x, pixel.y + frame.size.y), vec4(result.ground_sun, result.ground_air_t));
}

#version 450
// Pass 2d: the aerial-perspective volume (Hillaire 2020, section 5.4; layout in
// common/sky_view_inc.glsl), rebuilt with the sky-view LUT. One invocation per direction
// marches its slices front to back: in-scattered radiance of the key and the second light
// (single scattering through the transmittance LUT plus multiple scattering as the sky-view LUT
// has it) and the green transmittance
// from the camera to each slice's end. Past the ground nothing is added. compose.comp colours
// the haze in front of clouds with it.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "common/sky_view_inc.glsl"
#include "frame_atmosphere_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

const int STEPS_PER_SLICE = 2;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.x, frame.sky_view_rows.z + int(gl_GlobalInvocationID.y));
  if (texel.x >= AP_SIZE_U || texel.y >= AP_SIZE_V ||
      int(gl_GlobalInvocationID.y) >= frame.sky_view_rows.w)
    return;
  Atmosphere a = frame_atmosphere();
  vec3 eye = frame.camera_pos_m.xyz;
  vec3 sun = frame.sun_dir.xyz;
  SkyViewFrame sky_frame = sky_view_frame_from(frame.sky_view_build_up, frame.sky_view_build_forward);
  vec2 uv = (vec2(texel) + 0.5f) / vec2(AP_SIZE_U, AP_SIZE_V);
  vec3 dir = sky_view_texel_dir(sky_frame, uv, eye, a.planet_radius_m);
  vec2 ground = ray_sphere(eye, dir, a.planet_radius_m);
  float t_ground = ground.x > 0.0f ? ground.x : 1e30f;
  vec2 top = ray_sphere(eye, dir, a.top_radius_m);
  float t_in = max(top.x, 0.0f);
  float t_out = top.y > 0.0f ? min(top.y, t_ground) : 0.0f;
  // The key light and, when there is one, the second (both in units of the key's illuminance).
  vec4 second = frame.second_light;
  int lights = second.w > 0.0f ? 2 : 1;
  vec3 light_dir[2] = vec3[2](sun, second.xyz);
  float light_share[2] = float[2](1.0f, second.w);
  float phase_r[2], phase_m[2];
  for (int l = 0; l < lights; ++l) {
    float mu = dot(dir, light_dir[l]);
    phase_r[l] = rayleigh_phase(mu);
    phase_m[l] = cornette_shanks_phase(a.mie_g, mu);
  }
  float albedo = frame.sky_model.y;

  SkySample air = sky_sample_start();
  float t_prev = 0.0f;
  for (int k = 0; k < AP_SLICES; ++k) {
    float t_end = aerial_perspective_slice_end_m(k);
    // The part of [t_prev, t_end] that lies in the air.
    float t0 = clamp(t_prev, t_in, t_out);
    float t1 = clamp(t_end, t_in, t_out);
    float dt = (t1 - t0) / float(STEPS_PER_SLICE);
    for (int i = 0; i < STEPS_PER_SLICE; ++i) {
      vec3 x = eye + dir * (t0 + (float(i) + 0.5f) * dt);
      AtmosphereMedium m = atmosphere_medium(a, length(x) - a.planet_radius_m);
      vec3 source = vec3(0.0f);
      for (int l = 0; l < lights; ++l) {
        vec3 t_sun = transmittance_to_light(a, transmittance_lut, false, x, light_dir[l]);
        MsScattering ms = multiple_scattering_towards(a, transmittance_lut, ms_lut, ms_field,
                                                      frame.sky_options.x, false, x, light_dir[l],
                                                      dir, albedo);
        source += light_share[l] * sky_source(m, phase_r[l], phase_m[l], t_sun, ms);
      }
      air = sky_accumulate(air, m.extinction, dt, source);
    }
    imageStore(aerial_perspective_out, ivec3(texel, k), vec4(air.radiance, air.transmittance.g));
    t_prev = t_end;
  }
}

#version 450
// Pass 2c: the sky-view LUT (Hillaire 2020, section 5.3), recomputed only when the sun, the
// camera's position or the atmosphere change. The sky (common/atmosphere_lut_inc.glsl: single
// and multiple scattering through the transmittance LUT and the multiple-scattering light field
// or Psi_ms, FrameParams::sky_options.x) is integrated
// once per texel of a small latitude/longitude table around the camera
// (common/sky_view_inc.glsl) instead of once per pixel; compose.comp samples it bilinearly.
// Both of the sky's lights (FrameParams sun_dir and second_light) are summed. With
// atmosphere.model = preetham the sky above the horizon is Preetham's (seed 002) instead.
// The image stacks two tables: the in-scattered radiance (with the ground's sky-lit part) and
// the ground's sun-lit radiance, which compose multiplies by the clouds' shadow; its alpha is
// the air's transmittance to the ground, with which compose shadows the sky-lit part.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "common/preetham_inc.glsl"
#include "common/sky_view_inc.glsl"
#include "frame_atmosphere_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 size = imageSize(sky_view_out);
  int rows = size.y / 2;
  ivec2 texel = ivec2(gl_GlobalInvocationID.x, frame.sky_view_rows.x + int(gl_GlobalInvocationID.y));
  if (texel.x >= size.x || texel.y >= rows || int(gl_GlobalInvocationID.y) >= frame.sky_view_rows.y)
    return;

  vec3 eye = frame.camera_pos_m.xyz;
  vec3 sun = frame.sun_dir.xyz;
  SkyViewFrame sky_frame = sky_view_frame_from(frame.sky_view_build_up, frame.sky_view_build_forward);
  vec2 uv = vec2((float(texel.x) + 0.5f) / float(size.x), sky_view_row_v(texel.y, rows));
  vec3 dir = sky_view_texel_dir(sky_frame, uv, eye, frame.radii_m.x);
  Atmosphere a = frame_atmosphere();
  int ms_mode = frame.sky_options.x;
  SkySample sky = sky_hillaire(a, transmittance_lut, ms_lut, ms_field, ms_mode, false, eye, dir,
                               sun, frame.steps.z, frame.sky_model.y, frame_ground_sky());
  // The second light (the twilight sun under the moon, or the moon in twilight): its sky, and
  // its light on the ground, which the key light's cloud shadow does not darken. The ground's
  // sky light (frame_ground_sky) already holds both lights' and is added once.
  vec4 second = frame.second_light;
  if (second.w > 0.0f) {
    SkySample s2 = sky_hillaire(a, transmittance_lut, ms_lut, ms_field, ms_mode, false, eye, dir,
                                second.xyz, frame.steps.z, frame.sky_model.y, vec3(0.0f));
    sky.radiance += second.w * (s2.radiance + s2.ground_sun);
  }
  if (int(frame.sky_model.z) == SKY_MODEL_PREETHAM && uv.y >= 0.5f) {
    // Preetham's analytic sky above the horizon (the ground stays the physical model's). The
    // model knows no sun below the horizon: it is faded by a factor 10 every 3 degrees the sun
    // sinks, about how fast the twilight sky darkens. It has no second light.
    float sun_elevation_deg = degrees(asin(clamp(dot(sun, sky_frame.up), -1.0f, 1.0f)));
    float fade = pow(10.0f, min(sun_elevation_deg, 0.0f) / 3.0f);
    sky.radiance = preetham_sky_radiance(frame.sky_model.w, dir, sun, sky_frame.up) * fade;
  }
  imageStore(sky_view_out, texel, vec4(sky.radiance, 1.0f));
  imageStore(sky_view_out, ivec2(texel.x, texel.y + rows), vec4(sky.ground_sun, sky.ground_air_t));
}

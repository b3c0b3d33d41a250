#version 450
// Pass: the classical cloud models of seed 004 (issue 23, render/modules/classic_clouds.h),
// drawn in place of nephele's march into this frame's cloud buffer (clouds_a_out,
// clouds_b_out: what resolve.comp writes), so that compose.comp puts them in the sky as it
// does nephele's clouds. MODEL (specialization constant) selects the model:
//   CLASSIC_BLINN: Blinn 1982, the [clouds] layer as a uniform slab of small particles, lit by
//     the key light with low-albedo single scattering (common/classic_inc.glsl): the light
//     scattered once towards the eye and the transparency of the slab along the view.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/classic_inc.glsl"
#include "air_inc.glsl"

layout(constant_id = 0) const int MODEL = CLASSIC_BLINN;
layout(local_size_x = 8, local_size_y = 8) in;

void write_cloud(ivec2 pixel, vec3 radiance, float transmittance, float haze, float shadow,
                 float distance_m) {
  imageStore(clouds_a_out, pixel, vec4(radiance, transmittance));
  imageStore(clouds_b_out, pixel, vec4(haze, shadow, distance_m * 1e-3f, 1.0f));
}

// The slab between the spheres of radii frame.radii_m.z and .w crossed by the ray from `eye`
// along `dir`: (t_enter, t_exit), empty when exit <= enter; the ground stops it.
vec2 slab_segment(vec3 eye, vec3 dir) {
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  vec2 inner = ray_sphere(eye, dir, frame.radii_m.z);
  vec2 outer = ray_sphere(eye, dir, frame.radii_m.w);
  float r = length(eye);
  float t0, t1;
  if (r < frame.radii_m.z) {
    if (ground.x > 0.0f) return vec2(0.0f);
    t0 = inner.y;
    t1 = outer.y;
  } else if (r <= frame.radii_m.w) {
    t0 = 0.0f;
    t1 = inner.x > 0.0f ? inner.x : outer.y;
  } else {
    t0 = max(outer.x, 0.0f);
    t1 = inner.x > 0.0f ? inner.x : outer.y;
  }
  return outer.y <= 0.0f ? vec2(0.0f) : vec2(t0, t1);
}

// Blinn's slab. tau is its optical depth along the vertical: along the ray the slab's path
// (t1 - t0) is tau / mu with mu = thickness / path, which holds on the sphere too; mu0 is the
// light's cosine to the vertical where the ray crosses the slab's middle.
void blinn(ivec2 pixel, vec3 eye, vec3 dir, vec3 light) {
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  vec2 seg = slab_segment(eye, dir);
  float thickness_m = frame.radii_m.w - frame.radii_m.z;
  float tau = frame.classic_blinn.x;
  bool seed_form = frame.classic_options.x > 0.5f;
  // The ground's shadow: the light through the slab above the ground point.
  float shadow = 1.0f;
  if (ground.x > 0.0f) {
    vec3 up = normalize(eye + dir * ground.x);
    float mu0 = dot(up, light);
    shadow = mu0 > 0.0f ? exp(-tau / max(mu0, 1e-3f)) : 1.0f;
  }
  if (seg.y <= seg.x || tau <= 0.0f) {
    write_cloud(pixel, vec3(0.0f), 1.0f, 0.0f, shadow, ground.x > 0.0f ? ground.x : FAR_M);
    return;
  }
  float t_mid = 0.5f * (seg.x + seg.y);
  vec3 mid = eye + dir * t_mid;
  vec3 up = normalize(mid);
  float mu = clamp(thickness_m / (seg.y - seg.x), 1e-4f, 1.0f);
  // Within the slab only the part ahead counts: a thinner slab (its depth ahead).
  float tau_seen = tau;
  float eye_r = length(eye);
  if (eye_r > frame.radii_m.z && eye_r < frame.radii_m.w) tau_seen = tau * (seg.y - seg.x) * mu / thickness_m;
  // Where the eye looks from: below the slab it looks up (the light on the far side when above
  // the horizon); above it looks down (the light on its side).
  bool from_below = dot(dir, up) > 0.0f;
  float mu0 = dot(up, light);
  float cos_alpha = -dot(dir, light);
  int kind = int(frame.classic_blinn.w);
  float x = frame.classic_blinn.z, omega = frame.classic_blinn.y;
  float phi = blinn_phase(kind, x, cos_alpha, seed_form);
  float phi_pi = blinn_phase(kind, x, -1.0f, seed_form);
  bool lit_from_front = from_below ? mu0 < 0.0f : mu0 > 0.0f;
  vec2 b_tr = blinn_layer(tau_seen, mu, max(abs(mu0), 1e-4f), lit_from_front, omega, phi, phi_pi,
                          seed_form);
  // A light below the horizon of the slab lights nothing the slab can scatter (it would come
  // through the planet for an eye below).
  float lit = mu0 > 0.0f ? 1.0f : 0.0f;
  // Blinn's B is radiance over the beam's irradiance / 4 pi.
  vec3 radiance = frame.sun_at_clouds.rgb * (lit * b_tr.x / (4.0f * PI));
  float transmittance = clamp(b_tr.y, 0.0f, 1.0f);
  float eye_alt_m = eye_r - frame.radii_m.x;
  vec3 air = air_transmittance(eye_alt_m, length(mid) - frame.radii_m.x, t_mid);
  float haze = (1.0f - air.g) * (1.0f - transmittance);
  write_cloud(pixel, air * radiance, transmittance, haze, shadow, t_mid);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  int width = frame.cloud_grid.x, height = frame.cloud_grid.y;
  if (pixel.x >= width || pixel.y >= height) return;
  vec3 eye = frame.camera_pos_m.xyz;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x),
                        float(pixel.y), float(width), float(height));
  if (MODEL == CLASSIC_BLINN) blinn(pixel, eye, dir, frame.sun_dir.xyz);
}

// Lightning as one of compose's translucent layers (cmake/module_registry.cmake): the light the
// frame's flashes (lightning.comp) add, which hides nothing (a 0):
// - the clouds' faces, lit from inside: the cloud's opacity at the pixel times the glow of
//   each flash at the clouds' opacity-weighted distance (lightning_glow_cd_m2). The march
//   spreads a view over frames and a flash must light its own frame, so its emission is taken
//   here, every frame at every pixel, at that one point of the ray;
// - the ground, lit by each flash's glow on the cloud base above it (a Lambertian patch sending
//   half the flux down) and by a stroke's channel (a point at half its height), seen through
//   the clouds in front;
// - the bolt: its channel, a line whose luminous intensity per metre is the flux over 4 pi
//   and its length, over the larger of its width and the pixel's.
// The rain near the camera is lit by the flashes too (lightning_illuminance_lx, read by the
// precipitation's particles, precipitation_particles.frag). GLSL only; the includer includes bindings_inc.glsl.
#ifndef NEPHELE_LIGHTNING_LAYER
#define NEPHELE_LIGHTNING_LAYER

#include "common/lightning_inc.glsl"
#include "common/math_inc.glsl"
#include "render/modules/lightning/lightning_gpu_inc.glsl"

layout(std140, set = 1, binding = 7) uniform LightningBlock { LightningGpu lightning; };
layout(std430, set = 1, binding = 6) readonly buffer LightningFlashes { LightningFlashesGpu flashes; };

// A flash's light: the blue-white of its nitrogen lines, of luminance 1.
const vec3 LIGHTNING_RGB = vec3(0.8f, 0.85f, 1.0f) / 0.8493f;
const float LIGHTNING_CHANNEL_M = 0.5f;  // the glowing channel's width (m)

// The illuminance (lx) the flashes give at `pos` (planet frame) on a surface facing `normal`;
// a zero normal: on a small sphere (its cross-section's).
float lightning_illuminance_lx(vec3 pos, vec3 normal) {
  if (lightning.when.w == 0.0f) return 0.0f;
  float e = 0.0f;
  for (int k = 0; k < LIGHTNING_MAX_FLASHES; ++k) {
    vec4 f = flashes.flash[k];
    if (f.w <= 0.0f) continue;
    vec3 up = normalize(f.xyz);
    // The cloud base over the flash, a Lambertian patch sending half of it down.
    vec3 base = up * (frame.radii_m.x + lightning.cloud.x);
    vec3 to = base - pos;
    float d2 = max(dot(to, to), 1.0f);
    vec3 l = to * inversesqrt(d2);
    float facing = normal == vec3(0.0f) ? 1.0f : max(dot(normal, l), 0.0f);
    e += f.w / (2.0f * PI) * max(-dot(l, up), 0.0f) * facing / d2;
    if (flashes.kind[k].x > 0.5f) {  // the channel, a point at half its height
      to = up * (frame.radii_m.x + 0.5f * lightning.cloud.x) - pos;
      d2 = max(dot(to, to), 1.0f);
      facing = normal == vec3(0.0f) ? 1.0f : max(dot(normal, to * inversesqrt(d2)), 0.0f);
      e += f.w / (4.0f * PI) * facing / d2;
    }
  }
  return e;
}

// The bolt's luminance (cd/m^2) along the ray from `eye` along `dir` (x) and where (y, m).
vec2 lightning_bolt(vec3 eye, vec3 dir, float pixel_rad) {
  vec4 bolt = flashes.bolt;
  if (bolt.z <= 0.0f) return vec2(0.0f);
  vec3 centre = flashes.bolt_centre.xyz - eye;
  float along = dot(centre, dir);
  if (length(centre - dir * max(along, 0.0f)) > bolt.z + 100.0f) return vec2(0.0f);
  float per_m = bolt.x / (4.0f * PI * max(bolt.y, 1.0f));  // cd per metre of the main channel
  float luminance = 0.0f, where_m = 0.0f;
  vec3 a = flashes.bolt_vertex[0].xyz - eye;
  for (int j = 1; j < int(bolt.w); ++j) {
    vec4 v = flashes.bolt_vertex[j];
    vec3 b = v.xyz - eye;
    if (v.w > 0.0f) {
      vec3 closest = ray_segment_closest(dir, a, b - a);
      float width_m = max(LIGHTNING_CHANNEL_M, pixel_rad * closest.x);
      float l = v.w * per_m / width_m * saturate(1.0f - closest.y / width_m);
      if (l > luminance) where_m = closest.x;
      luminance = max(luminance, l);
    }
    a = b;
  }
  return vec2(luminance, where_m);
}

vec4 lightning_layer(vec2 uv, out float distance_m) {
  distance_m = 0.0f;
  if (lightning.when.w == 0.0f) return vec4(0.0f);
  vec2 image = vec2(frame.size.xy);
  vec2 pixel = uv * image - 0.5f;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, pixel.x, pixel.y, image.x,
                        image.y, vec2(frame.camera_right.w, frame.camera_up.w));
  vec3 eye = frame.camera_pos_m.xyz;
  vec4 clouds = textureLod(clouds_a, uv, 0.0f);
  float clouds_m = textureLod(clouds_b, uv, 0.0f).z * 1000.0f;
  float opacity = clouds_m > 0.0f ? 1.0f - clouds.a : 0.0f;
  float light = 0.0f;
  if (opacity > 0.0f) {
    vec3 face = eye + dir * clouds_m;
    for (int k = 0; k < LIGHTNING_MAX_FLASHES; ++k) {
      vec4 f = flashes.flash[k];
      if (f.w > 0.0f) light += opacity * lightning_glow_cd_m2(f.w, length(face - f.xyz));
    }
  }
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  float ground_m = ground.x > 0.0f ? ground.x : 0.0f;
  if (ground_m > 0.0f) {
    vec3 at = eye + dir * ground_m;
    light += (1.0f - opacity) * frame.sky_model.y / PI * lightning_illuminance_lx(at, normalize(at));
  }
  vec2 bolt = lightning_bolt(eye, dir, 2.0f * frame.camera_pos_m.w / image.y);
  if (bolt.x > 0.0f && (ground_m <= 0.0f || bolt.y < ground_m))
    light += bolt.x * (opacity > 0.0f && bolt.y > clouds_m ? clouds.a : 1.0f);
  if (light <= 0.0f) return vec4(0.0f);
  // In front of what it lights: the clouds, else the ground or the bolt.
  float at_m = opacity > 0.0f ? clouds_m : ground_m > 0.0f ? ground_m : bolt.y;
  distance_m = 0.999f * at_m;
  return vec4(light * LIGHTNING_RGB, 0.0f);
}

#endif

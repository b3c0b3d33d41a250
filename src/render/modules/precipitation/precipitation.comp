#version 450
// Pass: the precipitation's froxels (precipitation_field_inc.glsl) at an eighth of the image's
// resolution per axis: per texel, along the ray through its block's centre, the medium from the
// eye to each of the march's samples (slice k: rgb the light it scatters towards the eye per
// unit of the key light's illuminance, before the clouds' shade; a its transmittance; and the
// light's opacity-weighted distance, summed: depth x (1 - a), km). The medium is taken linear
// between the samples (the trapezoid rule), so that a shaft's edge moves smoothly from one
// pixel to the next. Compose reads them at its own distances (precipitation_medium.glsl).
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "render/modules/precipitation/precipitation_field_inc.glsl"

layout(set = 1, binding = 2, rgba16f) uniform writeonly image3D precipitation_froxels_out;
layout(set = 1, binding = 3, r16f) uniform writeonly image3D precipitation_depth_out;

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(precipitation_depth_out).xy;
  if (q.x >= size.x || q.y >= size.y) return;
  vec2 image = vec2(frame.size.xy);
  vec2 pixel = (vec2(q) + 0.5f) * image / vec2(size) - 0.5f;  // the block's centre
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, pixel.x, pixel.y, image.x, image.y,
                        vec2(frame.camera_right.w, frame.camera_up.w));
  vec3 eye = frame.camera_pos_m.xyz;
  vec2 stretch = precipitation_stretch(eye, dir);
  float horizontal = precipitation_horizontal(eye, dir);
  vec3 light = vec3(0.0f);
  float transmittance = 1.0f;
  float depth_km = 0.0f;
  float t_prev = stretch.x;
  vec4 prev = precipitation_at(eye + dir * t_prev);
  imageStore(precipitation_froxels_out, ivec3(q, 0), vec4(0.0f, 0.0f, 0.0f, 1.0f));
  imageStore(precipitation_depth_out, ivec3(q, 0), vec4(0.0f));
  for (int k = 1; k <= PRECIPITATION_STEPS; ++k) {
    float t_next = precipitation_sample_t(k, stretch, horizontal);
    vec4 next = precipitation_at(eye + dir * t_next);
    float step_transmittance = exp(-0.5f * (prev.a + next.a) * max(t_next - t_prev, 0.0f));
    vec3 scattered = prev.a + next.a > 0.0f
                         ? (prev.rgb * prev.a + next.rgb * next.a) / (prev.a + next.a)
                         : vec3(0.0f);
    float weight = transmittance * (1.0f - step_transmittance);
    light += weight * scattered;
    depth_km += weight * 0.0005f * (t_prev + t_next);
    transmittance *= step_transmittance;
    imageStore(precipitation_froxels_out, ivec3(q, k), vec4(light, transmittance));
    imageStore(precipitation_depth_out, ivec3(q, k), vec4(depth_km));
    t_prev = t_next;
    prev = next;
  }
}

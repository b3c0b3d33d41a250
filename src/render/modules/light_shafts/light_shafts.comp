#version 450
// Pass: volumetric light shafts (quality.light_shafts = "volumetric"; light_shafts_inc.glsl) at
// an eighth of the image's resolution per axis (the beams are broad; compose filters them up):
// per texel, along the ray through its block's centre, the share of the air's light (its
// single and multiple scattering) that the clouds' shadows take from the sun: rgb along the
// whole ray, a (of the luminance) in front of the clouds there.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "frame_atmosphere_inc.glsl"
const int MARCH_MODE = 0;  // cloud_field_inc.glsl's lookups
#include "light_shafts_inc.glsl"
#include "terrain_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 q = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(light_shafts_out);
  if (q.x >= size.x || q.y >= size.y) return;
  vec2 image = vec2(frame.size.xy);
  vec2 pixel = (vec2(q) + 0.5f) * image / vec2(size) - 0.5f;  // the block's centre
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, pixel.x, pixel.y, image.x, image.y,
                        vec2(frame.camera_right.w, frame.camera_up.w));
  vec2 uv = (pixel + 0.5f) / image;
  float transmittance = textureLod(clouds_a, uv, 0.0f).a;
  float cloud_m = transmittance < 0.999f ? textureLod(clouds_b, uv, 0.0f).z * 1000.0f : SHAFT_FAR_M;
  // Jittered by the whole image's texel (a tile's window starts at output_image.zw).
  vec2 texel = vec2(q) + round(frame.output_image.zw * vec2(size) / image);
  float jitter = interleaved_gradient_noise(texel.x, texel.y);
  float terrain_m = terrain_distance_at(uv);
  ShaftLight s = light_shaft_light(frame.camera_pos_m.xyz, dir, cloud_m,
                                   terrain_m > 0.0f ? terrain_m : SHAFT_FAR_M, jitter);
  vec3 air = s.single_front + s.single_behind + s.multiple_front + s.multiple_behind;
  vec3 lost = s.lost_front + s.lost_behind;
  const vec3 Y = vec3(0.2126f, 0.7152f, 0.0722f);
  vec3 share = lost / max(air, vec3(1e-30f));
  float front =
      dot(s.lost_front, Y) / max(dot(s.single_front + s.multiple_front, Y), 1e-30f);
  imageStore(light_shafts_out, q, vec4(clamp(share, 0.0f, 1.0f), clamp(front, 0.0f, 1.0f)));
}

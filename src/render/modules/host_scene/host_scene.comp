#version 450
// Pass: the host's geometry (render/modules/host_scene/host_scene.h), after the terrain and before the
// clouds, one thread per pixel: its depth turned into a distance along the view ray through
// the host's inverse projection, and where it is nearer than the terrain (or there is none)
// its radiance per unit key-light illuminance and that distance go into LAYER_SURFACES, where
// the clouds stop, compose fogs it with the aerial perspective and hides the sky behind it,
// as it does the terrain's.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "terrain_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

float host_depth(uint i) {
  int format = int(frame.host_scene.z);
  if (format == HOST_DEPTH_UNORM16) return float((host_texels[i >> 1] >> (16u * (i & 1u))) & 0xffffu) / 65535.0f;
  if (format == HOST_DEPTH_UNORM24) return float(host_texels[i] & 0xffffffu) / 16777215.0f;
  return uintBitsToFloat(host_texels[i]);
}

vec3 host_color(uint i) {
  uint start = uint(frame.host_layout.x);
  if (int(frame.host_scene.w) == HOST_COLOR_FLOAT4)
    return vec3(uintBitsToFloat(host_texels[start + 4u * i]), uintBitsToFloat(host_texels[start + 4u * i + 1u]),
                uintBitsToFloat(host_texels[start + 4u * i + 2u]));
  return vec3(unpackHalf2x16(host_texels[start + 2u * i]), unpackHalf2x16(host_texels[start + 2u * i + 1u]).x);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.size.x || pixel.y >= frame.size.y) return;
  vec4 terrain = terrain_present() ? imageLoad(layers_out, ivec3(pixel, LAYER_SURFACES)) : vec4(0.0f);
  uint i = uint(pixel.y) * uint(frame.size.x) + uint(pixel.x);
  float depth = host_depth(i);
  bool reversed = frame.host_scene.y > 0.5f;
  // The far plane (the cleared depth) holds no geometry.
  bool geometry = reversed ? depth > 0.0f : depth < 1.0f;
  vec2 ndc = (vec2(pixel) + 0.5f) / vec2(frame.size.xy) * 2.0f - 1.0f;
  vec4 view = frame.host_inverse_projection * vec4(ndc, depth, 1.0f);
  float distance_m = geometry && view.w != 0.0f ? length(view.xyz / view.w) : 0.0f;
  if (distance_m > 0.0f && (terrain.a <= 0.0f || distance_m < terrain.a)) {
    vec3 radiance = host_color(i) * frame.host_layout.y;
    terrain = vec4(radiance / max(frame.sun_illuminance.rgb, vec3(1e-30f)), distance_m);
  }
  imageStore(layers_out, ivec3(pixel, LAYER_SURFACES), terrain);
}

#version 450
// Pass: the cloud shadow map for the host (render/modules/host_lighting/host_lighting.h), one thread per
// texel: the share of the key light that passes the clouds (cloud_shadow_at) along its ray
// through the texel's point of the plane at the cloud shell's bottom. Every point below the
// shell on that ray has the same share, so the host looks its points up by projecting them
// along the light onto that plane (HostLighting::world_to_shadow_map).
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/clouds_inc.glsl"
const int MARCH_MODE = 0;  // cloud_field_inc.glsl's lookups
#include "cloud_field_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// The key light kept 3 degrees above the horizon (render/modules/host_lighting/host_lighting.cpp does too).
const float SHADOW_MAP_MIN_LIGHT_Z = 0.0523f;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  int size = frame.host_shadow_grid.x;
  if (texel.x >= size || texel.y >= size) return;
  vec4 map = frame.host_shadow_map;
  vec2 enu = vec2(map.x, map.y) + (vec2(texel) + 0.5f) / float(size) * vec2(map.z, -map.z);
  // A metre below the shell: cloud_shadow_at follows the light from there up through it.
  vec3 p = vec3(enu, frame.radii_m.x + map.w - 1.0f);
  vec3 light = frame.sun_dir.xyz;
  light = normalize(vec3(light.xy, max(light.z, SHADOW_MAP_MIN_LIGHT_Z)));
  imageStore(cloud_shadow_map_out, texel, vec4(cloud_shadow_at(p, light, 1.0e9f, 16)));
}

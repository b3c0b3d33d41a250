#version 450
// The particle clouds' lighting (seed 003, 3.3.2, after Harris and Lastra 2001) on the device:
// the CPU's splat (particles/particle_lighting.cpp, light_with and splat_row_scalar) with the
// same float arithmetic and rounding, to measure one against the other. One workgroup a cloud:
// its BUFFER x BUFFER buffer seen from the light lives in shared memory (a byte value a uint);
// its particles, sorted nearest the light first on the host, are splatted one after the other.
// For each: every invocation reads the texel under its centre, I_k (the first writes it out);
// after a barrier the invocations share out the texels of its bounding span; a barrier again.
// The arithmetic is `precise` so that no multiply and add fuse: the CPU build rounds each.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/particle_inc.glsl"

layout(constant_id = 0) const int BUFFER = 32;  // the buffer's side (texels), 1 to 64
// Invocations a cloud (render/modules/particle_light_gpu/particle_light_gpu.cpp: a few, splats are small).
layout(local_size_x_id = 1) in;

// BUFFER^2 uints: 16 KiB at 64, the least any device must give a workgroup.
shared uint texels[BUFFER * BUFFER];

// The texels a splat touches: [lo.x, hi.x) x [lo.y, hi.y), inside the buffer (span_of).
void span_of(vec3 s, out ivec2 lo, out ivec2 hi) {
  lo = max(ivec2(floor(s.xy - s.z)), ivec2(0));
  hi = min(ivec2(ceil(s.xy + s.z)), ivec2(BUFFER));
}

// Texel (x, y) under the splat: dst + (target - dst) a, a = opacity particle_profile(d^2 / r^2),
// rounded to the nearest byte (splat_row_scalar, operation for operation).
uint splat_texel(ivec2 texel, vec3 s, float inv_r2, float opacity, float target) {
  precise float dx = float(texel.x) + 0.5f - s.x;
  precise float dy = float(texel.y) + 0.5f - s.y;
  precise float dy2 = dy * dy;
  precise float q2 = (dx * dx + dy2) * inv_r2;
  precise float a = opacity * particle_profile(q2);
  precise float dst = float(texels[texel.y * BUFFER + texel.x]);
  precise float value = dst + (target - dst) * a + 0.5f;
  return uint(value);
}

void main() {
  ParticleLightCloudGpu cloud = particle_light_clouds[gl_WorkGroupID.x];
  uint id = gl_LocalInvocationIndex, invocations = gl_WorkGroupSize.x;
  for (uint i = id; i < uint(BUFFER * BUFFER); i += invocations) texels[i] = 255u;  // I_0 = 1
  float forward = cloud.shading.x, opacity = cloud.shading.y;
  int first = cloud.range.x, count = cloud.range.y;
  vec4 next = count > 0 ? particle_splats[first].splat : vec4(0.0f);
  for (int k = 0; k < count; ++k) {
    barrier();  // the last splat's texels written
    vec4 s = next;
    // Loaded while this splat is drawn: on a GPU the splats may lie in host memory.
    if (k + 1 < count) next = particle_splats[first + k + 1].splat;
    ivec2 centre = clamp(ivec2(s.xy), ivec2(0), ivec2(BUFFER - 1));
    precise float light = float(texels[centre.y * BUFFER + centre.x]) * (1.0f / 255.0f);
    if (id == 0u) particle_lights[first + int(s.w)] = light;
    barrier();  // every invocation has read the centre before any texel changes
    precise float target = 255.0f * forward * light;
    precise float inv_r2 = 1.0f / max(s.z * s.z, 1e-6f);
    ivec2 lo, hi;
    span_of(s.xyz, lo, hi);
    int width = hi.x - lo.x, texels_in_span = width * (hi.y - lo.y);
    for (int i = int(id); i < texels_in_span; i += int(invocations)) {
      ivec2 texel = lo + ivec2(i % width, i / width);
      texels[texel.y * BUFFER + texel.x] = splat_texel(texel, s.xyz, inv_r2, opacity, target);
    }
  }
}

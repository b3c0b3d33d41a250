#version 450
// Pass: march range. For each block of this frame's marched samples, the range (lo, hi) of
// march_a over the 4 x 4 samples from one block up and left to two down and right: the
// neighbourhood resolve.comp clamps reprojected history to while the image moves. Computed
// once per block here rather than by each of the stride^2 pixels that use it.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  int stride = frame.cloud_grid.z;
  // Blocks whose marched pixel lies inside the buffer: 0 ... last (as in resolve.comp).
  ivec2 last = (frame.cloud_grid.xy - 1 - frame.march_offset.xy) / stride;
  ivec2 block = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThan(block, last))) return;
  vec4 lo = vec4(1e30f);
  vec4 hi = vec4(-1e30f);
  for (int y = -1; y <= 2; ++y)
    for (int x = -1; x <= 2; ++x) {
      vec4 a = texelFetch(march_a, clamp(block + ivec2(x, y), ivec2(0), last), 0);
      lo = min(lo, a);
      hi = max(hi, a);
    }
  imageStore(range_lo, block, lo);
  imageStore(range_hi, block, hi);
}

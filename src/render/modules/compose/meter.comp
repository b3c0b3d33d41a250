#version 450
// Pass: the exposure meter. What a reflected-light meter reads of the final HDR image, on the
// device so that a live display (the viewer, a host) can expose automatically without reading
// the image back: the log-average luminance (nephele/exposure.h, metered_luminance) over a grid
// of METER_GRID^2 pixels spread evenly over the image. One workgroup: each invocation reads
// (METER_GRID / 16)^2 of them, then they sum in shared memory.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

const int GROUP_SIZE = 16;
const int METER_GRID = 64;
const int PER_AXIS = METER_GRID / GROUP_SIZE;

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

shared float partial[GROUP_SIZE * GROUP_SIZE];

void main() {
  uint id = gl_LocalInvocationIndex;
  float sum = 0.0f;
  for (int k = 0; k < PER_AXIS * PER_AXIS; ++k) {
    ivec2 cell = PER_AXIS * ivec2(gl_LocalInvocationID.xy) + ivec2(k % PER_AXIS, k / PER_AXIS);
    ivec2 p = ivec2((vec2(cell) + 0.5f) / float(METER_GRID) * vec2(frame.size.xy));
    vec3 c = imageLoad(color_rw, min(p, frame.size.xy - 1)).rgb;
    float luminance = dot(c, vec3(0.2126f, 0.7152f, 0.0722f));
    sum += log(max(luminance, 1e-9f));
  }
  partial[id] = sum;
  barrier();
  for (uint n = uint(GROUP_SIZE * GROUP_SIZE) / 2u; n > 0u; n >>= 1) {
    if (id < n) partial[id] += partial[id + n];
    barrier();
  }
  if (id == 0u) meter_mean_log_luminance = partial[0] / float(METER_GRID * METER_GRID);
}

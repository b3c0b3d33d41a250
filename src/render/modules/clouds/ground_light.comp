#version 450
// Pass: ground light. The clouds' mean diffuse transmittance straight down over the ground
// around the camera (GROUND_LIGHT_HALF_M each way): the share of the sky's light that the
// gaps and the clouds together pass to the ground there. Compose lights the ground's sky-lit
// part by it and by the cloud towards the sun (cloud_ground_sky_share), so a broken field's
// shadows keep the light of its gaps while a closed deck's ground is grey. One workgroup:
// each invocation marches 2 x 2 of the GRID^2 columns, then they sum in shared memory.
#extension GL_GOOGLE_include_directive : require

layout(constant_id = 0) const int MARCH_MODE = 0;

#include "cloud_field_inc.glsl"

const float GROUND_LIGHT_HALF_M = 16000.0f;  // the region's half extent
const int GROUP_SIZE = 16;                   // invocations per side of the workgroup
const int GRID = 2 * GROUP_SIZE;             // columns per side: 2 x 2 per invocation
const int COLUMN_SAMPLES = 16;               // density samples up each column

layout(local_size_x = GROUP_SIZE, local_size_y = GROUP_SIZE) in;

shared float partial[GROUP_SIZE * GROUP_SIZE];

// Diffuse transmittance of the clouds straight up from the shell's bottom at horizontal
// position xy (planet frame).
float column_transmittance(vec2 xy) {
  float bottom = frame.radii_m.z, top = frame.radii_m.w;
  float ds = (top - bottom) / float(COLUMN_SAMPLES);
  float depth = 0.0f;
  for (int i = 0; i < COLUMN_SAMPLES; ++i) {
    float r = bottom + (float(i) + 0.5f) * ds;
    depth += cloud_density(point_at_radius(xy, r), true) * ds;
  }
  return light_transmittance(depth);
}

void main() {
  uint id = gl_LocalInvocationIndex;
  const float cell_m = 2.0f * GROUND_LIGHT_HALF_M / float(GRID);
  float sum = 0.0f;
  for (int k = 0; k < 4; ++k) {
    ivec2 cell = 2 * ivec2(gl_LocalInvocationID.xy) + ivec2(k & 1, k >> 1);
    vec2 xy = frame.camera_pos_m.xy + (vec2(cell) + 0.5f) * cell_m - GROUND_LIGHT_HALF_M;
    sum += column_transmittance(xy);
  }
  partial[id] = sum;
  barrier();
  for (uint n = uint(GROUP_SIZE * GROUP_SIZE) / 2u; n > 0u; n >>= 1) {
    if (id < n) partial[id] += partial[id + n];
    barrier();
  }
  if (id == 0u) imageStore(ground_light_out, ivec2(0), vec4(partial[0] / float(GRID * GRID)));
}

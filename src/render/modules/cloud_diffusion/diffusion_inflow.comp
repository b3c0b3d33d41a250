#version 450
// Pass: cloud diffusion, after each completed gather of the light clear air carries
// (diffusion_exchange.comp): for each cell of cloud, the light that comes in through its faces
// towards clear air, sum of open conductance x 4 J- / h over them (exchange_incoming), the
// source the solve adds (diffusion_solve.comp reads one value a cell, not six faces' gathers).
// The gather's set to read: EXCHANGE_READ_SET (diffusion_exchange_inc.glsl).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bindings_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_exchange_inc.glsl"

layout(set = 1, binding = 2, rgba32f) uniform readonly image3D cloud_diffusion_medium;
layout(set = 1, binding = 3, rgba32f) uniform image3D cloud_diffusion_phi;
layout(set = 1, binding = 9, r32f) uniform writeonly image3D cloud_diffusion_inflow;

void main() {
  ivec3 c = diffusion_cell(gl_GlobalInvocationID.xy);
  int cascade = diffusion_cascade(c);
  if (!diffusion_in_grid(c, cascade)) return;
  vec4 m = imageLoad(cloud_diffusion_medium, c);
  float d = m.x;
  vec3 h = diffusion_cell_m(cascade);
  float inflow = 0.0f;
  for (int k = 0; k < 6 && d > 0.0f; ++k) {
    int axis = k >> 1;
    ivec3 step = ivec3(0);
    step[axis] = (k & 1) == 0 ? 1 : -1;
    ivec3 n = c + step;
    if (diffusion_in_grid(n, cascade) && imageLoad(cloud_diffusion_medium, n).x <= 0.0f)
      inflow += diffusion_open_conductance(d, h[axis]) / h[axis] * 4.0f *
                exchange_incoming(n, EXCHANGE_READ_SET, -step);
  }
  imageStore(cloud_diffusion_inflow, c, vec4(inflow));
  vec4 solved = imageLoad(cloud_diffusion_phi, c);
  imageStore(cloud_diffusion_phi, c, vec4(solved.xyz, m.z + inflow));
}

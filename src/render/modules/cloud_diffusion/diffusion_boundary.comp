#version 450
// Pass: cloud diffusion, the cells the gather casts its rays from (diffusion_exchange.comp):
// each row of the grid lists its cells of clear air next to cloud, once a build, after the
// medium is filled. Texel (i, y, z) of cloud_diffusion_boundary holds the x of row (y, z)'s i-th
// such cell, -1 past its last. The gather's invocations then take listed cells only: where a
// SIMD batch of lavapipe's held one such cell among eight, all eight ran its 14 rays (the
// gather took 200 ms of a build's 3 s). The other cells' gathered light is 0 (in both sets),
// as diffusion_exchange_inc.glsl has it, and the listed ones' too for a build from zero
// (dispatch.values.x 1, as diffusion_fill.comp's). One invocation a row, in x order: the list
// is the same on every run, and so is which cells an animation's band of the gather takes.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 64) in;

#include "common/bindings_inc.glsl"
#include "dispatch_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_exchange_inc.glsl"

layout(set = 1, binding = 2, rgba32f) uniform readonly image3D cloud_diffusion_medium;
layout(set = 1, binding = 10, r32f) uniform writeonly image3D cloud_diffusion_boundary;

// Whether clear cell c of cascade k has a cell of cloud beside it.
bool next_to_cloud(ivec3 c, int k) {
  bool found = false;
  for (int j = 0; j < 6; ++j) {
    ivec3 n = c;
    n[j >> 1] += (j & 1) == 0 ? 1 : -1;
    found = found || (diffusion_in_grid(n, k) && imageLoad(cloud_diffusion_medium, n).x > 0.0f);
  }
  return found;
}

void main() {
  int row = int(gl_GlobalInvocationID.x);
  ivec3 first = diffusion_cell(uvec2(0, row));
  int cascade = diffusion_cascade(first);
  if (!diffusion_in_grid(first, cascade)) return;
  bool zero = dispatch.values.x != 0;
  int listed = 0;
  for (int x = 0; x < DIFFUSION_XY; ++x) {
    ivec3 c = ivec3(x, first.yz);
    bool boundary = imageLoad(cloud_diffusion_medium, c).x <= 0.0f && next_to_cloud(c, cascade);
    if (boundary) {
      imageStore(cloud_diffusion_boundary, ivec3(listed, first.yz), vec4(float(x)));
      ++listed;
    }
    if (!boundary || zero) {
      exchange_store(c, 0, vec4(0.0f), vec4(0.0f));
      exchange_store(c, 1, vec4(0.0f), vec4(0.0f));
    }
  }
  for (int i = listed; i < DIFFUSION_XY; ++i)
    imageStore(cloud_diffusion_boundary, ivec3(i, first.yz), vec4(-1.0f));
}

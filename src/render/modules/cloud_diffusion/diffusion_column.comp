#version 450
// Pass: cloud diffusion, a deck's open base. Once a build, after the medium is filled
// (diffusion_fill.comp), one invocation a column of cells: a cell of cloud whose column below
// is thin in transport terms (the similarity-scaled optical depth from its centre to the
// grid's bottom under OPEN_TAU) and whose column above is thick (over THICK_TAU) takes
// diffusion's own coefficient D = 1 / (3 sigma_tr) instead of the fill's cap of a few cell
// sides. The cap stands for the free flight between dense blobs of an eroded cloud; under a
// deck's base nothing stops the light on its way down, and the cap held it in the base
// (the suite's overcast 25.6% too bright, 9.1% with this pass). A cumulus' base, thin above,
// keeps the cap (freeing every open base left the moonlit cumulus 6.2 -> 9.0% too dark).
// Clear air (D 0) stays out of the solve.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bindings_inc.glsl"
#include "dispatch_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"

layout(set = 1, binding = 2, rgba32f) uniform image3D cloud_diffusion_medium;
layout(set = 1, binding = 3, rgba32f) uniform image3D cloud_diffusion_phi;

// Transport optical depths (stop 73, the suite at 40 x 25: OPEN_TAU 0.25 to 1 the same within
// 0.2 points; THICK_TAU 2 frees a little more, 72.1 points against 72.5, 5 too little, 79.5).
const float OPEN_TAU = 0.5f;
const float THICK_TAU = 3.0f;

void main() {
  int x = int(gl_GlobalInvocationID.x), row = int(gl_GlobalInvocationID.y);
  int cascade = row / DIFFUSION_XY;
  if (x >= DIFFUSION_XY || cascade >= DIFFUSION_CASCADES) return;
  int y = row % DIFFUSION_XY;
  int bottom = cascade * DIFFUSION_Z;
  float h = diffusion_cell_m(cascade).z;
  float column = 0.0f;
  for (int z = bottom; z < bottom + DIFFUSION_Z; ++z)
    column += imageLoad(cloud_diffusion_medium, ivec3(x, y, z)).w * h;
  float below = 0.0f;  // from the grid's bottom to the cell's lower face
  for (int z = bottom; z < bottom + DIFFUSION_Z; ++z) {
    ivec3 c = ivec3(x, y, z);
    vec4 m = imageLoad(cloud_diffusion_medium, c);
    float centre = below + 0.5f * m.w * h;
    below += m.w * h;
    if (m.x <= 0.0f || centre >= OPEN_TAU || column - centre <= THICK_TAU) continue;
    m.x = 1.0f / (3.0f * m.w);
    imageStore(cloud_diffusion_medium, c, m);
    vec4 p = imageLoad(cloud_diffusion_phi, c);
    imageStore(cloud_diffusion_phi, c, vec4(p.x, m.x, p.zw));
  }
}

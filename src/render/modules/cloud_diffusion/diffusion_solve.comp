#version 450
// Pass: cloud diffusion, one half of a red-black successive over-relaxation sweep of the
// diffusion equation for the clouds' multiple-scattered light with similarity scaling
// (isotropic scattering at sigma_s (1 - g)), -div(D grad phi) + sigma_a phi = Q, in finite
// volumes on the grid
// (diffusion_grid_inc.glsl): each cell of one colour (dispatch.values.x: (x + y + z) % 2) from
// its six neighbours, which are of the other colour, in place. Faces towards clear air or past
// the grid take the Marshak condition (diffusion_open_conductance).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bindings_inc.glsl"
#include "dispatch_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"

// Each cell's (phi, D, sigma_a, source): its fluence, solved in place, and what the solve reads
// of its medium, in one load (the sunlight it scatters Q plus the light clear air brings back
// in, diffusion_fill.comp and diffusion_inflow.comp).
layout(set = 1, binding = 3, rgba32f) uniform image3D cloud_diffusion_phi;

void main() {
  ivec3 c = diffusion_cell(gl_GlobalInvocationID.xy);
  c.x = 2 * c.x + ((c.y + c.z + dispatch.values.x) & 1);
  int cascade = diffusion_cascade(c);
  if (!diffusion_in_grid(c, cascade)) return;
  vec4 cell = imageLoad(cloud_diffusion_phi, c);
  float phi = cell.x, d = cell.y;
  if (d <= 0.0f) return;
  vec3 h = diffusion_cell_m(cascade);
  // The balance Q = sigma_a phi + sum over faces of their flux out / h, linear in phi.
  float gained = cell.w, kept = cell.z;
  for (int k = 0; k < 6; ++k) {
    int axis = k >> 1;
    ivec3 step = ivec3(0);
    step[axis] = (k & 1) == 0 ? 1 : -1;
    ivec3 n = c + step;
    bool inside = diffusion_in_grid(n, cascade);
    // Past the grid's sides the clouds go on: no flux through them (a deck cut there would
    // lose its light sideways).
    if (!inside && axis < 2) continue;
    vec2 neighbour = inside ? imageLoad(cloud_diffusion_phi, n).xy : vec2(0.0f);
    if (neighbour.y > 0.0f) {
      // The limiter from the fluence as it is (lagged: the balance stays linear in phi).
      float g = diffusion_conductance(d, neighbour.y, h[axis],
                                      diffusion_limiter(phi, neighbour.x, h[axis]));
      gained += g * neighbour.x / h[axis];
      kept += g / h[axis];
    } else {
      kept += diffusion_open_conductance(d, h[axis]) / h[axis];  // clear air, or open sky
    }
  }
  float solved = gained / max(kept, 1e-12f);
  cell.x = max(mix(phi, solved, diffusion.cell[cascade].z), 0.0f);
  imageStore(cloud_diffusion_phi, c, cell);
}

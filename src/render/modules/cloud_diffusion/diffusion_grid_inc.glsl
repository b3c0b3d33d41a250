// The cloud diffusion's grid as its passes see it (diffusion_fill.comp, diffusion_solve.comp,
// diffusion_field.comp): the medium of each cell, x its diffusion coefficient D = 1 / (3
// sigma_tr) (m; 0 for a cell the solve leaves out, as clear air), y its absorption sigma_a
// (1/m), z the sunlight it scatters Q (per unit volume and of the sun's irradiance, 1/m), w
// its similarity-scaled extinction sigma_tr = sigma_t (1 - albedo g) (1/m); and the solve's
// image (phi, D, sigma_a, source): the fluence phi, solved in place, beside what the solve
// reads of the medium, so that a neighbour is one load (source: Q plus the light clear air
// brings in, diffusion_inflow.comp). Cells are indexed (x, y, z) with x east and z up, the
// cascades stacked in z (cloud_diffusion_gpu_inc.glsl); a dispatch row is y + z DIFFUSION_XY.
#ifndef NEPHELE_DIFFUSION_GRID_INC
#define NEPHELE_DIFFUSION_GRID_INC

#include "render/modules/cloud_diffusion/cloud_diffusion_gpu_inc.glsl"

layout(std140, set = 1, binding = 0) uniform CloudDiffusionBlock { CloudDiffusionGpu diffusion; };

// The cascade of a cell.
int diffusion_cascade(ivec3 c) { return c.z / DIFFUSION_Z; }

// A cell's sides (m) in cascade k: x, y horizontal, z vertical.
vec3 diffusion_cell_m(int k) { return diffusion.cell[k].xxy; }

// Whether n is a cell of cascade k.
bool diffusion_in_grid(ivec3 n, int k) {
  return all(greaterThanEqual(n, ivec3(0, 0, k * DIFFUSION_Z))) &&
         all(lessThan(n, ivec3(DIFFUSION_XY, DIFFUSION_XY, (k + 1) * DIFFUSION_Z)));
}

// The cell of a dispatch's invocation (x the column, y the row y + z DIFFUSION_XY).
ivec3 diffusion_cell(uvec2 id) {
  return ivec3(int(id.x), int(id.y) % DIFFUSION_XY, int(id.y) / DIFFUSION_XY);
}

// The flux limiter's term (Wilson's): |grad phi| / phi across the face between cells of
// fluence phi_i and phi_j, h apart. D = 1 / (3 sigma_tr + it) keeps the flux from exceeding
// the fluence where the light streams through thin cloud, instead of carrying it around a
// cloud's halo as if it were diffusing.
float diffusion_limiter(float phi_i, float phi_j, float h) {
  return abs(phi_i - phi_j) / (h * max(0.5f * (phi_i + phi_j), 1e-12f));
}

// The conductance of the face between cells of diffusion coefficients d_i and d_j, h apart:
// the flux from i to j per unit of phi_i - phi_j, the two half cells' resistances h / 2D in
// series, each D limited by `limiter` (diffusion_limiter).
float diffusion_conductance(float d_i, float d_j, float h, float limiter) {
  return 1.0f / (0.5f * h * (1.0f / d_i + 1.0f / d_j + 2.0f * limiter));
}

// The same towards a cell left out (clear air, or past the grid above or below it): the
// Marshak condition that no diffuse light comes back in makes the flux the face's fluence / 2,
// phi_i / (h / 2D + 2).
float diffusion_open_conductance(float d_i, float h) { return 1.0f / (0.5f * h / d_i + 2.0f); }

#endif

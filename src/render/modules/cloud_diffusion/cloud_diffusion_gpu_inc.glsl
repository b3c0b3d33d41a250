// The cloud diffusion's grid and uniform block (CloudDiffusionModule, set 1
// "CloudDiffusionBlock"): one definition, included by its shaders and by C++
// (cloud_diffusion.cpp), as params_inc.glsl is.
#ifndef NEPHELE_CLOUD_DIFFUSION_GPU_INC
#define NEPHELE_CLOUD_DIFFUSION_GPU_INC

#ifdef __cplusplus
namespace nephele::gpu {
using glm::vec4;
#endif

// Cells of each regular grid: DIFFUSION_XY per horizontal axis, DIFFUSION_Z across the cloud
// shell; DIFFUSION_CASCADES grids about one centre, each 4 times as wide as the one before,
// stacked in one volume (cascade k's cells at z in [k DIFFUSION_Z, (k + 1) DIFFUSION_Z)).
const int DIFFUSION_XY = 128;
const int DIFFUSION_Z = 32;
const int DIFFUSION_CASCADES = 2;

struct CloudDiffusionGpu {
  // Per cascade. grid: the field the clouds read, xy its grid's centre in cloud space (m), z
  // its horizontal half extent (m), w 1 when the clouds read it, 0 when not; build: the grid
  // being built (its passes'), xy its centre, z its half extent; cell: the grid being built, x
  // a cell's horizontal side (m), y its vertical side (m), z the solve's over-relaxation
  // factor, w unused.
  vec4 grid[DIFFUSION_CASCADES];
  vec4 build[DIFFUSION_CASCADES];
  vec4 cell[DIFFUSION_CASCADES];
};

#ifdef __cplusplus
}  // namespace nephele::gpu
#endif

#endif

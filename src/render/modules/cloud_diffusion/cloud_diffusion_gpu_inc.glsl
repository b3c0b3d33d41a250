// The cloud diffusion's grid and uniform block (CloudDiffusionModule, set 1
// "CloudDiffusionBlock"): one definition, included by its shaders and by C++
// (cloud_diffusion.cpp), as params_inc.glsl is.
#ifndef NEPHELE_CLOUD_DIFFUSION_GPU_INC
#define NEPHELE_CLOUD_DIFFUSION_GPU_INC

#ifdef __cplusplus
namespace nephele::gpu {
using glm::vec4;
#endif

// Cells of the regular grid: DIFFUSION_XY per horizontal axis, DIFFUSION_Z across the cloud
// shell.
const int DIFFUSION_XY = 128;
const int DIFFUSION_Z = 32;

struct CloudDiffusionGpu {
  vec4 grid;   // the field the clouds read: xy its grid's centre in cloud space (m), z its
               // horizontal half extent (m), w 1 when the clouds read it, 0 when not
  vec4 build;  // the grid being built (its passes'): xy its centre, z its half extent
  vec4 cell;   // the grid being built: x a cell's horizontal side (m), y its vertical side
               // (m), z the solve's over-relaxation factor, w unused
};

#ifdef __cplusplus
}  // namespace nephele::gpu
#endif

#endif

// The push constants, included by GLSL and by C++ (src/gpu: every pipeline layout has one range
// of sizeof(DrawConstants) for all stages, kDrawConstantStages). A shader reads one of the two:
// DrawConstants per draw of a raster pass (and impostor_tiles.comp), declaring its own block;
// DispatchConstants per dispatch of a compute pass (dispatch_inc.glsl declares the block,
// gpu::dispatch pushes it), in the range's first 16 bytes.
#ifndef NEPHELE_PUSH_CONSTANTS_INC
#define NEPHELE_PUSH_CONSTANTS_INC

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace nephele::gpu {
using glm::ivec4;
using glm::vec4;
#endif

// Per draw of a raster pass (gpu/raster.h): the camera it projects with. The frame's camera for
// the image; for an impostor (render/modules/impostors/impostors.h) a square view from the same
// eye framing the cloud's bounding sphere.
struct DrawConstants {
  vec4 forward;  // xyz unit view direction; w tan(vertical fov / 2)
  vec4 right;    // xyz unit right vector; w aspect (width / height)
  vec4 up;       // xyz unit up vector (image up); w unused
  ivec4 info;    // x the first impostor of an impostor draw (impostor.vert); yzw unused
};

// Per dispatch of a compute pass: what changes between the dispatches of one frame, so that the
// frame's parameters (FrameParams) stay one block a frame.
//   clouds.comp: x the first row of blocks of a band (a still marched in bands; else 0)
//   sky_reference.comp, sky_reference_psi.comp: xy the tile's first pixel
//   path_trace.comp: x the first sample of this dispatch, y its samples per pixel, z the random
//     streams' seed, w the paths' largest number of bounces
//   compose.comp, stars.comp: x the film layer (FramePlan::film_layer; 0 the image)
struct DispatchConstants {
  ivec4 values;
};

#ifdef __cplusplus
static_assert(sizeof(DrawConstants) == 4 * 16);
static_assert(sizeof(DispatchConstants) <= sizeof(DrawConstants));
}  // namespace nephele::gpu
#endif

#endif

// Lightning's GPU structs (LightningModule): its uniform block (set 1 "LightningBlock") and the
// flashes its pass finds each frame (set 1 "LightningFlashes", lightning.comp), one definition
// each, included by its GLSL and by C++ (lightning.cpp).
#ifndef NEPHELE_LIGHTNING_GPU_INC
#define NEPHELE_LIGHTNING_GPU_INC

#ifdef __cplusplus
namespace nephele::gpu {
using glm::ivec4;
using glm::vec4;
#endif

const int LIGHTNING_MAX_FLASHES = 4;  // the flashes seen at once
const int LIGHTNING_BOLT_VERTICES = 64;
const int LIGHTNING_TILES = 9;        // the tiles of candidates around the camera, per side
const int LIGHTNING_CANDIDATES = 8;   // candidate places a tile and a slot

struct LightningGpu {
  ivec4 slot;  // x the slot the frame's time is in (time / LIGHTNING_SLOT_S), y the seed, zw the
               // tile the camera is over (x east, y north)
  vec4 when;   // x the time into the slot (s), y the chance a candidate in a core flashes
               // (lightning_candidate_chance), z the share that strike the ground, w 1: on
  vec4 cloud;  // x the low layer's base, y its top (m above the ground), z a tile's side (m)
};

struct LightningFlashesGpu {
  // xyz where each flash is (planet frame, m), w its luminous flux this frame (lm; 0: none)
  vec4 flash[LIGHTNING_MAX_FLASHES];
  vec4 kind[LIGHTNING_MAX_FLASHES];  // x 1 for a stroke to the ground, 0 in the cloud
  // The bolt of the first stroke to the ground: x its flux this frame (lm), y its main
  // channel's length (m), z the radius of a sphere about it (m; 0: no bolt), w its vertices.
  vec4 bolt;
  vec4 bolt_centre;  // xyz that sphere's centre (planet frame, m)
  // The channel's vertices (planet frame, m), w the brightness of the segment from the one
  // before (0: a branch starts here; the main channel's 1, its branches' less).
  vec4 bolt_vertex[LIGHTNING_BOLT_VERTICES];
};

#ifdef __cplusplus
}  // namespace nephele::gpu
#endif

#endif

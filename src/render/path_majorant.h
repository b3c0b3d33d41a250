// nephele — internal: the reference path tracer's majorant grid for the noise clouds (issue 21):
// per cell of PATH_GRID_XY^2 columns around the camera and PATH_GRID_BINS shells of each layer,
// a bound on sigma_t that the density field (cloud_field_inc.glsl, noise_density_pair, default
// march) never exceeds there, so delta and ratio tracking cross the gaps between clouds in one
// step. Computed on the CPU from the base noise texture's values.
//
// The bound: the field is at most apply_coverage(noise, c) x 2 x the layer's density (the
// detail only erodes, the gradients and the weather map's density channel are at most 1),
// where noise = saturate((R - W + 1) / (2 - W)) grows with the Perlin-Worley R and falls with
// the Worley fBm W = 0.625 G + 0.25 B + 0.125 A, and apply_coverage grows with both arguments.
// A trilinear sample lies between its eight texels, so over the texels a cell can reach (its
// columns moved by the wind's offsets over its heights, one texel of filter beyond) the
// largest R and smallest W bound the noise, and c is at most min(1, 2 coverage) (1 with
// precipitation).
#pragma once

#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "render/gpu_params.h"

namespace nephele {

// Texels per side of the blocks the base noise is summarised in.
constexpr int kNoiseBlock = 8;

// The base noise tile (size^3 texels, RGBA8) summarised per block of kNoiseBlock^3 texels:
// the largest R and the smallest W there.
struct NoiseBlockBounds {
  int size = 0;    // texels per axis
  int blocks = 0;  // blocks per axis
  std::vector<glm::vec2> r_max_w_min;  // x fastest
  // The block (i, j, k), wrapped: the tile repeats.
  glm::vec2 at(int i, int j, int k) const;
};

// `rgba`: size^3 texels, 4 bytes each, x fastest (as the texture downloads).
NoiseBlockBounds noise_block_bounds(const std::vector<uint8_t>& rgba, int size);

// The grid for frame `f` (its layers, wind and noise frequency; cloud_shape.z the extinction
// at density 1): PATH_GRID_XY^2 x (CLOUD_LAYERS x PATH_GRID_BINS) bounds on sigma_t (1/m), x
// fastest, then y, then layer l's bins at l x PATH_GRID_BINS; cells of cell_m with their
// corner at corner_m (planet frame xy). A layer without coverage and precipitation is 0.
std::vector<float> noise_majorant_grid(const gpu::FrameParams& f, const NoiseBlockBounds& noise,
                                       glm::vec2 corner_m, float cell_m);

// The lab's brick majorants: per brick of VOXEL_BRICK^3 voxels (x fastest, bricks per axis
// ceil(dims / VOXEL_BRICK)), the largest density a trilinear sample inside it reads (brick b
// spans grid coordinates [8 b + 1/2, 8 b + 8 1/2), so voxels 8 b to 8 b + 8) times `scale`,
// raised by 2^-10 for the atlas' half floats, which round to within 2^-11.
std::vector<float> lab_brick_majorants(const std::vector<float>& density, glm::ivec3 dims,
                                       float scale);

}  // namespace nephele

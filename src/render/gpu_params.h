// C++ view of the GPU structs (one definition: shaders/common/params_inc.glsl).
#pragma once

#include <glm/glm.hpp>

#include "common/params_inc.glsl"

namespace nephele::gpu {
static_assert(
    sizeof(FrameParams) == (96 + 4 * CLOUD_LAYERS + 6 * MAX_VOXEL_CLOUDS) * 16,
    "FrameParams must be 96 + 4 x CLOUD_LAYERS + 6 x MAX_VOXEL_CLOUDS vec4s (std140 layout)");
static_assert(sizeof(CloudLayerGpu) == 4 * 16);
static_assert(sizeof(VoxelCloudGpu) == 6 * 16);
static_assert(sizeof(StarGpu) == 2 * 16);
static_assert(sizeof(ParticleGpu) == 2 * 16);
static_assert(sizeof(ImpostorGpu) == 6 * 16);
static_assert(sizeof(ImpostorTileJob) == 2 * 16);
static_assert(sizeof(ParticleSplatGpu) == 16);
static_assert(sizeof(ParticleLightCloudGpu) == 2 * 16);
static_assert(alignof(FrameParams) <= 16);
}  // namespace nephele::gpu

#include "render/modules/ground_fog/ground_fog.h"

#include <cmath>
#include <cstring>

#include "render/glsl.h"
#include "render/gpu_params.h"
#include "render/media_light.h"
// The block's one definition and the fog's closed forms, as the shader has them.
#include "render/modules/ground_fog/ground_fog_gpu_inc.glsl"

namespace nephele {

namespace {
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"  // the shader's functions this file needs not
namespace fog {
using namespace nephele::glsl;
#include "common/ground_fog_inc.glsl"
}  // namespace fog
#pragma GCC diagnostic pop

constexpr const char* kBlockName = "GroundFogBlock";
constexpr float kDropletPhaseG = 0.8f;  // fog droplets (micrometres) scatter forward
}  // namespace

GroundFogModule::GroundFogModule(const ModuleContext& context) : set_(context.set) {
  for (gpu::Buffer& b : blocks_) {
    b = gpu::Buffer(context.ctx, sizeof(gpu::GroundFogGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    std::memset(b.data(), 0, sizeof(gpu::GroundFogGpu));  // no fog
  }
  // compose.comp and stars.comp declare the block whether or not a frame has fog: always bound.
  set_.bind_module_buffer(kBlockName, blocks_[0], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
}

void GroundFogModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  const gpu::FrameParams& params = frame.params;
  const GroundFogParams& p = frame.scene.ground_fog;
  gpu::GroundFogGpu block{};
  const bool fog = p.visibility_m > 0.0f && p.top_m > p.base_m;
  if (fog) {
    const fog::GroundFog f =
        fog::ground_fog_layer(p.base_m, p.top_m, p.softness_m, p.visibility_m, 1.0f);
    block.layer = glm::vec4(f.base_m, f.top_m, f.soft_m, f.sigma_t_per_m);
    const MediumLight light = medium_light(params);
    block.sun = light.sun;
    block.sky = glm::vec4(light.sky, kDropletPhaseG);
  }
  // The keyframes' fog (frame_params.cpp's set_conditions, per unit of the key light's
  // illuminance): its colour, and the distances where it begins and where it is whole.
  const bool keyframes = params.conditions_sky.w != 0.0f;
  if (keyframes) {
    block.keyframes = glm::vec4(glm::vec3(params.conditions_fog), 1.0f);
    block.keyframes_range_m =
        glm::vec4(params.conditions_disk_fog.w, params.conditions_fog.w, 0, 0);
  }
  std::memcpy(blocks_[frame.slot].data(), &block, sizeof(block));
  set_.bind_module_buffer(kBlockName, blocks_[frame.slot], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  plan.media = plan.media || fog || keyframes;
}

void GroundFogModule::add_passes(FrameGraph&, const FrameSetup&) {
  // No pass: compose reads the block as one of its media.
}

std::unique_ptr<RenderModule> make_ground_fog_module(const ModuleContext& context) {
  return std::make_unique<GroundFogModule>(context);
}

}  // namespace nephele

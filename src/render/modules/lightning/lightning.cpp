#include "render/modules/lightning/lightning.h"

#include <cmath>
#include <cstring>

#include "render/glsl.h"

namespace nephele {

namespace {
constexpr const char* kBlockName = "LightningBlock";
constexpr const char* kFlashesName = "LightningFlashes";
constexpr const char* kFlashesOutName = "LightningFlashesOut";
}  // namespace

gpu::LightningGpu lightning_block(const Scene& scene) {
  gpu::LightningGpu block{};
  const LightningParams& p = scene.lightning;
  const CloudParams& c = scene.clouds;
  const bool on = p.flashes_per_min > 0.0f && c.precipitation > 0.0f && c.coverage > 0.0f &&
                  c.model == CloudModel::Nephele;
  if (!on) return block;
  const double slot_s = double(glsl::LIGHTNING_SLOT_S);
  const double slot = std::floor(double(scene.time_s) / slot_s);
  const glm::vec2 eye_m(scene.camera.position_m);
  block.slot =
      glm::ivec4(int(slot), int(p.seed & 0x7fffffffu), int(std::floor(eye_m.x / kLightningTileM)),
                 int(std::floor(eye_m.y / kLightningTileM)));
  block.when = glm::vec4(
      float(double(scene.time_s) - slot * slot_s),
      glsl::lightning_candidate_chance(p.flashes_per_min, float(gpu::LIGHTNING_CANDIDATES),
                                       kLightningTileM * kLightningTileM, kLightningCoreM2),
      p.ground_share, 1.0f);
  block.cloud = glm::vec4(c.bottom_altitude_m, c.top_altitude_m, kLightningTileM, 0.0f);
  return block;
}

LightningModule::LightningModule(const ModuleContext& context)
    : ctx_(context.ctx), set_(context.set) {
  for (int i = 0; i <= gpu::kFramesInFlight; ++i) {
    blocks_[i] = gpu::Buffer(ctx_, sizeof(gpu::LightningGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    std::memset(blocks_[i].data(), 0, sizeof(gpu::LightningGpu));  // off
    flashes_[i] =
        gpu::Buffer(ctx_, sizeof(gpu::LightningFlashesGpu), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    std::memset(flashes_[i].data(), 0, sizeof(gpu::LightningFlashesGpu));
  }
  // Compose and the stars declare them whether or not it flashes: always bound.
  set_.bind_module_buffer(kBlockName, blocks_[0], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  set_.bind_module_buffer(kFlashesName, flashes_[0], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_module_buffer(kFlashesOutName, flashes_[0], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
}

void LightningModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  const gpu::LightningGpu block = lightning_block(frame.scene);
  on_ = block.when.w != 0.0f;
  std::memcpy(blocks_[frame.slot].data(), &block, sizeof(block));
  set_.bind_module_buffer(kBlockName, blocks_[frame.slot], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  set_.bind_module_buffer(kFlashesName, flashes_[frame.slot], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  set_.bind_module_buffer(kFlashesOutName, flashes_[frame.slot], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  plan.layers = plan.layers || on_;
}

void LightningModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  if (!on_) return;
  // Written before compose and the stars read the layers.
  graph.add_pass("lightning", {"weather_map", FrameGraph::kView}, {"layers"},
                 [this, timer = frame.timer](VkCommandBuffer cmd) {
                   if (!kernel_)
                     kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "lightning.comp.spv");
                   gpu::dispatch(cmd, *kernel_, timer(), "lightning", 64, 1, 1, 64, 1, 1);
                 });
}

std::unique_ptr<RenderModule> make_lightning_module(const ModuleContext& context) {
  return std::make_unique<LightningModule>(context);
}

}  // namespace nephele

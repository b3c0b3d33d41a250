#include "render/modules/light_shafts/light_shafts.h"

namespace nephele {

LightShaftsModule::LightShaftsModule(gpu::Context& ctx, gpu::DescriptorSet& set)
    : ctx_(ctx),
      set_(set),
      shafts_(ctx, 1, 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set_.bind_image(gpu::kLightShaftsOut, gpu::kLightShafts, shafts_);
}

bool LightShaftsModule::prepare(const Scene& scene, int width, int height) {
  if (light_shafts_method(scene.quality.light_shafts) != gpu::LIGHT_SHAFTS_VOLUMETRIC) return false;
  const uint32_t w = uint32_t((width + kLightShaftsDownsample - 1) / kLightShaftsDownsample);
  const uint32_t h = uint32_t((height + kLightShaftsDownsample - 1) / kLightShaftsDownsample);
  if (shafts_.width() != w || shafts_.height() != h) {
    ctx_.wait_queue_idle();  // a frame in flight may still read the old one
    shafts_ = gpu::Texture(ctx_, w, h, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                           VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    set_.bind_image(gpu::kLightShaftsOut, gpu::kLightShafts, shafts_);
  }
  return true;
}

void LightShaftsModule::record(VkCommandBuffer cmd, gpu::PassTimer& timer) {
  if (!kernel_) kernel_ = std::make_unique<gpu::Kernel>(ctx_, set_, "light_shafts.comp.spv");
  gpu::dispatch(cmd, *kernel_, timer, "light_shafts", shafts_.width(), shafts_.height(), 1, 8, 8,
                1);
}

void LightShaftsModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("shafts");  // read whether or not they are drawn this frame
  if (!frame.plan.shafts) return;
  std::vector<std::string> reads = cloud_field_resources();
  for (const char* r : {"cloud_layer", "ground_light", "terrain", "atmosphere", FrameGraph::kView})
    reads.push_back(r);
  graph.add_pass("light_shafts", reads, {"shafts"},
                 [timer = frame.timer, this](VkCommandBuffer cmd) { record(cmd, timer()); });
}

void LightShaftsModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  plan.shafts = prepare(frame.scene, frame.width, frame.height);
}

}  // namespace nephele

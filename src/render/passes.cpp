#include "render/passes.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "render/glsl.h"
#include "render/gpu_params.h"
#include "sky/stars.h"

namespace nephele {

GpuState::GpuState(gpu::Context& c)
    : ctx(c),
      set(c),
      layers(c, set),
      compose_kernels(c, set, "compose.comp.spv", 1, {1, 1, 1, 1, 1, 1}),
      stars_kernel(c, set, "stars.comp.spv"),
      reference_psi_kernel(c, set, "sky_reference_psi.comp.spv"),
      reference_sky_kernel(c, set, "sky_reference.comp.spv"),
      tonemap_kernel(c, set, "tonemap.comp.spv"),
      meter_kernel(c, set, "meter.comp.spv"),
      stars(c, sizeof(gpu::StarGpu) * std::max<size_t>(star_catalogue().size(), 1),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
      reference_psi(c, gpu::REFERENCE_TILE, gpu::REFERENCE_TILE, gpu::REFERENCE_SAMPLES,
                    VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set.bind_image(gpu::kReferencePsiOut, gpu::kReferencePsi, reference_psi);
  resize_reference_sky(1, 1);
  for (int i = 0; i < kSlots; ++i) {
    timers[i] = std::make_unique<gpu::PassTimer>(c, 64);
    frame_params[i] = gpu::Buffer(c, sizeof(gpu::FrameParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    meter[i] = gpu::Buffer(c, 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
    *static_cast<float*>(meter[i].data()) = std::nanf("");
  }
  set.bind_buffer(gpu::kStars, stars, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  auto* star_data = static_cast<gpu::StarGpu*>(stars.data());
  for (const Star& star : star_catalogue())
    star_data[star_count++] = {glm::vec4(star.dir_j2000, star.vmag),
                               glm::vec4(star.irradiance, star.b_v)};
  resize(1, 1);
}

bool GpuState::resize(int w, int h) {
  if (w == width && h == height) return false;
  for (int i = 0; i < gpu::kFramesInFlight; ++i) {
    color[i] = gpu::Texture(ctx, uint32_t(w), uint32_t(h), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                            VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    display[i] = gpu::Texture(ctx, uint32_t(w), uint32_t(h), 1, VK_FORMAT_R8G8B8A8_UNORM,
                              VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  }
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    for (const gpu::Texture* t : {&color[0], &color[1], &display[0], &display[1]})
      t->record_clear(cmd);
  });
  width = w;
  height = h;
  return true;
}

void GpuState::begin(VkCommandBuffer cmd, int index, const gpu::FrameParams& params) {
  slot = index;
  std::memcpy(frame_params[slot].data(), &params, sizeof(params));
  set.bind_buffer(gpu::kFrameParams, frame_params[slot], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  set.bind_buffer(gpu::kMeter, meter[slot], VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  const int image = slot == kOneOff ? 0 : slot;  // one-off work writes no final image
  set.bind_storage_image(gpu::kColorOut, color[image]);
  set.bind_storage_image(gpu::kColorRw, color[image]);
  set.bind_storage_image(gpu::kDisplayOut, display[image]);
  set.use(slot);
  timer = timers[slot].get();
  timer->reset(cmd);
  gpu::full_barrier(cmd);
}

void GpuState::resize_reference_sky(int w, int h) {
  if (reference_sky.width() == uint32_t(w) && reference_sky.height() == uint32_t(2 * h)) return;
  reference_sky = gpu::Texture(ctx, uint32_t(w), uint32_t(2 * h), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                               VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  set.bind_image(gpu::kReferenceSkyOut, gpu::kReferenceSky, reference_sky);
}

void pass_reference_sky(VkCommandBuffer cmd, GpuState& s, glm::ivec2 tile) {
  const gpu::DispatchConstants constants{glm::ivec4(tile, 0, 0)};
  gpu::dispatch(cmd, s.reference_psi_kernel, *s.timer, "reference_psi", gpu::REFERENCE_TILE,
                gpu::REFERENCE_TILE, gpu::REFERENCE_SAMPLES, 4, 4, 4, constants);
  gpu::dispatch(cmd, s.reference_sky_kernel, *s.timer, "reference_sky", gpu::REFERENCE_TILE,
                gpu::REFERENCE_TILE, 1, 8, 8, 1, constants);
}

void pass_stars(VkCommandBuffer cmd, GpuState& s, int layer) {
  gpu::dispatch(cmd, s.stars_kernel, *s.timer, "stars", uint32_t(s.star_count), 1, 1, 64, 1, 1,
                gpu::DispatchConstants{glm::ivec4(layer, 0, 0, 0)});
}

void pass_tonemap(VkCommandBuffer cmd, GpuState& s) {
  gpu::dispatch(cmd, s.tonemap_kernel, *s.timer, "tonemap", uint32_t(s.width),
                uint32_t(s.height), 1, 8, 8, 1);
}

void pass_meter(VkCommandBuffer cmd, GpuState& s) {
  gpu::dispatch(cmd, s.meter_kernel, *s.timer, "meter", 16, 16, 1, 16, 16, 1);
}

double metered_luminance(const GpuState& s, int slot) {
  const float mean_log = *static_cast<const float*>(s.meter[slot].data());
  return std::isfinite(mean_log) ? std::exp(double(mean_log)) : 0.0;
}

std::vector<int32_t> compose_variant(const gpu::FrameParams& params, SkyModel model, bool layers,
                                     bool media) {
  // Each feature exactly where compose.comp would find it in the parameters, so that a variant
  // draws what the full shader draws.
  return {model == SkyModel::Reference ? 1 : 0,
          params.conditions_sky.w != 0.0f ? 1 : 0,
          int(params.light_shafts.x) == gpu::LIGHT_SHAFTS_VOLUMETRIC ? 1 : 0,
          params.terrain_shape.z > 0.5f || params.host_scene.x > 0.5f ? 1 : 0,
          params.cirrus.y > 0.0f ? 1 : 0,
          layers ? 1 : 0,
          media ? 1 : 0};
}

void pass_compose(VkCommandBuffer cmd, GpuState& s, const std::vector<int32_t>& variant,
                  int layer) {
  gpu::dispatch(cmd, s.compose_kernels.get(variant), *s.timer, "compose", uint32_t(s.width),
                uint32_t(s.height), 1, 8, 8, 1, gpu::DispatchConstants{glm::ivec4(layer, 0, 0, 0)});
}

}  // namespace nephele

#include "render/modules/precipitation/precipitation.h"

#include <cstring>
#include <limits>

#include "render/glsl.h"
#include "render/gpu_params.h"
#include "render/media_light.h"
// The block's one definition and the medium's pure functions, as the shader has them.
#include "render/modules/precipitation/precipitation_gpu_inc.glsl"

namespace nephele {

namespace {
namespace precip = nephele::glsl;

constexpr const char* kBlockName = "PrecipitationBlock";
constexpr float kKoschmieder = 3.912f;  // -ln(0.02): the visibility's contrast threshold
}  // namespace

int precipitation_kind(std::string_view name) {
  if (name == "rain") return precip::PRECIPITATION_RAIN;
  if (name == "drizzle") return precip::PRECIPITATION_DRIZZLE;
  if (name == "snow") return precip::PRECIPITATION_SNOW;
  if (name == "sleet") return precip::PRECIPITATION_SLEET;
  return -1;
}

float precipitation_sigma_t_per_m(const PrecipitationParams& p) {
  const int kind = precipitation_kind(p.kind);
  return kind < 0 ? 0.0f : precip::precipitation_sigma_t_per_m(kind, p.rate_mm_per_h);
}

float precipitation_visibility_m(const PrecipitationParams& p) {
  const float sigma = precipitation_sigma_t_per_m(p);
  return sigma > 0.0f ? kKoschmieder / sigma : std::numeric_limits<float>::infinity();
}

PrecipitationModule::PrecipitationModule(const ModuleContext& context) : set_(context.set) {
  for (gpu::Buffer& b : blocks_) {
    b = gpu::Buffer(context.ctx, sizeof(gpu::PrecipitationGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
    std::memset(b.data(), 0, sizeof(gpu::PrecipitationGpu));  // none
  }
  // compose.comp and stars.comp declare the block whether or not a frame has any: always bound.
  set_.bind_module_buffer(kBlockName, blocks_[0], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
}

void PrecipitationModule::prepare(const FramePrepare& frame, FramePlan& plan) {
  const PrecipitationParams& p = frame.scene.precipitation;
  const float top_m = frame.scene.clouds.bottom_altitude_m;
  gpu::PrecipitationGpu block{};
  const float sigma = precipitation_sigma_t_per_m(p);
  const bool falls = sigma > 0.0f && p.bottom_m < top_m;
  if (falls) {
    block.fall = glm::vec4(p.bottom_m, top_m, sigma,
                           precip::precipitation_phase_g(precipitation_kind(p.kind)));
    const MediumLight light = medium_light(frame.params);
    block.sun = light.sun;
    block.sky = glm::vec4(light.sky, p.shafts ? 1.0f : 0.0f);
  }
  std::memcpy(blocks_[frame.slot].data(), &block, sizeof(block));
  set_.bind_module_buffer(kBlockName, blocks_[frame.slot], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  plan.media = plan.media || falls;
}

void PrecipitationModule::add_passes(FrameGraph&, const FrameSetup&) {
  // No pass: compose reads the block as one of its media.
}

std::unique_ptr<RenderModule> make_precipitation_module(const ModuleContext& context) {
  return std::make_unique<PrecipitationModule>(context);
}

}  // namespace nephele

#include "render/passes.h"

#include <algorithm>
#include <cstring>

#include "render/glsl.h"
#include "render/gpu_params.h"
#include "sky/stars.h"

namespace nephele {

GpuState::GpuState(gpu::Context& c)
    : ctx(c),
      set(c),
      clouds_default_kernel(c, set, "clouds.comp.spv", {0}),
      clouds_baseline_kernel(c, set, "clouds.comp.spv", {1}),
      resolve_kernel(c, set, "resolve.comp.spv"),
      compose_kernel(c, set, "compose.comp.spv", {0}),
      compose_reference_kernel(c, set, "compose.comp.spv", {1}),
      march_range_kernel(c, set, "march_range.comp.spv"),
      stars_kernel(c, set, "stars.comp.spv"),
      reference_psi_kernel(c, set, "sky_reference_psi.comp.spv"),
      reference_sky_kernel(c, set, "sky_reference.comp.spv"),
      cloud_profile_kernel(c, set, "cloud_profile.comp.spv"),
      ground_light_default_kernel(c, set, "ground_light.comp.spv", {0}),
      ground_light_baseline_kernel(c, set, "ground_light.comp.spv", {1}),
      tonemap_kernel(c, set, "tonemap.comp.spv"),
      stars(c, sizeof(gpu::StarGpu) * std::max<size_t>(star_catalogue().size(), 1),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT),
      ground_light(c, 1, 1, 1, VK_FORMAT_R32_SFLOAT),
      reference_psi(c, gpu::REFERENCE_TILE, gpu::REFERENCE_TILE, gpu::REFERENCE_SAMPLES,
                    VK_FORMAT_R32G32B32A32_SFLOAT, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE) {
  set.bind_image(gpu::kReferencePsiOut, gpu::kReferencePsi, reference_psi);
  for (gpu::Texture* t : {&dome_a, &dome_b})
    *t = gpu::Texture(c, kSkyDomeSize, kSkyDomeSize, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                      VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  resize_reference_sky(1, 1);
  set.bind_image(gpu::kGroundLightOut, gpu::kGroundLight, ground_light);
  for (int i = 0; i < kSlots; ++i) {
    timers[i] = std::make_unique<gpu::PassTimer>(c, 16);
    frame_params[i] = gpu::Buffer(c, sizeof(gpu::FrameParams), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  }
  set.bind_buffer(gpu::kStars, stars, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  auto* star_data = static_cast<gpu::StarGpu*>(stars.data());
  for (const Star& star : star_catalogue())
    star_data[star_count++] = {glm::vec4(star.dir_j2000, star.vmag),
                               glm::vec4(star.irradiance, star.b_v)};
  resize(1, 1, 1, 1);
}

void GpuState::resize(int w, int h, int cloud_w, int cloud_h) {
  if (w == width && h == height && cloud_w == cloud_width && cloud_h == cloud_height) return;
  const auto cloud_image = [&] {
    return gpu::Texture(ctx, uint32_t(cloud_w), uint32_t(cloud_h), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                        VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  };
  // Room for a still image's march of every pixel.
  march_a = cloud_image();
  march_b = cloud_image();
  range_lo = cloud_image();
  range_hi = cloud_image();
  for (int i = 0; i < 2; ++i) {
    clouds_a[i] = cloud_image();
    clouds_b[i] = cloud_image();
  }
  for (int i = 0; i < gpu::kFramesInFlight; ++i) {
    color[i] = gpu::Texture(ctx, uint32_t(w), uint32_t(h), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                            VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
    display[i] = gpu::Texture(ctx, uint32_t(w), uint32_t(h), 1, VK_FORMAT_R8G8B8A8_UNORM,
                              VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  }
  bind_march(false);
  set.bind_storage_image(gpu::kRangeLo, range_lo);
  set.bind_storage_image(gpu::kRangeHi, range_hi);
  // Defined contents: filters read neighbours of the texels a frame writes.
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    for (const gpu::Texture* t : {&march_a, &march_b, &range_lo, &range_hi, &clouds_a[0],
                                  &clouds_a[1], &clouds_b[0], &clouds_b[1], &color[0], &color[1],
                                  &display[0], &display[1]})
      t->record_clear(cmd);
  });
  current = 1;
  swap_history();
  width = w;
  height = h;
  cloud_width = cloud_w;
  cloud_height = cloud_h;
}

void GpuState::begin(VkCommandBuffer cmd, int index, const gpu::FrameParams& params) {
  slot = index;
  std::memcpy(frame_params[slot].data(), &params, sizeof(params));
  set.bind_buffer(gpu::kFrameParams, frame_params[slot], VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER);
  const int image = slot == kOneOff ? 0 : slot;  // one-off work writes no final image
  set.bind_storage_image(gpu::kColorOut, color[image]);
  set.bind_storage_image(gpu::kColor, color[image]);
  set.bind_storage_image(gpu::kDisplayOut, display[image]);
  set.use(slot);
  timer = timers[slot].get();
  timer->reset(cmd);
  gpu::full_barrier(cmd);
}

void GpuState::bind_march(bool sky_dome) {
  set.bind_image(gpu::kMarchAOut, gpu::kMarchA, sky_dome ? dome_a : march_a);
  set.bind_image(gpu::kMarchBOut, gpu::kMarchB, sky_dome ? dome_b : march_b);
}

void GpuState::resize_reference_sky(int w, int h) {
  if (reference_sky.width() == uint32_t(w) && reference_sky.height() == uint32_t(2 * h)) return;
  reference_sky = gpu::Texture(ctx, uint32_t(w), uint32_t(2 * h), 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                               VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE);
  set.bind_image(gpu::kReferenceSkyOut, gpu::kReferenceSky, reference_sky);
}

void GpuState::swap_history() {
  current = 1 - current;
  set.bind_image(gpu::kCloudsAOut, gpu::kCloudsA, clouds_a[current]);
  set.bind_image(gpu::kCloudsBOut, gpu::kCloudsB, clouds_b[current]);
  set.bind_sampled_image(gpu::kHistoryA, clouds_a[1 - current]);
  set.bind_sampled_image(gpu::kHistoryB, clouds_b[1 - current]);
}

namespace {
const gpu::Kernel& clouds_kernel(const GpuState& s, MarchMode mode) {
  return mode == MarchMode::Baseline ? s.clouds_baseline_kernel : s.clouds_default_kernel;
}
}  // namespace

void pass_clouds(VkCommandBuffer cmd, GpuState& s, MarchMode mode, int rows) {
  const gpu::Kernel& kernel = clouds_kernel(s, mode);
  const auto blocks = [&](int n) { return uint32_t((n + s.stride - 1) / s.stride); };
  gpu::dispatch(cmd, kernel, s.set, *s.timer, "clouds", blocks(s.cloud_width),
                rows < 0 ? blocks(s.cloud_height) : uint32_t(rows), 1, 8, 8, 1);
}

void pass_sky_dome(VkCommandBuffer cmd, GpuState& s, MarchMode mode) {
  gpu::dispatch(cmd, clouds_kernel(s, mode), s.set, *s.timer, "sky_dome", kSkyDomeSize,
                kSkyDomeSize, 1, 8, 8, 1);
}

void pass_cloud_profile(VkCommandBuffer cmd, GpuState& s) {
  gpu::dispatch(cmd, s.cloud_profile_kernel, s.set, *s.timer, "cloud_profile", kCloudProfileSize,
                kCloudProfileSize, 1, 8, 8, 1);
}

void pass_march_range(VkCommandBuffer cmd, GpuState& s) {
  const auto blocks = [&](int n) { return uint32_t((n + s.stride - 1) / s.stride); };
  gpu::dispatch(cmd, s.march_range_kernel, s.set, *s.timer, "march_range", blocks(s.cloud_width),
                blocks(s.cloud_height), 1, 8, 8, 1);
}

void pass_resolve(VkCommandBuffer cmd, GpuState& s) {
  gpu::dispatch(cmd, s.resolve_kernel, s.set, *s.timer, "resolve", uint32_t(s.cloud_width),
                uint32_t(s.cloud_height), 1, 8, 8, 1);
}

void pass_reference_sky(VkCommandBuffer cmd, GpuState& s) {
  gpu::dispatch(cmd, s.reference_psi_kernel, s.set, *s.timer, "reference_psi", gpu::REFERENCE_TILE,
                gpu::REFERENCE_TILE, gpu::REFERENCE_SAMPLES, 4, 4, 4);
  gpu::dispatch(cmd, s.reference_sky_kernel, s.set, *s.timer, "reference_sky", gpu::REFERENCE_TILE,
                gpu::REFERENCE_TILE, 1, 8, 8, 1);
}

void pass_stars(VkCommandBuffer cmd, GpuState& s) {
  gpu::dispatch(cmd, s.stars_kernel, s.set, *s.timer, "stars", uint32_t(s.star_count), 1, 1, 64, 1,
                1);
}

void pass_ground_light(VkCommandBuffer cmd, GpuState& s, MarchMode mode) {
  gpu::dispatch(cmd,
                mode == MarchMode::Baseline ? s.ground_light_baseline_kernel
                                            : s.ground_light_default_kernel,
                s.set, *s.timer, "ground_light", 16, 16, 1, 16, 16, 1);
}

void pass_tonemap(VkCommandBuffer cmd, GpuState& s) {
  gpu::dispatch(cmd, s.tonemap_kernel, s.set, *s.timer, "tonemap", uint32_t(s.width),
                uint32_t(s.height), 1, 8, 8, 1);
}

void pass_compose(VkCommandBuffer cmd, GpuState& s, SkyModel model) {
  gpu::dispatch(cmd, model == SkyModel::Reference ? s.compose_reference_kernel : s.compose_kernel,
                s.set, *s.timer, "compose", uint32_t(s.width), uint32_t(s.height), 1, 8, 8, 1);
}

}  // namespace nephele

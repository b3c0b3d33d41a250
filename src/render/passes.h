// The render passes: each one .comp shader and one short function that records it.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gpu/context.h"
#include "gpu/kernel.h"
#include "gpu/resources.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"

namespace nephele {

// The sky dome (sky_dome_ray): kSkyDomeSize^2 directions of equal solid angle over the
// observer's upper hemisphere, where sky_cover_fraction is measured.
constexpr uint32_t kSkyDomeSize = 64;
// The cloud profile (cloud_profile.comp): altitude bins, and points per side of its grid. It
// writes the sky dome's image, so the two are one size.
constexpr uint32_t kCloudProfileSize = kSkyDomeSize;

// Everything the passes read and write.
struct GpuState {
  // Per frame in flight (slots 0 .. kFramesInFlight - 1), and one more for one-off work.
  static constexpr int kOneOff = gpu::DescriptorSet::kOneOff;
  static constexpr int kSlots = gpu::kFramesInFlight + 1;

  explicit GpuState(gpu::Context& ctx);
  // Starts recording a frame of `slot` into `cmd`: its parameters, bindings and timestamps
  // (the command buffers that used the slot before must have completed), and a barrier after
  // everything submitted before.
  void begin(VkCommandBuffer cmd, int slot, const gpu::FrameParams& params);
  // One-off work: records `record` after begin(kOneOff, params), submits it, waits, and
  // returns the passes' timings.
  template <typename F>
  std::vector<std::pair<std::string, double>> run_once(const gpu::FrameParams& params, F&& record) {
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      begin(cmd, kOneOff, params);
      record(cmd);
    });
    return timers[kOneOff]->results();
  }
  // (Re)allocates the per-pixel buffers: the image, the cloud buffer and the marched samples.
  void resize(int width, int height, int cloud_width, int cloud_height);
  // The cloud buffer just written becomes the history of the next frame.
  void swap_history();
  // Points the clouds pass's outputs at the sky dome's images (true) or the marched samples.
  void bind_march(bool sky_dome);

  gpu::Context& ctx;
  gpu::DescriptorSet set;
  gpu::Kernel clouds_default_kernel, clouds_baseline_kernel, resolve_kernel;
  gpu::Kernel compose_kernel, compose_reference_kernel, march_range_kernel;
  gpu::Kernel stars_kernel;
  gpu::Kernel reference_psi_kernel, reference_sky_kernel, cloud_profile_kernel;
  gpu::Kernel ground_light_default_kernel, ground_light_baseline_kernel, tonemap_kernel;
  std::unique_ptr<gpu::PassTimer> timers[kSlots];
  gpu::PassTimer* timer = nullptr;  // the slot's, since begin()
  gpu::Buffer frame_params[kSlots];
  int slot = kOneOff;               // since begin()
  gpu::Buffer stars;  // the star catalogue (StarGpu), written once
  int star_count = 0;
  gpu::Texture ground_light;
  // The reference sky (bindings_inc.glsl): one tile's Psi_ms, and the sky per pixel (resized to
  // the image only when the reference is rendered).
  gpu::Texture reference_psi, reference_sky;
  void resize_reference_sky(int width, int height);
  // Per-pixel images (bindings_inc.glsl): the marched samples (A, B), the cloud buffer of this
  // frame and of the previous one (history), and the final image.
  gpu::Texture march_a, march_b, range_lo, range_hi;
  gpu::Texture dome_a, dome_b;  // the clouds pass over the sky dome (bind_march)
  gpu::Texture clouds_a[2], clouds_b[2];
  // The final images of each frame in flight (index: slot; kOneOff's are unused): linear HDR,
  // and the display image (tonemap.comp).
  gpu::Texture color[kSlots], display[kSlots];
  int current = 0;  // index of this frame's cloud buffer
  int width = 0, height = 0, cloud_width = 0, cloud_height = 0;
  int stride = 1;  // this frame's march stride
};

// Every row of blocks, or `rows` of them from FrameParams::cloud_band.x.
void pass_clouds(VkCommandBuffer cmd, GpuState& s, MarchMode mode, int rows = -1);
// The clouds pass over the sky dome (FrameParams::steps.w = PROJECTION_SKY_DOME), into dome_a
// and dome_b (bind_march(true) first).
void pass_sky_dome(VkCommandBuffer cmd, GpuState& s, MarchMode mode);
// The cloud density averaged per altitude bin (cloud_profile.comp), into dome_a
// (bind_march(true) first).
void pass_cloud_profile(VkCommandBuffer cmd, GpuState& s);
void pass_march_range(VkCommandBuffer cmd, GpuState& s);
void pass_resolve(VkCommandBuffer cmd, GpuState& s);
// The clouds' mean diffuse transmittance over the ground around the camera (one texel).
void pass_ground_light(VkCommandBuffer cmd, GpuState& s, MarchMode mode);
void pass_compose(VkCommandBuffer cmd, GpuState& s, SkyModel model);
// One tile (FrameParams::reference_tile) of the brute-force reference sky.
void pass_reference_sky(VkCommandBuffer cmd, GpuState& s);
void pass_stars(VkCommandBuffer cmd, GpuState& s);
// The display image from the final one: exposure, ACES fit, sRGB.
void pass_tonemap(VkCommandBuffer cmd, GpuState& s);

}  // namespace nephele

// The render passes: each one .comp shader and one short function that records it.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "gpu/context.h"
#include "gpu/kernel.h"
#include "gpu/kernel_variants.h"
#include "gpu/resources.h"
#include "nephele/image.h"
#include "nephele/scene.h"
#include "render/gpu_params.h"
#include "render/image_layers.h"

namespace nephele {

// Everything the passes read and write.
// Reads an RGBA image of 32-bit (or, with `half`, 16-bit) float texels back to the host.
Image download(gpu::Context& ctx, const gpu::Texture& texture, bool half);

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
  // (Re)allocates the final images; true when they were.
  bool resize(int width, int height);

  gpu::Context& ctx;
  gpu::DescriptorSet set;
  ImageLayers layers;  // the layers compose blends over the clouds (image_layers.h)
  gpu::KernelVariants compose_kernels;  // compose.comp's, by compose_variant
  gpu::Kernel stars_kernel;
  gpu::Kernel reference_psi_kernel, reference_sky_kernel, tonemap_kernel, meter_kernel;
  std::unique_ptr<gpu::PassTimer> timers[kSlots];
  gpu::PassTimer* timer = nullptr;  // the slot's, since begin()
  gpu::Buffer frame_params[kSlots];
  gpu::Buffer meter[kSlots];  // meter.comp's reading of the slot's last frame (host-visible)
  int slot = kOneOff;               // since begin()
  gpu::Buffer stars;  // the star catalogue (StarGpu), written once
  int star_count = 0;
  // The reference sky (bindings_inc.glsl): one tile's Psi_ms, and the sky per pixel (resized to
  // the image only when the reference is rendered).
  gpu::Texture reference_psi, reference_sky;
  void resize_reference_sky(int width, int height);
  // The final images of each frame in flight (index: slot; kOneOff's are unused): linear HDR,
  // and the display image (tonemap.comp).
  gpu::Texture color[kSlots], display[kSlots];
  int width = 0, height = 0;
};

// compose.comp's specialization constants for a frame: the sky model's (REFERENCE) and the
// features it uses, from its parameters, whether a translucent layer draws and whether a
// medium's module is on (FramePlan::layers, media).
std::vector<int32_t> compose_variant(const gpu::FrameParams& params, SkyModel model, bool layers,
                                     bool media);
// `layer`: the film layer written (FramePlan::film_layer; 0 the image).
void pass_compose(VkCommandBuffer cmd, GpuState& s, const std::vector<int32_t>& variant, int layer);
// The tile of the brute-force reference sky whose first pixel is `tile`.
void pass_reference_sky(VkCommandBuffer cmd, GpuState& s, glm::ivec2 tile);
void pass_stars(VkCommandBuffer cmd, GpuState& s, int layer);
// The display image from the final one: exposure, ACES fit, sRGB.
void pass_tonemap(VkCommandBuffer cmd, GpuState& s);
// The exposure meter (meter.comp) of the final image, into s.meter[s.slot].
void pass_meter(VkCommandBuffer cmd, GpuState& s);
// Its reading of the last frame recorded in `slot` once that completed: the log-average
// luminance (cd/m^2).
double metered_luminance(const GpuState& s, int slot);

}  // namespace nephele

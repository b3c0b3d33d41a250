// The clouds module: the noise clouds' march (clouds.comp, seed 000 and 002), its temporal
// reconstruction (march_range.comp, resolve.comp) and the light the clouds let through to the
// ground (ground_light.comp), with the per-pixel images they own: the marched samples, the
// cloud buffer of this frame and the previous one (the history), and the sky dome's images
// (the same march over the observer's hemisphere, and the cloud profile). Another cloud model
// is another module beside this one.
#pragma once

#include "gpu/kernel.h"
#include "gpu/kernel_variants.h"
#include "nephele/scene.h"
#include "render/render_module.h"

namespace nephele {

// The sky dome (sky_dome_ray): kSkyDomeSize^2 directions of equal solid angle over the
// observer's upper hemisphere, where sky_cover_fraction is measured.
constexpr uint32_t kSkyDomeSize = 64;
// The cloud profile (cloud_profile.comp): altitude bins, and points per side of its grid. It
// writes the sky dome's image, so the two are one size.
constexpr uint32_t kCloudProfileSize = kSkyDomeSize;

// What a frame reprojecting its history (params.cloud_grid.w) marches itself: x, y the columns
// (from, how many) and z, w the rows where the previous frame's camera did not see beyond its
// sides or its top and bottom (what a turning or pitching camera brings in: the history has
// nothing there, and interpolating this frame's samples draws blocks), a pixel wider each
// side; none (0) without history, or over a quarter of the buffer. Sampled every 2 pixels.
glm::ivec4 entering_region(const gpu::FrameParams& params);

class CloudsModule : public RenderModule {
 public:
  CloudsModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // (Re)allocates the cloud buffer and the marched samples at `width` x `height`; true when
  // they were. The history is lost, unless `carry_history`: then the last frame's cloud buffer
  // (a still's, at the image's resolution) is box-filtered down into the next frame's history,
  // so that an animation continues from the still instead of starting afresh.
  bool resize(int width, int height, bool carry_history = false);
  // The cloud buffer just written becomes the history of the next frame.
  void swap_history();
  // The contract's (render_module.h): swaps the history.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  // Points the march's outputs at the sky dome's images (true) or the marched samples.
  void bind_march(bool sky_dome);
  void set_stride(int stride) { stride_ = stride; }

  // clouds.comp's specialization constants for a frame of these parameters: the march mode,
  // whether there are voxel clouds and which light the clouds scatter.
  static std::vector<int32_t> march_variant(MarchMode mode, const gpu::FrameParams& params);
  // The march of the frame of `params`: every row of blocks, or `rows` of them from row
  // `first_row` (a band of a still; pushed, DispatchConstants).
  void record_march(VkCommandBuffer cmd, gpu::PassTimer& timer, MarchMode mode,
                    const gpu::FrameParams& params, int rows = -1, int first_row = 0);
  // The march range and the resolve: the cloud buffer of this frame.
  void record_reconstruction(VkCommandBuffer cmd, gpu::PassTimer& timer);
  // Instead of the march and the reconstruction when the scene has no volumetric clouds: this
  // frame's cloud buffers as a clear sky's march leaves them (nothing scattered, transmittance
  // 1, no haze, the ground unshadowed).
  void record_clear_sky(VkCommandBuffer cmd);
  // The clouds' mean diffuse transmittance over the ground around the camera (one texel).
  void record_ground_light(VkCommandBuffer cmd, gpu::PassTimer& timer, MarchMode mode);
  // The same with no clouds: all of the sky's light.
  void record_clear_ground_light(VkCommandBuffer cmd);
  // The march over the sky dome (FrameParams::steps.w = PROJECTION_SKY_DOME) into dome_a and
  // dome_b, and the cloud profile into dome_a (bind_march(true) first).
  void record_sky_dome(VkCommandBuffer cmd, gpu::PassTimer& timer, MarchMode mode,
                       const gpu::FrameParams& params);
  void record_profile(VkCommandBuffer cmd, gpu::PassTimer& timer);

  int width() const { return width_; }
  int height() const { return height_; }
  int stride() const { return stride_; }
  const gpu::Texture& cloud_buffer() const { return clouds_a_[current_]; }  // this frame's
  const gpu::Texture& dome() const { return dome_a_; }

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::KernelVariants march_;
  gpu::Kernel range_, resolve_, profile_;
  gpu::Kernel ground_default_, ground_baseline_;
  gpu::Texture march_a_, march_b_, range_lo_, range_hi_, dome_a_, dome_b_, ground_light_;
  gpu::Texture clouds_a_[2], clouds_b_[2];
  int current_ = 0;  // index of this frame's cloud buffer
  int width_ = 0, height_ = 0, stride_ = 1;
};

}  // namespace nephele

// The sky-view module: Hillaire's sky-view LUT and aerial-perspective volume (sky_view.comp,
// aerial_perspective.comp), which depend on the light, the camera's position and the
// atmosphere only. A pair is reused while the camera stays within kSkyViewReuseM and the light
// within kSkyViewReuseSunDeg (sky_view_reusable); its successor is built into a second pair,
// a band of rows a frame over kSkyViewBuildFrames frames (the LUT's in the first half, the
// volume's in the second), while the old pair is read, so a moving camera never pays for a
// whole pair in one frame. Still images, the first frame and a new atmosphere build the pair
// at once.
#pragma once

#include <optional>

#include "gpu/kernel.h"
#include "render/frame_params.h"
#include "render/gpu_params.h"
#include "render/render_module.h"

namespace nephele {

// Sky-view LUT (Hillaire 2020, 5.3): azimuth x elevation texels per table; the image stacks two
// tables (radiance, sun-lit ground), so it is kSkyViewWidth x 2 kSkyViewHeight.
constexpr uint32_t kSkyViewWidth = 256;
constexpr uint32_t kSkyViewHeight = 108;
// Frames over which a pair is built: a camera flying at 100 m/s and 20 frames/s leaves the
// reuse distance every 10 frames.
constexpr int kSkyViewBuildFrames = 6;

class SkyViewModule : public RenderModule {
 public:
  SkyViewModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

  // Decides this frame's work; sets params.sky_view_up/forward (the pair read) and
  // sky_view_build_up/forward (the pair built), and the bindings.
  void prepare(bool still, gpu::FrameParams& params);
  // The contract's (render_module.h): the above with the frame's values.
  void prepare(const FramePrepare& frame, FramePlan& plan) override;
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);
  // The table the frames read (its sky rows, then its ground rows).
  const gpu::Texture& lut() const { return luts_[read_index_]; }
  // The atmosphere changed: the pairs built are no longer valid.
  void invalidate() { read_.reset(), building_.reset(); }

 private:
  struct Built {
    SkyViewKey key;
    glm::vec4 up, forward;  // the LUT's frame
  };
  gpu::DescriptorSet& set_;
  gpu::Kernel lut_kernel_, volume_kernel_;
  gpu::Texture luts_[2], volumes_[2];
  int read_index_ = 0;
  std::optional<Built> read_;      // the pair read, index read_index_
  std::optional<Built> building_;  // the pair being built, 1 - read_index_
  int step_ = 0;                   // of its kSkyViewBuildFrames
  glm::ivec4 rows_{0};             // this frame's bands (FrameParams::sky_view_rows)
};

}  // namespace nephele

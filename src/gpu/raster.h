// Raster passes: a render pass over colour attachments kept in VK_IMAGE_LAYOUT_GENERAL (the
// layout every nephele image lives in, so compute passes sample them after), cleared to zero
// (or kept, with the areas drawn cleared), drawn with premultiplied-alpha "over" blending (or
// none, with a depth buffer) by graphics pipelines of embedded vertex and fragment shaders, each
// with the bindings its shaders use (PassInterface) and per-draw push constants (DrawConstants).
// The vertex shaders make their geometry from gl_VertexIndex: there are no vertex buffers.
#pragma once

#include <vulkan/vulkan.h>

#include <memory>
#include <string>
#include <vector>

#include "common/push_constants_inc.glsl"  // DrawConstants, DispatchConstants
#include "gpu/context.h"
#include "gpu/kernel.h"
#include "gpu/resources.h"

namespace nephele::gpu {

// A pipeline's shaders: embedded SPIR-V names ("particles.vert.spv"), and the fragment
// shader's integer specialization constants 0..n-1.
struct RasterShaders {
  std::string vert, frag;
  std::vector<int32_t> frag_specialization = {};
};

// One draw: `vertex_count` vertices from `first_vertex` with `pipeline`, its constants, into
// `area` of the targets (viewport and scissor; width 0 = all of them), cleared first when
// `clear_area`.
struct RasterDraw {
  int pipeline = 0;
  uint32_t first_vertex = 0, vertex_count = 0;
  DrawConstants constants{};
  VkRect2D area{};
  bool clear_area = false;
};

// A depth buffer (VK_FORMAT_D32_SFLOAT) for a raster pass with depth: cleared when the pass
// begins, tested and written in it, never read after.
class DepthTarget {
 public:
  DepthTarget() = default;
  DepthTarget(Context& ctx, uint32_t width, uint32_t height);
  ~DepthTarget() { reset(); }
  DepthTarget(DepthTarget&& other) noexcept { *this = std::move(other); }
  DepthTarget& operator=(DepthTarget&& other) noexcept;
  VkImageView view() const { return view_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }

 private:
  void reset();
  VkDevice device_ = VK_NULL_HANDLE;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  uint32_t width_ = 0, height_ = 0;
};

class RasterPass {
 public:
  // `clear`: the targets are cleared to zero when the pass begins, else kept. `with_depth`: the
  // pass draws opaque geometry (no blending) tested against a DepthTarget, reversed: cleared to
  // 0, the nearer (larger) depth kept. Throws RuntimeError when the queue cannot draw or a
  // format cannot be a (blended) attachment.
  RasterPass(Context& ctx, DescriptorSet& set, const std::vector<VkFormat>& formats,
             bool clear, const std::vector<RasterShaders>& pipelines, bool with_depth = false);
  ~RasterPass();
  RasterPass(const RasterPass&) = delete;
  RasterPass& operator=(const RasterPass&) = delete;

  // Records the draws into `targets` (one per format, all the same size: the part drawn,
  // Texture::render_target) and makes the result visible to compute shaders and transfers;
  // timed as `name`. With depth, `depth` is the pass's depth buffer, of the targets' size.
  void record(VkCommandBuffer cmd, PassTimer& timer, const std::string& name,
              const std::vector<RenderTarget>& targets, const std::vector<RasterDraw>& draws,
              const DepthTarget* depth = nullptr);

 private:
  VkFramebuffer framebuffer_for(const std::vector<RenderTarget>& targets, const DepthTarget* depth);
  VkDevice device_;
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  std::vector<std::unique_ptr<PassInterface>> interfaces_;  // one a pipeline, its layout
  std::vector<VkPipeline> pipelines_;
  size_t attachments_ = 0;
  bool with_depth_ = false;
  // Framebuffers by their image views; a target replaced (resized) gets a new one, the old
  // ones are destroyed with the pass (a handful over a viewer session's resizes).
  struct Cached {
    std::vector<VkImageView> views;
    uint32_t width, height;
    VkFramebuffer framebuffer;
  };
  std::vector<Cached> framebuffers_;
};

}  // namespace nephele::gpu

// Raster passes: a render pass over colour attachments kept in VK_IMAGE_LAYOUT_GENERAL (the
// layout every nephele image lives in, so compute passes sample them after), cleared to zero
// and drawn with premultiplied-alpha "over" blending, and a graphics pipeline of embedded
// vertex and fragment shaders with the shared descriptor set. The vertex shader makes its
// geometry from gl_VertexIndex: there are no vertex buffers.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/kernel.h"
#include "gpu/resources.h"

namespace nephele::gpu {

class RasterPass {
 public:
  // Throws RuntimeError when the queue cannot draw or a format cannot be a blended attachment.
  RasterPass(Context& ctx, const DescriptorSet& set, const std::string& vert_spv,
             const std::string& frag_spv, const std::vector<VkFormat>& formats);
  ~RasterPass();
  RasterPass(const RasterPass&) = delete;
  RasterPass& operator=(const RasterPass&) = delete;

  // Clears `targets` (one per format, all the same size), draws `vertex_count` vertices into
  // them, and makes the result visible to compute shaders; timed as `name`.
  void record(VkCommandBuffer cmd, const DescriptorSet& set, PassTimer& timer,
              const std::string& name, const std::vector<const Texture*>& targets,
              uint32_t vertex_count);

 private:
  VkFramebuffer framebuffer_for(const std::vector<const Texture*>& targets);
  VkDevice device_;
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
  size_t attachments_ = 0;
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

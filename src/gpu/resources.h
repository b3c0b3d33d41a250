// GPU buffers and images with their memory; RAII, move-only.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <exception>
#include <utility>
#include <vector>

#include "gpu/context.h"

namespace nephele::gpu {

// For a constructor that creates Vulkan objects one after another: where it throws part way
// (out of memory, a format the device lacks), `undo` (the class's reset()) frees what was made,
// since no destructor runs for an object whose constructor threw. Declared first in its body.
template <class Undo>
class UndoOnThrow {
 public:
  explicit UndoOnThrow(Undo undo) : undo_(std::move(undo)) {}
  ~UndoOnThrow() {
    if (std::uncaught_exceptions() > exceptions_) undo_();
  }
  UndoOnThrow(const UndoOnThrow&) = delete;
  UndoOnThrow& operator=(const UndoOnThrow&) = delete;

 private:
  Undo undo_;
  int exceptions_ = std::uncaught_exceptions();
};

// vkCreateImage into `image`, and device-local memory for it (vkAllocateMemory into `memory`,
// vkBindImageMemory); each handle stored as soon as it is made (below).
void allocate_device_local_image(Context& ctx, const VkImageCreateInfo& info, VkImage& image,
                                 VkDeviceMemory& memory);
// The steps of a device-local image after its VkImageCreateInfo: vkCreateImage into `image`,
// device-local memory for it (vkAllocateMemory into `memory`, vkBindImageMemory) and a view of
// every mip level (create_image_view into `view`). Each handle is stored as soon as it is made,
// so where a step throws, the owner's reset() (UndoOnThrow) frees those made before it.
void create_device_local_image(Context& ctx, const VkImageCreateInfo& info,
                               VkImageAspectFlags aspect, VkImage& image, VkDeviceMemory& memory,
                               VkImageView& view);
// A view of `image`, made from `info`: its format, `aspect`, mip levels 0 to `levels` - 1, and
// its array layers `first_layer` to `first_layer + layers - 1`; `array` makes it a 2D array
// view (else 1D, 2D or 3D as the image).
VkImageView create_image_view(VkDevice device, VkImage image, const VkImageCreateInfo& info,
                              VkImageAspectFlags aspect, uint32_t levels, bool array = false,
                              uint32_t first_layer = 0, uint32_t layers = 1);

// What a raster pass draws into (gpu/raster.h): a 2D image view, and the part of it drawn, its
// top-left width x height texels.
struct RenderTarget {
  VkImageView view = VK_NULL_HANDLE;
  uint32_t width = 0, height = 0;
};

// The number of layers of a 2D array texture (Texture's constructor).
struct ArrayLayers {
  uint32_t count = 1;
};

// A host-visible, coherent buffer (storage, uniform or transfer), persistently mapped.
class Buffer {
 public:
  Buffer() = default;
  Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage);
  ~Buffer() { reset(); }
  Buffer(Buffer&& other) noexcept { *this = std::move(other); }
  Buffer& operator=(Buffer&& other) noexcept;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  void* data() const { return mapped_; }

 private:
  void reset();
  VkDevice device_ = VK_NULL_HANDLE;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  void* mapped_ = nullptr;
};

// A device-local 2D or 3D image kept in VK_IMAGE_LAYOUT_GENERAL, so compute shaders
// can write it as a storage image and sample it (with its own sampler) later.
class Texture {
 public:
  Texture() = default;
  // depth == 1 makes a 2D image. Sampled with trilinear filtering and `address` on every axis
  // (repeat for tiling noise and weather, clamp-to-edge for look-up tables). Throws if the
  // device cannot use `format` as a storage image and sample it with linear filtering (and,
  // with mip levels, blit it with linear filtering). Passes write level 0 (storage_view);
  // record_mipmaps fills the others.
  // `render_target`: a 2D image a raster pass draws into (gpu/raster.h) as well (RasterPass
  // checks that a blended one can be blended).
  Texture(Context& ctx, uint32_t width, uint32_t height, uint32_t depth, VkFormat format,
          VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_REPEAT, uint32_t mip_levels = 1,
          bool render_target = false);
  // A 2D array of `layers.count` images of one size (sampler2DArray, image2DArray), clamped at
  // its edges, one mip level; each layer a render target (render_target(layer)) when asked.
  Texture(Context& ctx, uint32_t width, uint32_t height, ArrayLayers layers, VkFormat format,
          bool render_target = false);
  ~Texture() { reset(); }
  Texture(Texture&& other) noexcept { *this = std::move(other); }
  Texture& operator=(Texture&& other) noexcept;

  VkImage image() const { return image_; }
  VkImageView view() const { return view_; }  // every mip level (and layer), for sampling
  VkImageView storage_view() const { return storage_view_; }  // level 0
  // Level 0 of `layer` as a raster pass's target (a texture made with render_target).
  RenderTarget render_target(uint32_t layer = 0) const;
  VkSampler sampler() const { return sampler_; }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t depth() const { return depth_; }
  uint32_t layers() const { return layers_; }

  // Copies tightly packed texels from `staging` into the image (recorded into `cmd`).
  void record_upload(VkCommandBuffer cmd, const Buffer& staging) const;
  // Copies the image into `staging` (recorded into `cmd`).
  void record_download(VkCommandBuffer cmd, const Buffer& staging) const;
  // Sets every texel (of every layer) to `value` (recorded into `cmd`).
  void record_clear(VkCommandBuffer cmd, const VkClearColorValue& value = {}) const;
  // The same for one layer of an array.
  void record_clear_layer(VkCommandBuffer cmd, uint32_t layer) const;
  // Box-filters each mip level from the one above it (recorded into `cmd`).
  void record_mipmaps(VkCommandBuffer cmd) const;
  // Scales level 0 of this 2D image into level 0 of `to`'s with linear filtering (a 2:1
  // reduction is a 2 x 2 box filter; recorded into `cmd`).
  void record_blit_to(VkCommandBuffer cmd, const Texture& to) const;

 private:
  // Both constructors': `layers` 0 makes a 2D or 3D image, else a 2D array.
  void create(Context& ctx, VkFormat format, VkSamplerAddressMode address, bool render_target);
  void reset();
  VkDevice device_ = VK_NULL_HANDLE;
  VkImage image_ = VK_NULL_HANDLE;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  VkImageView storage_view_ = VK_NULL_HANDLE;
  std::vector<VkImageView> layer_views_;  // a render-target array's, one a layer
  VkSampler sampler_ = VK_NULL_HANDLE;
  uint32_t width_ = 0, height_ = 0, depth_ = 0, levels_ = 1;
  uint32_t layers_ = 1;
  bool array_ = false;
};

// A full memory barrier between compute/transfer work (shader writes -> reads).
void compute_barrier(VkCommandBuffer cmd);
// Everything submitted before (any stage, any write) before the compute and transfer work
// that follows: the first command of every frame and one-off submission.
void full_barrier(VkCommandBuffer cmd);
// The end of a frame: its compute writes made visible to the host's transfers, fragment and
// compute shaders (nephele/frame.h, FrameImages); fragment shaders only where the queue has
// graphics.
void frame_end_barrier(VkCommandBuffer cmd, bool graphics);
// Between two passes of the frame graph: every write before is visible to every read and
// write after, in every stage (compute, transfer, the raster passes).
void pass_barrier(VkCommandBuffer cmd);

}  // namespace nephele::gpu

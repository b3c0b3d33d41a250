#include "gpu/resources.h"

#include <algorithm>
#include <utility>

#include "gpu/vk_check.h"

namespace nephele::gpu {

void allocate_device_local_image(Context& ctx, const VkImageCreateInfo& info, VkImage& image,
                                 VkDeviceMemory& memory) {
  const VkDevice device = ctx.device();
  NEPHELE_VK(vkCreateImage(device, &info, nullptr, &image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(device, image, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = ctx.memory_type(req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  NEPHELE_VK(vkAllocateMemory(device, &alloc, nullptr, &memory));
  NEPHELE_VK(vkBindImageMemory(device, image, memory, 0));
}

void create_device_local_image(Context& ctx, const VkImageCreateInfo& info,
                               VkImageAspectFlags aspect, VkImage& image, VkDeviceMemory& memory,
                               VkImageView& view) {
  allocate_device_local_image(ctx, info, image, memory);
  view = create_image_view(ctx.device(), image, info, aspect, info.mipLevels);
}

VkImageView create_image_view(VkDevice device, VkImage image, const VkImageCreateInfo& info,
                              VkImageAspectFlags aspect, uint32_t levels, bool array,
                              uint32_t first_layer, uint32_t layers) {
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = image;
  view.viewType = array                                ? VK_IMAGE_VIEW_TYPE_2D_ARRAY
                  : info.imageType == VK_IMAGE_TYPE_3D ? VK_IMAGE_VIEW_TYPE_3D
                  : info.imageType == VK_IMAGE_TYPE_1D ? VK_IMAGE_VIEW_TYPE_1D
                                                       : VK_IMAGE_VIEW_TYPE_2D;
  view.format = info.format;
  view.subresourceRange = {aspect, 0, levels, first_layer, layers};
  VkImageView handle = VK_NULL_HANDLE;
  NEPHELE_VK(vkCreateImageView(device, &view, nullptr, &handle));
  return handle;
}

Buffer::Buffer(Context& ctx, VkDeviceSize size, VkBufferUsageFlags usage)
    : device_(ctx.device()), size_(size) {
  // A failure part way (out of memory) frees what was made: no destructor runs for it.
  const UndoOnThrow undo([this] { reset(); });
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  NEPHELE_VK(vkCreateBuffer(device_, &info, nullptr, &buffer_));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(device_, buffer_, &req);
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex =
      ctx.memory_type(req.memoryTypeBits,
                      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  NEPHELE_VK(vkAllocateMemory(device_, &alloc, nullptr, &memory_));
  NEPHELE_VK(vkBindBufferMemory(device_, buffer_, memory_, 0));
  NEPHELE_VK(vkMapMemory(device_, memory_, 0, VK_WHOLE_SIZE, 0, &mapped_));
}

Buffer& Buffer::operator=(Buffer&& other) noexcept {
  if (this != &other) {
    reset();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    buffer_ = std::exchange(other.buffer_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    size_ = std::exchange(other.size_, 0);
    mapped_ = std::exchange(other.mapped_, nullptr);
  }
  return *this;
}

void Buffer::reset() {
  if (!device_) return;
  if (mapped_) vkUnmapMemory(device_, memory_);
  vkDestroyBuffer(device_, buffer_, nullptr);
  vkFreeMemory(device_, memory_, nullptr);
  device_ = VK_NULL_HANDLE;
}

Texture::Texture(Context& ctx, uint32_t width, uint32_t height, uint32_t depth, VkFormat format,
                 VkSamplerAddressMode address, uint32_t mip_levels, bool render_target)
    : device_(ctx.device()), width_(width), height_(height), depth_(depth), levels_(mip_levels) {
  create(ctx, format, address, render_target);
}

Texture::Texture(Context& ctx, uint32_t width, uint32_t height, ArrayLayers layers, VkFormat format,
                 bool render_target)
    : device_(ctx.device()),
      width_(width),
      height_(height),
      depth_(1),
      layers_(std::max(layers.count, 1u)),
      array_(true) {
  create(ctx, format, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, render_target);
}

void Texture::create(Context& ctx, VkFormat format, VkSamplerAddressMode address,
                     bool render_target) {
  // A failure part way (out of memory) frees what was made: no destructor runs for it.
  const UndoOnThrow undo([this] { reset(); });
  const uint32_t mip_levels = levels_;
  // Every texture is written by a compute pass and then sampled with linear filtering.
  VkFormatProperties props;
  vkGetPhysicalDeviceFormatProperties(ctx.physical_device(), format, &props);
  const VkFormatFeatureFlags needed =
      VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT | VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
      VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT |
      (mip_levels > 1 ? VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT : 0);
  if ((props.optimalTilingFeatures & needed) != needed)
    throw RuntimeError("Vulkan format " + std::to_string(int(format)) +
                       " cannot be a filtered storage image on " + ctx.device_name());
  const bool is_3d = depth_ > 1;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = is_3d ? VK_IMAGE_TYPE_3D : VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width_, height_, depth_};
  info.mipLevels = mip_levels;
  info.arrayLayers = layers_;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
               VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  if (render_target) {
    if (is_3d || !(props.optimalTilingFeatures & VK_FORMAT_FEATURE_COLOR_ATTACHMENT_BIT))
      throw RuntimeError("Vulkan format " + std::to_string(int(format)) +
                         " cannot be a 2D render target on " + ctx.device_name());
    info.usage |= VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  }
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  allocate_device_local_image(ctx, info, image_, memory_);
  const VkImageAspectFlags color = VK_IMAGE_ASPECT_COLOR_BIT;
  view_ = create_image_view(device_, image_, info, color, mip_levels, array_, 0, layers_);
  storage_view_ = create_image_view(device_, image_, info, color, 1, array_, 0, layers_);
  if (array_ && render_target)
    for (uint32_t layer = 0; layer < layers_; ++layer)
      layer_views_.push_back(create_image_view(device_, image_, info, color, 1, false, layer, 1));

  VkSamplerCreateInfo sampler{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  sampler.magFilter = VK_FILTER_LINEAR;
  sampler.minFilter = VK_FILTER_LINEAR;
  sampler.mipmapMode =
      mip_levels > 1 ? VK_SAMPLER_MIPMAP_MODE_LINEAR : VK_SAMPLER_MIPMAP_MODE_NEAREST;
  sampler.addressModeU = sampler.addressModeV = sampler.addressModeW = address;
  sampler.maxLod = float(mip_levels - 1);
  NEPHELE_VK(vkCreateSampler(device_, &sampler, nullptr, &sampler_));

  // Move to GENERAL once; it stays there.
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    barrier.srcAccessMask = 0;
    barrier.dstAccessMask =
        VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    barrier.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    barrier.newLayout = VK_IMAGE_LAYOUT_GENERAL;
    barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    barrier.image = image_;
    barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, mip_levels, 0, layers_};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                         0, nullptr, 0, nullptr, 1, &barrier);
  });
}

RenderTarget Texture::render_target(uint32_t layer) const {
  if (layer >= layers_ || (array_ && layer >= layer_views_.size()))
    throw RuntimeError("Texture::render_target: layer " + std::to_string(layer) +
                       " of a texture of " + std::to_string(layers_) +
                       (array_ ? " layers not made as a render target" : " layer"));
  return {array_ ? layer_views_[layer] : storage_view_, width_, height_};
}

Texture& Texture::operator=(Texture&& other) noexcept {
  if (this != &other) {
    reset();
    device_ = std::exchange(other.device_, VK_NULL_HANDLE);
    image_ = std::exchange(other.image_, VK_NULL_HANDLE);
    memory_ = std::exchange(other.memory_, VK_NULL_HANDLE);
    view_ = std::exchange(other.view_, VK_NULL_HANDLE);
    storage_view_ = std::exchange(other.storage_view_, VK_NULL_HANDLE);
    layer_views_ = std::exchange(other.layer_views_, {});
    sampler_ = std::exchange(other.sampler_, VK_NULL_HANDLE);
    width_ = other.width_;
    height_ = other.height_;
    depth_ = other.depth_;
    levels_ = other.levels_;
    layers_ = other.layers_;
    array_ = other.array_;
  }
  return *this;
}

void Texture::reset() {
  if (!device_) return;
  vkDestroySampler(device_, sampler_, nullptr);
  vkDestroyImageView(device_, view_, nullptr);
  vkDestroyImageView(device_, storage_view_, nullptr);
  for (VkImageView v : layer_views_) vkDestroyImageView(device_, v, nullptr);
  layer_views_.clear();
  vkDestroyImage(device_, image_, nullptr);
  vkFreeMemory(device_, memory_, nullptr);
  device_ = VK_NULL_HANDLE;
}

static VkBufferImageCopy whole_image_copy(const Texture& t) {
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, t.layers()};
  region.imageExtent = {t.width(), t.height(), t.depth()};
  return region;
}

// Moves `image` between GENERAL (where shaders use it) and a transfer layout, making all
// earlier compute and transfer work visible.
static void transition(VkCommandBuffer cmd, VkImage image, uint32_t layers, VkImageLayout from,
                       VkImageLayout to) {
  VkImageMemoryBarrier barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.oldLayout = from;
  barrier.newLayout = to;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers};
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                       nullptr, 0, nullptr, 1, &barrier);
}

void Texture::record_upload(VkCommandBuffer cmd, const Buffer& staging) const {
  VkBufferImageCopy region = whole_image_copy(*this);
  transition(cmd, image_, layers_, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  vkCmdCopyBufferToImage(cmd, staging.handle(), image_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1,
                         &region);
  transition(cmd, image_, layers_, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
}

void Texture::record_download(VkCommandBuffer cmd, const Buffer& staging) const {
  VkBufferImageCopy region = whole_image_copy(*this);
  transition(cmd, image_, layers_, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  vkCmdCopyImageToBuffer(cmd, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.handle(), 1,
                         &region);
  transition(cmd, image_, layers_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_GENERAL);
  compute_barrier(cmd);
}

void Texture::record_clear(VkCommandBuffer cmd, const VkClearColorValue& value) const {
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, layers_};
  vkCmdClearColorImage(cmd, image_, VK_IMAGE_LAYOUT_GENERAL, &value, 1, &range);
  compute_barrier(cmd);
}

void Texture::record_clear_layer(VkCommandBuffer cmd, uint32_t layer) const {
  const VkClearColorValue zero{};
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, layer, 1};
  vkCmdClearColorImage(cmd, image_, VK_IMAGE_LAYOUT_GENERAL, &zero, 1, &range);
  compute_barrier(cmd);
}

void compute_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT |
                           VK_PIPELINE_STAGE_HOST_BIT,
                       0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void full_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_SHADER_WRITE_BIT |
                          VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1,
                       &barrier, 0, nullptr, 0, nullptr);
}

void pass_barrier(VkCommandBuffer cmd) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_MEMORY_READ_BIT | VK_ACCESS_MEMORY_WRITE_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT,
                       0, 1, &barrier, 0, nullptr, 0, nullptr);
}

void frame_end_barrier(VkCommandBuffer cmd, bool graphics) {
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
  VkPipelineStageFlags dst = VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
  if (graphics) dst |= VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, dst, 0, 1, &barrier, 0, nullptr,
                       0, nullptr);
}

namespace {

// Blits level `from_level` of `from` (`from_size` texels) into level `to_level` of `to`
// (`to_size`) with linear filtering. Both are kept in the general layout: moved to the
// transfer's layouts for the blit and back.
void blit_level(VkCommandBuffer cmd, VkImage from, uint32_t from_level, VkOffset3D from_size,
                VkImage to, uint32_t to_level, VkOffset3D to_size) {
  const VkImage images[2] = {from, to};
  const uint32_t levels[2] = {from_level, to_level};
  const VkImageLayout transfer[2] = {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL};
  const auto transition = [&](bool to_transfer) {
    VkImageMemoryBarrier barriers[2];
    for (int i = 0; i < 2; ++i) {
      barriers[i] = {VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
      barriers[i].srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
      barriers[i].dstAccessMask =
          VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
      barriers[i].oldLayout = to_transfer ? VK_IMAGE_LAYOUT_GENERAL : transfer[i];
      barriers[i].newLayout = to_transfer ? transfer[i] : VK_IMAGE_LAYOUT_GENERAL;
      barriers[i].srcQueueFamilyIndex = barriers[i].dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
      barriers[i].image = images[i];
      barriers[i].subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, levels[i], 1, 0, 1};
    }
    const VkPipelineStageFlags stages =
        VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    vkCmdPipelineBarrier(cmd, stages, stages, 0, 0, nullptr, 0, nullptr, 2, barriers);
  };
  VkImageBlit blit{};
  blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, from_level, 0, 1};
  blit.srcOffsets[1] = from_size;
  blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, to_level, 0, 1};
  blit.dstOffsets[1] = to_size;
  transition(true);
  vkCmdBlitImage(cmd, from, transfer[0], to, transfer[1], 1, &blit, VK_FILTER_LINEAR);
  transition(false);
}

}  // namespace

void Texture::record_mipmaps(VkCommandBuffer cmd) const {
  const auto size = [&](uint32_t level) {
    const auto at = [level](uint32_t n) { return int32_t(std::max(n >> level, 1u)); };
    return VkOffset3D{at(width_), at(height_), at(depth_)};
  };
  for (uint32_t level = 1; level < levels_; ++level)
    blit_level(cmd, image_, level - 1, size(level - 1), image_, level, size(level));
}

void Texture::record_blit_to(VkCommandBuffer cmd, const Texture& to) const {
  blit_level(cmd, image_, 0, {int32_t(width_), int32_t(height_), 1}, to.image_, 0,
             {int32_t(to.width_), int32_t(to.height_), 1});
}

}  // namespace nephele::gpu

// nephele-view — TEMPORARY stand-in for nephele::FrameRenderer (see stand_in_renderer.h).
#include "stand_in_renderer.h"

#include <chrono>
#include <cmath>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "nephele/sky.h"
#include "vulkan_window.h"

namespace nephele::view {

StandInRenderer::StandInRenderer(const HostVulkan& host, const RendererOptions&) : host_(host) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(host_.physical_device, &props);
  device_name_ = props.deviceName;
  slots_.resize(size_t(frames_in_flight()));
}

StandInRenderer::~StandInRenderer() {
  vkDeviceWaitIdle(host_.device);
  for (Slot& slot : slots_) {
    destroy(slot.hdr);
    destroy(slot.display);
  }
}

StandInRenderer::Target StandInRenderer::create_target(VkFormat format, uint32_t width,
                                                       uint32_t height) {
  Target t;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
               VK_IMAGE_USAGE_SAMPLED_BIT;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  vk_check(vkCreateImage(host_.device, &info, nullptr, &t.image), "vkCreateImage");
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(host_.device, t.image, &req);
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(host_.physical_device, &props);
  uint32_t type = 0;
  while (type < props.memoryTypeCount &&
         !((req.memoryTypeBits & (1u << type)) &&
           (props.memoryTypes[type].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)))
    ++type;
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = type;
  vk_check(vkAllocateMemory(host_.device, &alloc, nullptr, &t.memory), "vkAllocateMemory");
  vkBindImageMemory(host_.device, t.image, t.memory, 0);
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = t.image;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  vk_check(vkCreateImageView(host_.device, &view, nullptr, &t.view), "vkCreateImageView");
  return t;
}

void StandInRenderer::destroy(Target& t) {
  if (t.view) vkDestroyImageView(host_.device, t.view, nullptr);
  if (t.image) vkDestroyImage(host_.device, t.image, nullptr);
  if (t.memory) vkFreeMemory(host_.device, t.memory, nullptr);
  t = {};
}

FrameImages StandInRenderer::record_frame(VkCommandBuffer cmd, const Scene& scene,
                                          const FrameOptions&) {
  const auto start = std::chrono::steady_clock::now();
  validate_scene(scene);
  const int index = int(calls_ % frames_in_flight());
  Slot& slot = slots_[size_t(index)];
  if (slot.stats) completed_ = slot.stats;  // the host waited for this slot's last frame

  const uint32_t width = uint32_t(scene.output.width), height = uint32_t(scene.output.height);
  if (slot.width != width || slot.height != height) {
    vkDeviceWaitIdle(host_.device);
    destroy(slot.hdr);
    destroy(slot.display);
    slot.hdr = create_target(VK_FORMAT_R32G32B32A32_SFLOAT, width, height);
    slot.display = create_target(VK_FORMAT_R8G8B8A8_UNORM, width, height);
    slot.width = width;
    slot.height = height;
    slot.initialised = false;
  }
  // A clear colour from the scene: blue sky, greyer with coverage, darker with a low sun.
  const float cover = scene.clouds.coverage;
  const float light = 0.3f + 0.7f * std::max(0.0f, scene_sun_direction(scene).z);
  const glm::vec4 hdr = light * glm::vec4(0.35f + 0.4f * cover, 0.55f + 0.2f * cover,
                                          0.9f - 0.1f * cover, 1.0f);
  last_color_ = hdr;
  last_width_ = width;
  last_height_ = height;

  VkImageMemoryBarrier to_general[2]{};
  for (int i = 0; i < 2; ++i) {
    to_general[i].sType = VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER;
    to_general[i].srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
    to_general[i].dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_general[i].oldLayout =
        slot.initialised ? VK_IMAGE_LAYOUT_GENERAL : VK_IMAGE_LAYOUT_UNDEFINED;
    to_general[i].newLayout = VK_IMAGE_LAYOUT_GENERAL;
    to_general[i].srcQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_general[i].dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_general[i].image = i == 0 ? slot.hdr.image : slot.display.image;
    to_general[i].subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  }
  vkCmdPipelineBarrier(cmd,
                       VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 2, to_general);
  slot.initialised = true;
  const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  VkClearColorValue hdr_value{{hdr.r, hdr.g, hdr.b, 1.0f}};
  vkCmdClearColorImage(cmd, slot.hdr.image, VK_IMAGE_LAYOUT_GENERAL, &hdr_value, 1, &range);
  Image one(1, 1);
  one.at(0, 0) = hdr;
  const std::vector<unsigned char> srgb = tonemap_srgb8(one, scene.output.exposure);
  VkClearColorValue display_value{
      {srgb[0] / 255.0f, srgb[1] / 255.0f, srgb[2] / 255.0f, 1.0f}};
  vkCmdClearColorImage(cmd, slot.display.image, VK_IMAGE_LAYOUT_GENERAL, &display_value, 1,
                       &range);
  // frame.h's closing barrier.
  VkMemoryBarrier barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  barrier.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  barrier.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT | VK_ACCESS_SHADER_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT,
                       VK_PIPELINE_STAGE_TRANSFER_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT |
                           VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT,
                       0, 1, &barrier, 0, nullptr, 0, nullptr);

  FrameStats stats;
  stats.device = device_name_;
  stats.width = int(width);
  stats.height = int(height);
  stats.ephemeris = scene_ephemeris(scene);
  const glm::vec3 sun = scene_sun_direction(scene, stats.ephemeris);
  const SunAngles angles = sun_angles_from_direction(sun);
  stats.sun.direction = sun;
  stats.sun.elevation_deg = angles.elevation_deg;
  stats.sun.azimuth_deg = angles.azimuth_deg;
  stats.mean_luminance = luminance(hdr);
  stats.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  stats.passes = {{"clear (stand-in)", 0.0}};
  slot.stats = stats;
  ++calls_;

  FrameImages out;
  out.slot = index;
  out.width = width;
  out.height = height;
  out.hdr = slot.hdr.image;
  out.hdr_view = slot.hdr.view;
  out.display = slot.display.image;
  out.display_view = slot.display.view;
  return out;
}

Frame StandInRenderer::read_back() {
  vkDeviceWaitIdle(host_.device);
  Frame frame;
  frame.color = Image(int(last_width_), int(last_height_));
  for (glm::vec4& p : frame.color.pixels) p = last_color_;
  frame.clouds = Image(int(last_width_), int(last_height_));
  if (completed_) frame.stats = *completed_;
  return frame;
}

}  // namespace nephele::view

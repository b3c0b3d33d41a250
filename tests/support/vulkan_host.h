// A host's Vulkan for the tests that use the frame API as an engine does (nephele/frame.h):
// the test owns the instance, device, queue, command buffers and fences, with validation and
// synchronisation validation on, and keeps two frames in flight; and the images and buffers
// such a host makes.
#pragma once

#include <vulkan/vulkan.h>

#include <cstdio>
#include <cstring>
#include <vector>

#include "nephele/frame.h"

namespace nephele_test {

// A host's Vulkan: instance with the validation layer (synchronisation validation too) and a
// counting messenger, the first device, a queue of its first compute family.
class Host {
 public:
  Host() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.apiVersion = VK_API_VERSION_1_2;
    const char* layer = "VK_LAYER_KHRONOS_validation";
    const char* extension = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
    VkValidationFeatureEnableEXT enables[] = {
        VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = enables;
    VkDebugUtilsMessengerCreateInfoEXT messenger{
        VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                            VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger.pfnUserCallback = &Host::on_message;
    messenger.pUserData = this;
    features.pNext = &messenger;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pNext = &features;
    info.pApplicationInfo = &app;
    info.enabledLayerCount = 1;
    info.ppEnabledLayerNames = &layer;
    info.enabledExtensionCount = 1;
    info.ppEnabledExtensionNames = &extension;
    if (vkCreateInstance(&info, nullptr, &vk.instance) != VK_SUCCESS) return;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(vk.instance, "vkCreateDebugUtilsMessengerEXT"));
    create(vk.instance, &messenger, nullptr, &messenger_);

    uint32_t count = 1;
    vkEnumeratePhysicalDevices(vk.instance, &count, &vk.physical_device);
    uint32_t families = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(vk.physical_device, &families, nullptr);
    std::vector<VkQueueFamilyProperties> props(families);
    vkGetPhysicalDeviceQueueFamilyProperties(vk.physical_device, &families, props.data());
    for (uint32_t i = 0; i < families; ++i)
      if (props[i].queueFlags & VK_QUEUE_COMPUTE_BIT) {
        vk.queue_family = i;
        break;
      }
    const float priority = 1.0f;
    VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue.queueFamilyIndex = vk.queue_family;
    queue.queueCount = 1;
    queue.pQueuePriorities = &priority;
    VkDeviceCreateInfo device{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    device.queueCreateInfoCount = 1;
    device.pQueueCreateInfos = &queue;
    vkCreateDevice(vk.physical_device, &device, nullptr, &vk.device);
    vkGetDeviceQueue(vk.device, vk.queue_family, 0, &vk.queue);

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = vk.queue_family;
    vkCreateCommandPool(vk.device, &pool_info, nullptr, &pool);
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool;
    alloc.commandBufferCount = 2;
    vkAllocateCommandBuffers(vk.device, &alloc, cmd);
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    fence_info.flags = VK_FENCE_CREATE_SIGNALED_BIT;
    for (VkFence& f : fence) vkCreateFence(vk.device, &fence_info, nullptr, &f);
  }
  ~Host() {
    if (vk.device) {
      vkDeviceWaitIdle(vk.device);
      for (VkFence f : fence) vkDestroyFence(vk.device, f, nullptr);
      vkDestroyCommandPool(vk.device, pool, nullptr);
      vkDestroyDevice(vk.device, nullptr);
    }
    if (messenger_) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(vk.instance, "vkDestroyDebugUtilsMessengerEXT"));
      destroy(vk.instance, messenger_, nullptr);
    }
    if (vk.instance) vkDestroyInstance(vk.instance, nullptr);
  }

  // Waits for the slot's previous frame, begins its command buffer.
  VkCommandBuffer begin(int slot) {
    vkWaitForFences(vk.device, 1, &fence[slot], VK_TRUE, UINT64_MAX);
    vkResetFences(vk.device, 1, &fence[slot]);
    vkResetCommandBuffer(cmd[slot], 0);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(cmd[slot], &begin);
    return cmd[slot];
  }
  void submit(int slot) {
    vkEndCommandBuffer(cmd[slot]);
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &cmd[slot];
    vkQueueSubmit(vk.queue, 1, &submit, fence[slot]);
  }

  nephele::HostVulkan vk;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd[2] = {};
  VkFence fence[2] = {};
  int messages = 0;

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user) {
    static_cast<Host*>(user)->messages++;
    std::fprintf(stderr, "validation: %s\n", data->pMessage);
    return VK_FALSE;
  }
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
};

// The first of the device's memory types in `bits` with all of `wanted`.
inline uint32_t memory_type(const nephele::HostVulkan& vk, uint32_t bits,
                            VkMemoryPropertyFlags wanted) {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(vk.physical_device, &props);
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & wanted) == wanted) return i;
  return 0;
}

// A host-visible buffer: the display image is copied into it, texels are uploaded from it.
struct Readback {
  Readback(const nephele::HostVulkan& vk, VkDeviceSize size,
           VkBufferUsageFlags usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT)
      : device(vk.device) {
    VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    info.size = size;
    info.usage = usage;
    vkCreateBuffer(device, &info, nullptr, &buffer);
    VkMemoryRequirements req;
    vkGetBufferMemoryRequirements(device, buffer, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex =
        memory_type(vk, req.memoryTypeBits,
                    VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
    vkAllocateMemory(device, &alloc, nullptr, &memory);
    vkBindBufferMemory(device, buffer, memory, 0);
    vkMapMemory(device, memory, 0, VK_WHOLE_SIZE, 0, &mapped);
  }
  ~Readback() {
    vkDestroyBuffer(device, buffer, nullptr);
    vkFreeMemory(device, memory, nullptr);
  }
  VkDevice device;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;
};

// A device-local 2D image of the host's (a depth or colour target) and its memory.
struct HostImage {
  HostImage(const nephele::HostVulkan& vk, uint32_t width, uint32_t height, VkFormat format,
            VkImageUsageFlags usage)
      : device(vk.device) {
    VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
    info.imageType = VK_IMAGE_TYPE_2D;
    info.format = format;
    info.extent = {width, height, 1};
    info.mipLevels = 1;
    info.arrayLayers = 1;
    info.samples = VK_SAMPLE_COUNT_1_BIT;
    info.tiling = VK_IMAGE_TILING_OPTIMAL;
    info.usage = usage;
    info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    vkCreateImage(device, &info, nullptr, &image);
    VkMemoryRequirements req;
    vkGetImageMemoryRequirements(device, image, &req);
    VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    alloc.allocationSize = req.size;
    alloc.memoryTypeIndex =
        memory_type(vk, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
    vkAllocateMemory(device, &alloc, nullptr, &memory);
    vkBindImageMemory(device, image, memory, 0);
  }
  ~HostImage() {
    vkDestroyImage(device, image, nullptr);
    vkFreeMemory(device, memory, nullptr);
  }
  HostImage(const HostImage&) = delete;
  HostImage& operator=(const HostImage&) = delete;

  // Records the copy of `staging` (its texels, tightly packed) into the image's `aspect`,
  // leaving it in `layout` with the copy made visible to later transfers.
  void record_upload(VkCommandBuffer cmd, VkBuffer staging, VkImageAspectFlags aspect,
                     uint32_t width, uint32_t height, VkImageLayout layout) const {
    VkImageMemoryBarrier to_dst{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    to_dst.dstAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_dst.oldLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    to_dst.newLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    to_dst.srcQueueFamilyIndex = to_dst.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_dst.image = image;
    to_dst.subresourceRange = {aspect, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0,
                         0, nullptr, 0, nullptr, 1, &to_dst);
    VkBufferImageCopy region{};
    region.imageSubresource = {aspect, 0, 0, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyBufferToImage(cmd, staging, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    VkImageMemoryBarrier to_src = to_dst;
    to_src.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    to_src.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    to_src.oldLayout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
    to_src.newLayout = layout;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0,
                         nullptr, 0, nullptr, 1, &to_src);
  }

  VkDevice device;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
};

}  // namespace nephele_test

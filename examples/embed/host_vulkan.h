// The example host's own Vulkan, as an engine would have it: an instance (validation on when
// asked, its messages counted), a device with one queue family for graphics, compute and
// present, a fixed-size window's swapchain, and the small helpers the host's drawing needs.
// Nothing here is nephele's: nephele only gets the handles (nephele::HostVulkan).
#pragma once

#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

struct GLFWwindow;

namespace embed {

// A Vulkan call that must succeed; throws std::runtime_error naming the call otherwise.
void check(VkResult result, const char* what);

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  void* mapped = nullptr;  // host-visible and coherent, mapped for its lifetime
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

class HostVulkan {
 public:
  HostVulkan(GLFWwindow* window, bool validation);
  ~HostVulkan();
  HostVulkan(const HostVulkan&) = delete;
  HostVulkan& operator=(const HostVulkan&) = delete;

  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkQueue queue = VK_NULL_HANDLE;
  std::string device_name;

  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkFormat swapchain_format = VK_FORMAT_UNDEFINED;
  VkExtent2D extent{};
  std::vector<VkImage> swapchain_images;

  // Warnings and errors of the validation layer so far (each printed to stderr).
  int validation_messages() const { return messages_; }

  Buffer make_buffer(VkDeviceSize size, VkBufferUsageFlags usage) const;
  void destroy(Buffer& buffer) const;
  Image make_image(uint32_t width, uint32_t height, VkFormat format, VkImageUsageFlags usage,
                   VkImageAspectFlags aspect) const;
  void destroy(Image& image) const;
  VkShaderModule load_shader(const std::string& path) const;

 private:
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                   VkDebugUtilsMessageTypeFlagsEXT,
                                                   const VkDebugUtilsMessengerCallbackDataEXT*,
                                                   void*);
  uint32_t memory_type(uint32_t bits, VkMemoryPropertyFlags wanted) const;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  int messages_ = 0;
};

}  // namespace embed

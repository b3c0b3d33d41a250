// nephele-view — the viewer's own Vulkan: instance (with validation and its messenger when
// asked), a device with one queue family for graphics, compute and present, the window's
// swapchain, a render pass that draws over the blitted image, and per-frame command buffers,
// fences and semaphores for kFramesInFlight frames.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "nephele/frame.h"

struct GLFWwindow;

namespace nephele::view {

inline constexpr int kFramesInFlight = 2;

struct VulkanWindowOptions {
  bool validation = false;  // VK_LAYER_KHRONOS_validation with synchronisation validation
  std::string device;       // substring of the device's name; empty = the best one
};

// A Vulkan call that must succeed; throws nephele::RuntimeError naming the call otherwise.
void vk_check(VkResult result, const char* what);

class VulkanWindow {
 public:
  VulkanWindow(GLFWwindow* window, const VulkanWindowOptions& options);
  ~VulkanWindow();
  VulkanWindow(const VulkanWindow&) = delete;
  VulkanWindow& operator=(const VulkanWindow&) = delete;

  HostVulkan host() const;
  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  const std::string& device_name() const { return device_name_; }
  // Validation messages (warnings and errors) seen so far by any VulkanWindow of the process,
  // also those of its destruction; each is printed to stderr.
  static int validation_messages();

  // (Re)creates the swapchain for the window's framebuffer size; false while it is 0 x 0
  // (minimised), and nothing is drawn then.
  bool recreate_swapchain();
  bool has_swapchain() const { return swapchain_ != VK_NULL_HANDLE; }
  VkSwapchainKHR swapchain() const { return swapchain_; }
  VkExtent2D extent() const { return extent_; }
  VkFormat format() const { return format_; }
  uint32_t image_count() const { return uint32_t(images_.size()); }
  VkImage image(uint32_t i) const { return images_[i]; }
  VkFramebuffer framebuffer(uint32_t i) const { return framebuffers_[i]; }
  // Signalled when image i may be presented (one per image: a present may still wait on it).
  VkSemaphore render_finished(uint32_t i) const { return render_finished_[i]; }
  // Expects the image in TRANSFER_DST_OPTIMAL, keeps its contents (the blitted frame), leaves
  // it in PRESENT_SRC_KHR; its colour writes are made visible to later transfers.
  VkRenderPass render_pass() const { return render_pass_; }
  // Linear filtering when blitting the frame is supported (else nearest).
  bool linear_blit() const { return linear_blit_; }

  VkCommandBuffer command_buffer(int slot) const { return frames_[size_t(slot)].cmd; }
  VkFence fence(int slot) const { return frames_[size_t(slot)].fence; }
  VkSemaphore image_available(int slot) const { return frames_[size_t(slot)].image_available; }

  // A host-visible buffer of `bytes`, for reading images back.
  struct HostBuffer {
    VkBuffer buffer = VK_NULL_HANDLE;
    VkDeviceMemory memory = VK_NULL_HANDLE;
    void* mapped = nullptr;
  };
  HostBuffer create_host_buffer(VkDeviceSize bytes, VkBufferUsageFlags usage) const;
  void destroy(HostBuffer& buffer) const;
  uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const;

  // Records with `record` into a one-off command buffer, submits it and waits.
  template <typename F>
  void run_once(F&& record) {
    VkCommandBuffer cmd = begin_once();
    record(cmd);
    end_once(cmd);
  }

 private:
  struct FrameSync {
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    VkSemaphore image_available = VK_NULL_HANDLE;
  };

  static VKAPI_ATTR VkBool32 VKAPI_CALL on_message(
      VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT type,
      const VkDebugUtilsMessengerCallbackDataEXT* data, void* user);
  void pick_device(const std::string& wanted);
  void destroy_swapchain();
  VkCommandBuffer begin_once();
  void end_once(VkCommandBuffer cmd);

  GLFWwindow* window_;
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkSurfaceKHR surface_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  VkQueue queue_ = VK_NULL_HANDLE;
  std::string device_name_;
  bool linear_blit_ = false;

  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::vector<FrameSync> frames_;

  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkColorSpaceKHR color_space_ = VK_COLOR_SPACE_SRGB_NONLINEAR_KHR;
  VkExtent2D extent_{0, 0};
  VkRenderPass render_pass_ = VK_NULL_HANDLE;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<VkFramebuffer> framebuffers_;
  std::vector<VkSemaphore> render_finished_;
};

}  // namespace nephele::view

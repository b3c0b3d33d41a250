// Headless Vulkan context: instance, optional validation, one compute queue.
// Picks a real GPU when there is one, otherwise a CPU device (Mesa lavapipe).
#pragma once

#include <vulkan/vulkan.h>

#include <atomic>
#include <functional>
#include <string>

namespace nephele::gpu {

// A device the host created (nephele::HostVulkan): used, never destroyed.
struct HostDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkQueue queue = VK_NULL_HANDLE;
};

// What a device lacks that nephele needs (Vulkan 1.2; its textures' formats as filtered
// storage images, the noise's with blits for its mip levels), named in one line for `who`
// (e.g. "HostVulkan.physical_device 'NAME'"), or empty. `features` gives a format's
// optimal-tiling features (vkGetPhysicalDeviceFormatProperties, or a test's).
std::string device_problem(const std::string& who, uint32_t api_version,
                           const std::function<VkFormatFeatureFlags(VkFormat)>& features);

struct ContextOptions {
  std::string device;       // substring of the device name; empty = best by type
  bool validation = false;  // VK_LAYER_KHRONOS_validation + debug messenger
  bool verbose = false;
};

class Context {
 public:
  explicit Context(const ContextOptions& options);
  // On the host's device: only a command pool and a fence of its own.
  Context(const HostDevice& host, bool verbose);
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkDevice device() const { return device_; }
  VkPhysicalDevice physical_device() const { return physical_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  VkCommandPool command_pool() const { return pool_; }
  const std::string& device_name() const { return device_name_; }
  bool is_cpu() const { return is_cpu_; }
  bool has_graphics() const { return has_graphics_; }  // the queue family's
  double timestamp_period_ns() const { return timestamp_period_ns_; }
  bool has_timestamps() const { return has_timestamps_; }
  int validation_messages() const { return validation_messages_.load(); }
  // Whether passes compile a variant for the features a frame uses (KernelVariants); false
  // runs their full shaders (RendererOptions::feature_variants).
  bool feature_variants() const { return feature_variants_; }
  void set_feature_variants(bool on) { feature_variants_ = on; }

  // Waits until the queue has finished everything submitted to it (before freeing resources
  // that frames in flight may still use).
  void wait_queue_idle() const;

  uint32_t memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const;

  // Records with `record`, submits, and waits for completion.
  // When `record` throws, the command buffer is freed unsubmitted and the exception goes on.
  template <typename F>
  void submit_and_wait(F&& record) {
    VkCommandBuffer cmd = begin_commands();
    try {
      record(cmd);
    } catch (...) {
      discard(cmd);
      throw;
    }
    end_and_wait(cmd);
  }

 private:
  VkCommandBuffer begin_commands();
  void end_and_wait(VkCommandBuffer cmd);
  void discard(VkCommandBuffer cmd);
  void pick_physical_device(const std::string& wanted);
  void read_device_properties();
  void create_pool_and_fence(bool verbose);
  static VKAPI_ATTR VkBool32 VKAPI_CALL on_validation(VkDebugUtilsMessageSeverityFlagBitsEXT,
                                                      VkDebugUtilsMessageTypeFlagsEXT,
                                                      const VkDebugUtilsMessengerCallbackDataEXT*,
                                                      void*);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  VkFence fence_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  bool owns_device_ = true;
  std::string device_name_;
  bool is_cpu_ = false;
  bool feature_variants_ = true;
  bool has_graphics_ = false;
  bool has_timestamps_ = false;
  double timestamp_period_ns_ = 1.0;
  std::atomic<int> validation_messages_{0};
};

}  // namespace nephele::gpu

#include "gpu/context.h"

#include <cstdio>
#include <cstring>
#include <vector>

#include "gpu/vk_check.h"

namespace nephele::gpu {

const char* result_name(VkResult result) {
  switch (result) {
    case VK_SUCCESS: return "VK_SUCCESS";
    case VK_NOT_READY: return "VK_NOT_READY";
    case VK_TIMEOUT: return "VK_TIMEOUT";
    case VK_ERROR_OUT_OF_HOST_MEMORY: return "VK_ERROR_OUT_OF_HOST_MEMORY";
    case VK_ERROR_OUT_OF_DEVICE_MEMORY: return "VK_ERROR_OUT_OF_DEVICE_MEMORY";
    case VK_ERROR_INITIALIZATION_FAILED: return "VK_ERROR_INITIALIZATION_FAILED";
    case VK_ERROR_DEVICE_LOST: return "VK_ERROR_DEVICE_LOST";
    case VK_ERROR_LAYER_NOT_PRESENT: return "VK_ERROR_LAYER_NOT_PRESENT";
    case VK_ERROR_EXTENSION_NOT_PRESENT: return "VK_ERROR_EXTENSION_NOT_PRESENT";
    case VK_ERROR_FEATURE_NOT_PRESENT: return "VK_ERROR_FEATURE_NOT_PRESENT";
    case VK_ERROR_INCOMPATIBLE_DRIVER: return "VK_ERROR_INCOMPATIBLE_DRIVER (no Vulkan driver found)";
    case VK_ERROR_FORMAT_NOT_SUPPORTED: return "VK_ERROR_FORMAT_NOT_SUPPORTED";
    default: return "VkResult error";
  }
}

namespace {

bool has_layer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  for (const auto& layer : layers)
    if (std::strcmp(layer.layerName, name) == 0) return true;
  return false;
}

// Higher is preferred: discrete GPU, integrated, virtual, then CPU (lavapipe).
int type_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 4;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 3;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 1;
    default: return 0;
  }
}

int compute_family(VkPhysicalDevice device) {
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(device, &count, families.data());
  for (uint32_t i = 0; i < count; ++i)
    if (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) return int(i);
  return -1;
}

}  // namespace

VKAPI_ATTR VkBool32 VKAPI_CALL Context::on_validation(
    VkDebugUtilsMessageSeverityFlagBitsEXT severity, VkDebugUtilsMessageTypeFlagsEXT,
    const VkDebugUtilsMessengerCallbackDataEXT* data, void* user) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    static_cast<Context*>(user)->validation_messages_++;
    std::fprintf(stderr, "nephele: Vulkan validation: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

Context::Context(const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "nephele";
  app.pEngineName = "nephele";
  app.apiVersion = VK_API_VERSION_1_2;

  std::vector<const char*> layers, extensions;
  const char* kValidation = "VK_LAYER_KHRONOS_validation";
  if (options.validation) {
    if (!has_layer(kValidation))
      throw RuntimeError(
          "Vulkan validation requested but VK_LAYER_KHRONOS_validation is not installed "
          "(Debian: vulkan-validationlayers)");
    layers.push_back(kValidation);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkDebugUtilsMessengerCreateInfoEXT messenger_info{
      VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger_info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT |
                                   VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                               VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = &Context::on_validation;
  messenger_info.pUserData = this;

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  if (options.validation) info.pNext = &messenger_info;  // also covers instance creation
  NEPHELE_VK(vkCreateInstance(&info, nullptr, &instance_));

  if (options.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    if (create) NEPHELE_VK(create(instance_, &messenger_info, nullptr, &messenger_));
  }

  pick_physical_device(options.device);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = queue_family_;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;
  VkDeviceCreateInfo device_info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  device_info.queueCreateInfoCount = 1;
  device_info.pQueueCreateInfos = &queue_info;
  NEPHELE_VK(vkCreateDevice(physical_, &device_info, nullptr, &device_));
  vkGetDeviceQueue(device_, queue_family_, 0, &queue_);

  create_pool_and_fence(options.verbose);
}

std::string device_problem(const std::string& who, uint32_t api_version,
                           const std::function<VkFormatFeatureFlags(VkFormat)>& features) {
  if (api_version < VK_API_VERSION_1_2)
    return who + " supports Vulkan " + std::to_string(VK_API_VERSION_MAJOR(api_version)) + "." +
           std::to_string(VK_API_VERSION_MINOR(api_version)) + "; nephele needs Vulkan 1.2";
  const VkFormatFeatureFlags filtered_storage = VK_FORMAT_FEATURE_STORAGE_IMAGE_BIT |
                                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_BIT |
                                                VK_FORMAT_FEATURE_SAMPLED_IMAGE_FILTER_LINEAR_BIT;
  const struct {
    VkFormat format;
    const char* name;
    VkFormatFeatureFlags needed;
  } formats[] = {
      {VK_FORMAT_R32G32B32A32_SFLOAT, "R32G32B32A32_SFLOAT", filtered_storage},
      {VK_FORMAT_R16G16B16A16_SFLOAT, "R16G16B16A16_SFLOAT", filtered_storage},
      {VK_FORMAT_R32_SFLOAT, "R32_SFLOAT", filtered_storage},
      {VK_FORMAT_R16G16_SFLOAT, "R16G16_SFLOAT", filtered_storage},
      {VK_FORMAT_R8G8B8A8_UNORM, "R8G8B8A8_UNORM",
       filtered_storage | VK_FORMAT_FEATURE_BLIT_SRC_BIT | VK_FORMAT_FEATURE_BLIT_DST_BIT},
  };
  for (const auto& f : formats)
    if ((features(f.format) & f.needed) != f.needed)
      return who + " cannot use VK_FORMAT_" + f.name +
             " as a linearly filtered storage image" +
             (f.format == VK_FORMAT_R8G8B8A8_UNORM ? " with blits" : "") + " (optimal tiling); nephele needs it";
  return {};
}

Context::Context(const HostDevice& host, bool verbose) : owns_device_(false) {
  if (!host.instance || !host.physical_device || !host.device || !host.queue)
    throw InputError(
        "HostVulkan: instance, physical_device, device and queue must all be set (a null handle "
        "was given)");
  instance_ = host.instance;
  physical_ = host.physical_device;
  device_ = host.device;
  queue_ = host.queue;
  queue_family_ = host.queue_family;
  uint32_t count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &count, nullptr);
  std::vector<VkQueueFamilyProperties> families(count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &count, families.data());
  if (queue_family_ >= count || !(families[queue_family_].queueFlags & VK_QUEUE_COMPUTE_BIT))
    throw InputError("HostVulkan.queue_family = " + std::to_string(queue_family_) +
                     ": must be a queue family with compute (the device has " +
                     std::to_string(count) + " families)");
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physical_, &props);
  const std::string problem = device_problem(
      std::string("HostVulkan.physical_device '") + props.deviceName + "'", props.apiVersion,
      [&](VkFormat format) {
        VkFormatProperties p;
        vkGetPhysicalDeviceFormatProperties(physical_, format, &p);
        return p.optimalTilingFeatures;
      });
  if (!problem.empty()) throw InputError(problem);
  read_device_properties();
  create_pool_and_fence(verbose);
}

void Context::create_pool_and_fence(bool verbose) {
  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = queue_family_;
  NEPHELE_VK(vkCreateCommandPool(device_, &pool_info, nullptr, &pool_));
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  NEPHELE_VK(vkCreateFence(device_, &fence_info, nullptr, &fence_));
  if (verbose)
    std::fprintf(stderr, "nephele: device: %s%s%s\n", device_name_.c_str(),
                 is_cpu_ ? " (CPU, Mesa lavapipe)" : "", owns_device_ ? "" : " (the host's)");
}

void Context::wait_queue_idle() const { NEPHELE_VK(vkQueueWaitIdle(queue_)); }

void Context::pick_physical_device(const std::string& wanted) {
  uint32_t count = 0;
  vkEnumeratePhysicalDevices(instance_, &count, nullptr);
  std::vector<VkPhysicalDevice> devices(count);
  vkEnumeratePhysicalDevices(instance_, &count, devices.data());
  if (count == 0)
    throw RuntimeError(
        "no Vulkan device found (install a GPU driver, or Mesa's lavapipe: "
        "Debian package mesa-vulkan-drivers)");

  int best_rank = -1;
  std::string names;
  for (VkPhysicalDevice device : devices) {
    VkPhysicalDeviceProperties props;
    vkGetPhysicalDeviceProperties(device, &props);
    names += (names.empty() ? "" : ", ") + std::string("'") + props.deviceName + "'";
    if (compute_family(device) < 0) continue;
    if (!wanted.empty() && std::strstr(props.deviceName, wanted.c_str()) == nullptr) continue;
    int rank = type_rank(props.deviceType);
    if (rank > best_rank) {
      best_rank = rank;
      physical_ = device;
    }
  }
  if (physical_ == VK_NULL_HANDLE)
    throw InputError("--device '" + wanted + "': no such Vulkan device with compute (available: " +
                     names + ")");

  queue_family_ = uint32_t(compute_family(physical_));
  read_device_properties();
}

void Context::read_device_properties() {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physical_, &props);
  device_name_ = props.deviceName;
  is_cpu_ = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;
  timestamp_period_ns_ = props.limits.timestampPeriod;

  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_, &family_count, families.data());
  has_graphics_ = (families[queue_family_].queueFlags & VK_QUEUE_GRAPHICS_BIT) != 0;
  has_timestamps_ = families[queue_family_].timestampValidBits > 0 &&
                    props.limits.timestampComputeAndGraphics;
}

Context::~Context() {
  if (!owns_device_) {  // the host has waited for what it submitted; ours was waited for
    vkDestroyFence(device_, fence_, nullptr);
    vkDestroyCommandPool(device_, pool_, nullptr);
    return;
  }
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyFence(device_, fence_, nullptr);
    vkDestroyCommandPool(device_, pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroy) destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

uint32_t Context::memory_type(uint32_t type_bits, VkMemoryPropertyFlags flags) const {
  VkPhysicalDeviceMemoryProperties props;
  vkGetPhysicalDeviceMemoryProperties(physical_, &props);
  for (uint32_t i = 0; i < props.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (props.memoryTypes[i].propertyFlags & flags) == flags) return i;
  throw RuntimeError("Vulkan: no memory type with the required properties");
}

VkCommandBuffer Context::begin_commands() {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = pool_;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd;
  NEPHELE_VK(vkAllocateCommandBuffers(device_, &alloc, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  NEPHELE_VK(vkBeginCommandBuffer(cmd, &begin));
  return cmd;
}

void Context::discard(VkCommandBuffer cmd) {
  vkEndCommandBuffer(cmd);
  vkFreeCommandBuffers(device_, pool_, 1, &cmd);
}

void Context::end_and_wait(VkCommandBuffer cmd) {
  NEPHELE_VK(vkEndCommandBuffer(cmd));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  NEPHELE_VK(vkResetFences(device_, 1, &fence_));
  NEPHELE_VK(vkQueueSubmit(queue_, 1, &submit, fence_));
  NEPHELE_VK(vkWaitForFences(device_, 1, &fence_, VK_TRUE, UINT64_MAX));
  vkFreeCommandBuffers(device_, pool_, 1, &cmd);
}

}  // namespace nephele::gpu

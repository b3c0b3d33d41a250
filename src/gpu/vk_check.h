// Turns a failed Vulkan call into nephele::RuntimeError naming the call and the result.
#pragma once

#include <vulkan/vulkan.h>

#include <string>

#include "nephele/error.h"

namespace nephele::gpu {

const char* result_name(VkResult result);

inline void check(VkResult result, const char* what) {
  if (result != VK_SUCCESS)
    throw RuntimeError(std::string("Vulkan: ") + what + " failed: " + result_name(result));
}

}  // namespace nephele::gpu

#define NEPHELE_VK(call) ::nephele::gpu::check((call), #call)

// What a pipeline's shaders bind: the descriptors of set 0 that their entry points statically
// use, read from the SPIR-V itself (SPIRV-Cross's reflection). Each pipeline's layout is made
// of these alone (gpu::PassInterface, kernel.h), so a pass sees only the bindings it uses.
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace nephele::gpu {

struct ShaderBinding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  VkShaderStageFlags stages = 0;
};

// The bindings the SPIR-V module's entry point uses, sorted by number, each visible to `stage`.
// `name` names the module in errors (RuntimeError): words that are not SPIR-V, a descriptor in
// a set other than 0, separate images or samplers (nephele binds combined ones).
std::vector<ShaderBinding> reflect_spirv(const uint32_t* words, size_t word_count,
                                         VkShaderStageFlagBits stage, const std::string& name);

// The words of an embedded SPIR-V file ("clouds.comp.spv"); throws RuntimeError when this build
// does not embed it.
std::span<const uint32_t> embedded_spirv(const std::string& spv_name);

// The same for an embedded shader ("clouds.comp.spv"): throws RuntimeError when this build does
// not embed it.
std::vector<ShaderBinding> reflect_embedded(const std::string& spv_name, VkShaderStageFlagBits stage);

// The union of several stages' bindings (a raster pipeline's vertex and fragment shaders): one
// entry a binding, visible to every stage that uses it. Throws RuntimeError when two stages
// use one binding as different descriptor types.
std::vector<ShaderBinding> merge_bindings(const std::vector<std::vector<ShaderBinding>>& stages);

}  // namespace nephele::gpu

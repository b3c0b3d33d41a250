// What a pipeline's shaders bind: the descriptors that their entry points statically use, read
// from the SPIR-V itself (SPIRV-Cross's reflection). Each pipeline's layout is made of these
// alone (gpu::PassInterface, kernel.h), so a pass sees only the bindings it uses.
//
// Two descriptor sets:
// - set 0, the global table: shaders/common/bindings_inc.glsl numbers every binding once
//   (gpu::Binding is generated from it), and the host binds them by number
//   (DescriptorSet::bind_buffer, bind_sampled_image, ...).
// - set 1, a module's own resources, declared by the module's shaders and bound by the module
//   by name, never added to the global table:
//     layout(set = 1, binding = 0) uniform GroundFogBlock { vec4 a; } ground_fog;
//     layout(set = 1, binding = 1) uniform sampler2D ground_fog_map;
//   are "GroundFogBlock" (a uniform or storage block: its block name) and "ground_fog_map" (an
//   image or sampler: its variable name), bound with DescriptorSet::bind_module_buffer and
//   bind_module_sampled_image. The binding numbers in set 1 are the shader's own; one pipeline
//   may not use one number for two names or one name at two numbers. The names are the table's
//   keys for every pipeline: a module starts its names with its own ("ground_fog_...").
//   The build keeps the names in the optimised SPIR-V (CMakeLists.txt, cmake/spv_strip.cpp).
#pragma once

#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace nephele::gpu {

// Set 1: a module's own resources, bound by name (above).
constexpr uint32_t kModuleSet = 1;

struct ShaderBinding {
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  VkShaderStageFlags stages = 0;
  uint32_t set = 0;  // 0 (bindings_inc.glsl) or kModuleSet
  // The block's name for a uniform or storage block ("FrameParamsBlock"), else the variable's
  // ("sky_view_lut"); how set 1's resources are bound.
  std::string name;
};

// The bindings the SPIR-V module's entry point uses, sorted by set and number, each visible to
// `stage`. `name` names the module in errors (RuntimeError): words that are not SPIR-V, a
// descriptor in a set other than 0 and 1, separate images or samplers (nephele binds combined
// ones), a set-1 resource without a name, or two set-1 resources at one binding or of one name.
std::vector<ShaderBinding> reflect_spirv(const uint32_t* words, size_t word_count,
                                         VkShaderStageFlagBits stage, const std::string& name);

// The words of an embedded SPIR-V file ("clouds.comp.spv"); throws RuntimeError when this build
// does not embed it.
std::span<const uint32_t> embedded_spirv(const std::string& spv_name);

// The same for an embedded shader ("clouds.comp.spv"): throws RuntimeError when this build does
// not embed it.
std::vector<ShaderBinding> reflect_embedded(const std::string& spv_name, VkShaderStageFlagBits stage);

// The union of several stages' bindings (a raster pipeline's vertex and fragment shaders): one
// entry a (set, binding), visible to every stage that uses it, sorted by set and number. Throws
// RuntimeError when two stages use one binding as different descriptor types, or, in set 1,
// one binding under two names or one name at two bindings.
// `pipeline` names the pipeline in errors.
std::vector<ShaderBinding> merge_bindings(const std::vector<std::vector<ShaderBinding>>& stages,
                                          const std::string& pipeline = {});

}  // namespace nephele::gpu

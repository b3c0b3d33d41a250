#include "gpu/shader_interface.h"

#include <spirv_cross_c.h>

#include <algorithm>
#include <map>
#include <memory>
#include <tuple>
#include <utility>

#include "nephele/error.h"
#include "nephele_embedded.h"

namespace nephele_shaders {
extern const EmbeddedFile kFiles[];
extern const size_t kFileCount;
}  // namespace nephele_shaders

namespace nephele::gpu {

namespace {

struct ContextDeleter {
  void operator()(spvc_context_s* context) const { spvc_context_destroy(context); }
};

// The SPIRV-Cross resource kinds nephele's shaders declare, as Vulkan descriptor types.
struct Kind {
  spvc_resource_type resource;
  VkDescriptorType type;
};
constexpr Kind kKinds[] = {
    {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
    {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
    {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
    {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
};

}  // namespace

std::vector<ShaderBinding> reflect_spirv(const uint32_t* words, size_t word_count,
                                         VkShaderStageFlagBits stage, const std::string& name) {
  spvc_context raw = nullptr;
  if (spvc_context_create(&raw) != SPVC_SUCCESS)
    throw RuntimeError("shader " + name + ": SPIRV-Cross could not start");
  const std::unique_ptr<spvc_context_s, ContextDeleter> context(raw);
  const auto fail = [&](const char* what) {
    throw RuntimeError("shader " + name + ": " + what + ": " +
                       spvc_context_get_last_error_string(raw));
  };
  spvc_parsed_ir ir = nullptr;
  if (spvc_context_parse_spirv(raw, words, word_count, &ir) != SPVC_SUCCESS)
    fail("not SPIR-V SPIRV-Cross can read");
  spvc_compiler compiler = nullptr;
  if (spvc_context_create_compiler(raw, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                   &compiler) != SPVC_SUCCESS)
    fail("no reflection");
  spvc_set active = nullptr;
  spvc_resources resources = nullptr;
  if (spvc_compiler_get_active_interface_variables(compiler, &active) != SPVC_SUCCESS ||
      spvc_compiler_create_shader_resources_for_active_variables(compiler, &resources, active) !=
          SPVC_SUCCESS)
    fail("no resources");
  for (spvc_resource_type separate :
       {SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS,
        SPVC_RESOURCE_TYPE_SUBPASS_INPUT, SPVC_RESOURCE_TYPE_ACCELERATION_STRUCTURE}) {
    const spvc_reflected_resource* list = nullptr;
    size_t count = 0;
    spvc_resources_get_resource_list_for_type(resources, separate, &list, &count);
    if (count > 0)
      throw RuntimeError("shader " + name +
                         ": uses a kind of descriptor nephele does not bind (separate images or "
                         "samplers, input attachments or acceleration structures)");
  }
  std::vector<ShaderBinding> out;
  for (const Kind& kind : kKinds) {
    const spvc_reflected_resource* list = nullptr;
    size_t count = 0;
    spvc_resources_get_resource_list_for_type(resources, kind.resource, &list, &count);
    const bool block = kind.type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ||
                       kind.type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    for (size_t i = 0; i < count; ++i) {
      ShaderBinding b;
      b.binding = spvc_compiler_get_decoration(compiler, list[i].id, SpvDecorationBinding);
      b.type = kind.type;
      b.stages = VkShaderStageFlags(stage);
      b.set = spvc_compiler_get_decoration(compiler, list[i].id, SpvDecorationDescriptorSet);
      // The names the SPIR-V declares (OpName), empty where it has none: a block's type name,
      // an image's variable name.
      b.name = spvc_compiler_get_name(compiler, block ? list[i].base_type_id : list[i].id);
      const std::string what =
          "resource " +
          (b.name.empty() ? "at binding " + std::to_string(b.binding) : "'" + b.name + "'");
      if (b.set != 0 && b.set != kModuleSet)
        throw RuntimeError("shader " + name + ": " + what + " is in descriptor set " +
                           std::to_string(b.set) +
                           "; nephele binds set 0 (bindings_inc.glsl) and set 1 (a module's own "
                           "resources, by name) only");
      if (b.set == kModuleSet && b.name.empty())
        throw RuntimeError("shader " + name + ": set 1's " + what +
                           " has no name in the SPIR-V (compiled without names? the build "
                           "compiles with -g and spv_strip to keep them)");
      out.push_back(std::move(b));
    }
  }
  std::sort(out.begin(), out.end(), [](const ShaderBinding& a, const ShaderBinding& b) {
    return std::tie(a.set, a.binding) < std::tie(b.set, b.binding);
  });
  // Set 1 is bound by name: a number or a name used twice would make that ambiguous. (Set 0's
  // numbers are bindings_inc.glsl's, one declaration each.)
  std::map<uint32_t, const ShaderBinding*> at;
  std::map<std::string, uint32_t> number_of;
  for (const ShaderBinding& b : out) {
    if (b.set != kModuleSet) continue;
    const auto [it, inserted] = at.emplace(b.binding, &b);
    if (!inserted)
      throw RuntimeError("shader " + name + ": two resources at set 1, binding " +
                         std::to_string(b.binding) + " ('" + it->second->name + "' and '" + b.name +
                         "')");
    const auto [named, first] = number_of.emplace(b.name, b.binding);
    if (!first)
      throw RuntimeError("shader " + name + ": set 1's '" + b.name + "' at two bindings (" +
                         std::to_string(named->second) + " and " + std::to_string(b.binding) + ")");
  }
  return out;
}

std::span<const uint32_t> embedded_spirv(const std::string& spv_name) {
  const EmbeddedFile* spv =
      find_embedded(nephele_shaders::kFiles, nephele_shaders::kFileCount, spv_name);
  if (!spv) throw RuntimeError("shader '" + spv_name + "' is not embedded in this build");
  // The embedded bytes are 4-aligned (cmake/embed_files.cmake aligns each file's array).
  return {reinterpret_cast<const uint32_t*>(spv->data), spv->size / 4};
}

std::vector<ShaderBinding> reflect_embedded(const std::string& spv_name, VkShaderStageFlagBits stage) {
  const std::span<const uint32_t> words = embedded_spirv(spv_name);
  return reflect_spirv(words.data(), words.size(), stage, spv_name);
}

std::vector<ShaderBinding> merge_bindings(const std::vector<std::vector<ShaderBinding>>& stages,
                                          const std::string& pipeline) {
  const std::string who = pipeline.empty() ? "one pipeline" : "pipeline " + pipeline;
  std::map<std::pair<uint32_t, uint32_t>, ShaderBinding> merged;  // by (set, binding)
  for (const std::vector<ShaderBinding>& stage : stages)
    for (const ShaderBinding& b : stage) {
      auto [it, inserted] = merged.emplace(std::pair(b.set, b.binding), b);
      if (inserted) continue;
      const std::string where =
          "set " + std::to_string(b.set) + ", binding " + std::to_string(b.binding);
      if (it->second.type != b.type)
        throw RuntimeError(where + " is a different kind of descriptor in two stages of " + who +
                           (b.name.empty() && it->second.name.empty()
                                ? ""
                                : " ('" + it->second.name + "' and '" + b.name + "')"));
      if (b.set == kModuleSet && it->second.name != b.name)
        throw RuntimeError(where + " is '" + it->second.name + "' in one stage of " + who +
                           " and '" + b.name + "' in another");
      it->second.stages |= b.stages;
    }
  std::map<std::string, uint32_t> number_of;  // set 1's names
  std::vector<ShaderBinding> out;
  for (const auto& [key, b] : merged) {
    if (b.set == kModuleSet) {
      const auto [named, first] = number_of.emplace(b.name, b.binding);
      if (!first)
        throw RuntimeError("set 1's '" + b.name + "' is at binding " +
                           std::to_string(named->second) + " in one stage of " + who +
                           " and at binding " + std::to_string(b.binding) + " in another");
    }
    out.push_back(b);
  }
  return out;
}

}  // namespace nephele::gpu

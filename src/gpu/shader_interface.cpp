#include "gpu/shader_interface.h"

#include <spirv_cross_c.h>

#include <algorithm>
#include <map>
#include <memory>

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
    for (size_t i = 0; i < count; ++i) {
      const unsigned set = spvc_compiler_get_decoration(compiler, list[i].id, SpvDecorationDescriptorSet);
      if (set != 0)
        throw RuntimeError("shader " + name + ": a descriptor in set " + std::to_string(set) +
                           "; nephele binds set 0 only");
      out.push_back({spvc_compiler_get_decoration(compiler, list[i].id, SpvDecorationBinding),
                     kind.type, VkShaderStageFlags(stage)});
    }
  }
  std::sort(out.begin(), out.end(),
            [](const ShaderBinding& a, const ShaderBinding& b) { return a.binding < b.binding; });
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

std::vector<ShaderBinding> merge_bindings(const std::vector<std::vector<ShaderBinding>>& stages) {
  std::map<uint32_t, ShaderBinding> merged;
  for (const std::vector<ShaderBinding>& stage : stages)
    for (const ShaderBinding& b : stage) {
      auto [it, inserted] = merged.emplace(b.binding, b);
      if (inserted) continue;
      if (it->second.type != b.type)
        throw RuntimeError("binding " + std::to_string(b.binding) +
                           " is a different kind of descriptor in two stages of one pipeline");
      it->second.stages |= b.stages;
    }
  std::vector<ShaderBinding> out;
  for (const auto& [number, b] : merged) out.push_back(b);
  return out;
}

}  // namespace nephele::gpu

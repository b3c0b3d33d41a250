#include "gpu/kernel.h"

#include <algorithm>
#include <iterator>
#include <map>
#include <vector>

#include "common/push_constants_inc.glsl"  // DrawConstants, DispatchConstants
#include "gpu/vk_check.h"

namespace nephele::gpu {

DescriptorSet::DescriptorSet(Context& ctx) : device_(ctx.device()) {}

DescriptorSet::~DescriptorSet() {
  // Interfaces outliving the table would write into it: the modules own them and are destroyed
  // first (FrameRenderer::Impl).
}

void DescriptorSet::set_entry(Binding binding, VkDescriptorType type,
                              const VkDescriptorBufferInfo* buffer,
                              const VkDescriptorImageInfo* image) {
  Entry& e = table_[binding];
  e.type = type;
  e.buffer = buffer ? *buffer : VkDescriptorBufferInfo{};
  e.image = image ? *image : VkDescriptorImageInfo{};
  e.bound = true;
}

void DescriptorSet::use(int index) {
  current_ = index;
  std::copy(std::begin(table_), std::end(table_), std::begin(used_));
  module_used_ = module_table_;
  for (PassInterface* i : interfaces_) i->write(index);
}

void DescriptorSet::bind_buffer(Binding binding, const Buffer& buffer, VkDescriptorType type) {
  VkDescriptorBufferInfo info{buffer.handle(), 0, VK_WHOLE_SIZE};
  set_entry(binding, type, &info, nullptr);
}

void DescriptorSet::bind_storage_image(Binding binding, const Texture& texture) {
  VkDescriptorImageInfo info{texture.sampler(), texture.storage_view(), VK_IMAGE_LAYOUT_GENERAL};
  set_entry(binding, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, nullptr, &info);
}

void DescriptorSet::bind_image(Binding written, Binding read, const Texture& texture) {
  bind_storage_image(written, texture);
  bind_sampled_image(read, texture);
}

void DescriptorSet::bind_sampled_image(Binding binding, const Texture& texture) {
  VkDescriptorImageInfo info{texture.sampler(), texture.view(), VK_IMAGE_LAYOUT_GENERAL};
  set_entry(binding, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, nullptr, &info);
}

void DescriptorSet::bind_module_buffer(const std::string& name, const Buffer& buffer,
                                       VkDescriptorType type) {
  if (type != VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER && type != VK_DESCRIPTOR_TYPE_STORAGE_BUFFER)
    throw RuntimeError("bind_module_buffer('" + name + "'): descriptor type " +
                       std::to_string(int(type)) + " is not a uniform or storage buffer's");
  Entry& e = module_table_[name];
  e = {type, {buffer.handle(), 0, VK_WHOLE_SIZE}, {}, true};
}

void DescriptorSet::bind_module_storage_image(const std::string& name, const Texture& texture) {
  Entry& e = module_table_[name];
  e = {VK_DESCRIPTOR_TYPE_STORAGE_IMAGE,
       {},
       {texture.sampler(), texture.storage_view(), VK_IMAGE_LAYOUT_GENERAL},
       true};
}

void DescriptorSet::bind_module_sampled_image(const std::string& name, const Texture& texture) {
  Entry& e = module_table_[name];
  e = {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
       {},
       {texture.sampler(), texture.view(), VK_IMAGE_LAYOUT_GENERAL},
       true};
}

PassInterface::PassInterface(DescriptorSet& table, std::string name,
                             std::vector<ShaderBinding> bindings)
    : table_(table), name_(std::move(name)), bindings_(std::move(bindings)) {
  const VkDevice device = table_.device_;
  UndoOnThrow undo([this] { destroy(); });
  std::vector<VkDescriptorSetLayoutBinding> layout_bindings[2];
  std::map<VkDescriptorType, uint32_t> count_of;
  for (const ShaderBinding& b : bindings_) {
    if (b.set == 0 && b.binding >= kBindingCount)
      throw RuntimeError("pipeline " + name_ + ": binding " + std::to_string(b.binding) +
                         " is not one of bindings_inc.glsl's (0 to " +
                         std::to_string(kBindingCount - 1) + ")");
    if (b.set != 0 && b.set != kModuleSet)
      throw RuntimeError("pipeline " + name_ + ": '" + b.name + "' is in descriptor set " +
                         std::to_string(b.set) + "; nephele binds sets 0 and 1 only");
    layout_bindings[b.set].push_back({b.binding, b.type, 1, b.stages, nullptr});
    has_set_[b.set] = true;
    ++count_of[b.type];
  }
  // Set 0's layout always (empty when the pipeline uses none of the table: a pipeline layout
  // needs a valid one for each set below its highest), set 1's when it has bindings.
  const uint32_t layout_count = has_set_[kModuleSet] ? 2 : 1;
  for (uint32_t number = 0; number < layout_count; ++number) {
    VkDescriptorSetLayoutCreateInfo layout_info{
        VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
    layout_info.bindingCount = uint32_t(layout_bindings[number].size());
    layout_info.pBindings = layout_bindings[number].data();
    NEPHELE_VK(vkCreateDescriptorSetLayout(device, &layout_info, nullptr, &layouts_[number]));
  }

  VkPipelineLayoutCreateInfo pipeline_info{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pipeline_info.setLayoutCount = layout_count;
  pipeline_info.pSetLayouts = layouts_;
  // The per-draw constants (params_inc.glsl, DrawConstants).
  const VkPushConstantRange push{kDrawConstantStages, 0, sizeof(DrawConstants)};
  pipeline_info.pushConstantRangeCount = 1;
  pipeline_info.pPushConstantRanges = &push;
  NEPHELE_VK(vkCreatePipelineLayout(device, &pipeline_info, nullptr, &pipeline_layout_));

  if (!bindings_.empty()) {
    // Room for the sets of every slot and all their descriptors: lavapipe allocates beyond a
    // pool's sizes, a GPU's driver does not. Only the sets with bindings are allocated.
    const uint32_t slot_count = uint32_t(std::size(sets_));
    const uint32_t sets_a_slot = uint32_t(has_set_[0]) + uint32_t(has_set_[kModuleSet]);
    std::vector<VkDescriptorPoolSize> sizes;
    for (const auto& [type, count] : count_of) sizes.push_back({type, count * slot_count});
    VkDescriptorPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
    pool_info.maxSets = slot_count * sets_a_slot;
    pool_info.poolSizeCount = uint32_t(sizes.size());
    pool_info.pPoolSizes = sizes.data();
    NEPHELE_VK(vkCreateDescriptorPool(device, &pool_info, nullptr, &pool_));
    for (uint32_t number = 0; number < 2; ++number) {
      if (!has_set_[number]) continue;
      std::vector<VkDescriptorSetLayout> layouts(slot_count, layouts_[number]);
      std::vector<VkDescriptorSet> sets(slot_count);
      VkDescriptorSetAllocateInfo alloc{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
      alloc.descriptorPool = pool_;
      alloc.descriptorSetCount = slot_count;
      alloc.pSetLayouts = layouts.data();
      NEPHELE_VK(vkAllocateDescriptorSets(device, &alloc, sets.data()));
      for (uint32_t slot = 0; slot < slot_count; ++slot) sets_[slot][number] = sets[slot];
    }
  }
  table_.interfaces_.push_back(this);
  // Made while a command buffer records (a pass's kernel made when first recorded): its set
  // of the current slot holds what the others' hold; the other slots are written at their use().
  write(table_.current_);
}

PassInterface::~PassInterface() {
  std::erase(table_.interfaces_, this);
  destroy();
}

void PassInterface::destroy() {
  const VkDevice device = table_.device_;
  vkDestroyDescriptorPool(device, pool_, nullptr);
  vkDestroyPipelineLayout(device, pipeline_layout_, nullptr);
  for (VkDescriptorSetLayout& layout : layouts_) {
    vkDestroyDescriptorSetLayout(device, layout, nullptr);
    layout = VK_NULL_HANDLE;
  }
  pool_ = VK_NULL_HANDLE;
  pipeline_layout_ = VK_NULL_HANDLE;
}

void PassInterface::write(int index) {
  if (bindings_.empty()) return;
  std::vector<VkWriteDescriptorSet> writes;
  writes.reserve(bindings_.size());
  for (const ShaderBinding& b : bindings_) {
    const DescriptorSet::Entry* e = nullptr;
    std::string what;  // the binding, for errors
    if (b.set == kModuleSet) {
      const auto it = table_.module_used_.find(b.name);
      if (it != table_.module_used_.end()) e = &it->second;
      what = "set 1's '" + b.name + "' (binding " + std::to_string(b.binding) + ")";
    } else {
      e = &table_.used_[b.binding];
      what = "binding " + std::to_string(b.binding) + " (" + binding_name(Binding(b.binding)) + ")";
    }
    // A pass that runs binds it first; one that runs without it reads an unwritten descriptor,
    // which the validation layer reports.
    if (!e || !e->bound) continue;
    if (e->type != b.type)
      throw RuntimeError("pipeline " + name_ + " reads " + what + " as descriptor type " +
                         std::to_string(int(b.type)) + ", but type " +
                         std::to_string(int(e->type)) + " is bound there");
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = sets_[index][b.set];
    w.dstBinding = b.binding;
    w.descriptorCount = 1;
    w.descriptorType = e->type;
    const bool is_buffer = e->type == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER ||
                           e->type == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = is_buffer ? &e->buffer : nullptr;
    w.pImageInfo = is_buffer ? nullptr : &e->image;
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(table_.device_, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void PassInterface::bind(VkCommandBuffer cmd, VkPipelineBindPoint bind_point) const {
  const VkDescriptorSet* sets = sets_[table_.current()];
  if (has_set_[0] && has_set_[kModuleSet])
    vkCmdBindDescriptorSets(cmd, bind_point, pipeline_layout_, 0, 2, sets, 0, nullptr);
  else if (has_set_[0] || has_set_[kModuleSet]) {
    const uint32_t number = has_set_[0] ? 0 : kModuleSet;
    vkCmdBindDescriptorSets(cmd, bind_point, pipeline_layout_, number, 1, &sets[number], 0,
                            nullptr);
  }
}

VkShaderModule create_shader_module(VkDevice device, const std::string& spv_name) {
  const std::span<const uint32_t> spv = embedded_spirv(spv_name);
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = spv.size_bytes();
  info.pCode = spv.data();
  VkShaderModule module;
  NEPHELE_VK(vkCreateShaderModule(device, &info, nullptr, &module));
  return module;
}

Specialization::Specialization(const std::vector<int32_t>& values) {
  for (uint32_t i = 0; i < values.size(); ++i)
    entries_.push_back({i, uint32_t(i * sizeof(int32_t)), sizeof(int32_t)});
  info_ = {uint32_t(entries_.size()), entries_.data(), values.size() * sizeof(int32_t), values.data()};
}

Kernel::Kernel(Context& ctx, DescriptorSet& set, const std::string& spv_name,
               const std::vector<int32_t>& specialization)
    : Kernel(ctx, set, embedded_spirv(spv_name), spv_name, specialization) {}

Kernel::Kernel(Context& ctx, DescriptorSet& set, std::span<const uint32_t> spirv,
               const std::string& name, const std::vector<int32_t>& specialization)
    : device_(ctx.device()),
      interface_(set, name,
                 reflect_spirv(spirv.data(), spirv.size(), VK_SHADER_STAGE_COMPUTE_BIT, name)) {
  VkShaderModuleCreateInfo module_info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  module_info.codeSize = spirv.size_bytes();
  module_info.pCode = spirv.data();
  VkShaderModule module;
  NEPHELE_VK(vkCreateShaderModule(device_, &module_info, nullptr, &module));
  const Specialization spec(specialization);
  VkComputePipelineCreateInfo info{VK_STRUCTURE_TYPE_COMPUTE_PIPELINE_CREATE_INFO};
  info.stage.sType = VK_STRUCTURE_TYPE_PIPELINE_SHADER_STAGE_CREATE_INFO;
  info.stage.stage = VK_SHADER_STAGE_COMPUTE_BIT;
  info.stage.module = module;
  info.stage.pName = "main";
  info.stage.pSpecializationInfo = spec.info();
  info.layout = interface_.pipeline_layout();
  VkResult result = vkCreateComputePipelines(device_, VK_NULL_HANDLE, 1, &info, nullptr, &pipeline_);
  vkDestroyShaderModule(device_, module, nullptr);
  check(result, ("vkCreateComputePipelines(" + name + ")").c_str());
}

Kernel::~Kernel() { vkDestroyPipeline(device_, pipeline_, nullptr); }

PassTimer::PassTimer(Context& ctx, uint32_t max_passes) : ctx_(ctx), max_passes_(max_passes) {
  if (!ctx.has_timestamps()) return;
  VkQueryPoolCreateInfo info{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  info.queryType = VK_QUERY_TYPE_TIMESTAMP;
  info.queryCount = 2 * max_passes;
  NEPHELE_VK(vkCreateQueryPool(ctx.device(), &info, nullptr, &pool_));
}

PassTimer::~PassTimer() {
  if (pool_) vkDestroyQueryPool(ctx_.device(), pool_, nullptr);
}

void PassTimer::reset(VkCommandBuffer cmd) {
  names_.clear();
  if (pool_) vkCmdResetQueryPool(cmd, pool_, 0, 2 * max_passes_);
}

void PassTimer::begin(VkCommandBuffer cmd, const std::string& name) {
  if (names_.size() >= max_passes_) throw RuntimeError("PassTimer: too many passes");
  names_.push_back(name);
  if (pool_)
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, pool_,
                        uint32_t(2 * (names_.size() - 1)));
}

void PassTimer::end(VkCommandBuffer cmd) {
  if (pool_)
    vkCmdWriteTimestamp(cmd, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, pool_,
                        uint32_t(2 * names_.size() - 1));
}

std::vector<std::pair<std::string, double>> PassTimer::results() const {
  std::vector<std::pair<std::string, double>> out;
  if (!pool_ || names_.empty()) return out;
  std::vector<uint64_t> stamps(2 * names_.size());
  // No wait: a frame the host recorded and never submitted has no timings (VK_NOT_READY).
  const VkResult result = vkGetQueryPoolResults(
      ctx_.device(), pool_, 0, uint32_t(stamps.size()), stamps.size() * sizeof(uint64_t),
      stamps.data(), sizeof(uint64_t), VK_QUERY_RESULT_64_BIT);
  if (result == VK_NOT_READY) return out;
  NEPHELE_VK(result);
  for (size_t i = 0; i < names_.size(); ++i)
    out.emplace_back(names_[i],
                     double(stamps[2 * i + 1] - stamps[2 * i]) * ctx_.timestamp_period_ns() * 1e-6);
  return out;
}

void dispatch(VkCommandBuffer cmd, const Kernel& kernel, PassTimer& timer, const std::string& name,
              uint32_t size_x, uint32_t size_y, uint32_t size_z, uint32_t local_x, uint32_t local_y,
              uint32_t local_z) {
  timer.begin(cmd, name);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline());
  kernel.interface().bind(cmd, VK_PIPELINE_BIND_POINT_COMPUTE);
  vkCmdDispatch(cmd, (size_x + local_x - 1) / local_x, (size_y + local_y - 1) / local_y,
                (size_z + local_z - 1) / local_z);
  compute_barrier(cmd);
  timer.end(cmd);
}

void dispatch(VkCommandBuffer cmd, const Kernel& kernel, PassTimer& timer, const std::string& name,
              uint32_t size_x, uint32_t size_y, uint32_t size_z, uint32_t local_x, uint32_t local_y,
              uint32_t local_z, const DispatchConstants& constants) {
  // The range covers every stage (kDrawConstantStages): pushed for all of them, as Vulkan asks.
  vkCmdPushConstants(cmd, kernel.interface().pipeline_layout(), kDrawConstantStages, 0,
                     sizeof(constants), &constants);
  dispatch(cmd, kernel, timer, name, size_x, size_y, size_z, local_x, local_y, local_z);
}

void dispatch_repeated(VkCommandBuffer cmd, const Kernel& kernel, PassTimer& timer,
                       const std::string& name, int count, glm::uvec3 size, glm::uvec3 local,
                       const std::function<DispatchConstants(int)>& constants) {
  timer.begin(cmd, name);
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, kernel.pipeline());
  kernel.interface().bind(cmd, VK_PIPELINE_BIND_POINT_COMPUTE);
  const glm::uvec3 groups = (size + local - 1u) / local;
  for (int k = 0; k < count; ++k) {
    const DispatchConstants values = constants(k);
    vkCmdPushConstants(cmd, kernel.interface().pipeline_layout(), kDrawConstantStages, 0,
                       sizeof(values), &values);
    vkCmdDispatch(cmd, groups.x, groups.y, groups.z);
    compute_barrier(cmd);
  }
  timer.end(cmd);
}

}  // namespace nephele::gpu

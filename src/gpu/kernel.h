// Compute kernels: the bindings of shaders/common/bindings_inc.glsl (descriptor set 0) and the
// modules' own resources (set 1, by name) kept in one table, each pipeline with a layout of only
// the bindings its shaders use, compute pipelines from embedded SPIR-V, and per-pass timestamps.
#pragma once

#include <vulkan/vulkan.h>

#include <functional>
#include <map>
#include <span>
#include <string>
#include <vector>

#include "common/push_constants_inc.glsl"  // DrawConstants, DispatchConstants
#include "gpu/context.h"
#include "gpu/resources.h"
#include "gpu/shader_interface.h"
#include "gpu_bindings.h"  // gpu::Binding, generated from bindings_inc.glsl

namespace nephele::gpu {

// The stages that read the per-draw push constants (DrawConstants, params_inc.glsl): the raster
// passes' shaders and impostor_tiles.comp.
constexpr VkShaderStageFlags kDrawConstantStages =
    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;

// How many frames may be in flight at once (nephele::FrameRenderer): each has its own
// descriptor set, frame parameters, timestamps and output images.
constexpr int kFramesInFlight = 2;

class PassInterface;

// The bindings of every pass, kept as a table on the host (bind_*), and the pipelines'
// interfaces (PassInterface) that read it. When a command buffer starts, use() writes each
// interface's bindings from the table into that interface's Vulkan descriptor sets for the slot:
// one of kFramesInFlight + 1, so a set is never updated while a command buffer that uses it may
// be pending. The last slot is for one-off work that is submitted and waited for.
//
// Two parts (shader_interface.h): set 0, numbered by bindings_inc.glsl (gpu::Binding: bind_buffer,
// bind_storage_image, bind_sampled_image, bind_image), and set 1, a module's own resources,
// keyed by the names its shaders declare them with (bind_module_buffer,
// bind_module_storage_image, bind_module_sampled_image) and never added to bindings_inc.glsl.
// What a pipeline uses and nobody bound is left unwritten (a pass that runs binds it first; the
// validation layer reports a dispatch or draw that reads an unwritten descriptor).
class DescriptorSet {
 public:
  static constexpr int kOneOff = kFramesInFlight;
  explicit DescriptorSet(Context& ctx);
  ~DescriptorSet();
  DescriptorSet(const DescriptorSet&) = delete;
  DescriptorSet& operator=(const DescriptorSet&) = delete;

  // The slot of the last use().
  int current() const { return current_; }
  // Writes the table into every interface's set for slot `index` (a frame's slot, or kOneOff)
  // and makes it current. The command buffers that used that slot before must have completed.
  // Throws RuntimeError when a pipeline uses a binding as another kind of descriptor than the
  // one bound there.
  void use(int index);
  void bind_buffer(Binding binding, const Buffer& buffer, VkDescriptorType type);
  void bind_storage_image(Binding binding, const Texture& texture);
  void bind_sampled_image(Binding binding, const Texture& texture);
  // The texture as a storage image at `written` (where a pass writes it) and sampled at `read`.
  void bind_image(Binding written, Binding read, const Texture& texture);

  // Set 1: a module's resource by the name its shaders give it (a block's name,
  // "GroundFogBlock"; an image's or sampler's variable name, "ground_fog_map"). Every pipeline
  // that declares the name in set 1 reads what is bound here, whatever its binding number
  // there. bind_module_buffer throws RuntimeError when `type` is not a uniform or storage
  // buffer.
  void bind_module_buffer(const std::string& name, const Buffer& buffer, VkDescriptorType type);
  void bind_module_storage_image(const std::string& name, const Texture& texture);
  void bind_module_sampled_image(const std::string& name, const Texture& texture);

 private:
  friend class PassInterface;
  struct Entry {
    VkDescriptorType type{};
    VkDescriptorBufferInfo buffer{};
    VkDescriptorImageInfo image{};
    bool bound = false;
  };
  VkDevice device_;
  int current_ = kOneOff;
  Entry table_[kBindingCount];
  Entry used_[kBindingCount];  // the table as the last use() wrote it
  std::map<std::string, Entry> module_table_;  // set 1, by name
  std::map<std::string, Entry> module_used_;   // set 1 as the last use() wrote it
  std::vector<PassInterface*> interfaces_;  // registered by their constructors
  void set_entry(Binding binding, VkDescriptorType type, const VkDescriptorBufferInfo* buffer,
                 const VkDescriptorImageInfo* image);
};

// One pipeline's view of the table: descriptor-set layouts of the bindings its shaders use
// (shader_interface.h) and the per-draw push constants (DrawConstants), and descriptor sets of
// those layouts for each slot of the DescriptorSet, which writes them. A pipeline with set-1
// bindings has two set layouts, set 0's (empty when it uses none of the global table) and set
// 1's, and two sets a slot (set 0's only when it has bindings); others have set 0 alone.
class PassInterface {
 public:
  // `name` names the pipeline in errors. `bindings` as reflect_spirv or merge_bindings give
  // them; throws RuntimeError for a set-0 number bindings_inc.glsl does not declare.
  PassInterface(DescriptorSet& table, std::string name, std::vector<ShaderBinding> bindings);
  ~PassInterface();
  PassInterface(const PassInterface&) = delete;
  PassInterface& operator=(const PassInterface&) = delete;

  VkPipelineLayout pipeline_layout() const { return pipeline_layout_; }
  // Set `number` (0, or kModuleSet) of the table's current slot; VK_NULL_HANDLE when the
  // pipeline has no bindings in it.
  VkDescriptorSet set(uint32_t number = 0) const { return sets_[table_.current()][number]; }
  const std::vector<ShaderBinding>& bindings() const { return bindings_; }
  // Binds the current slot's sets to `bind_point` with this layout: sets 0 and 1 in one call,
  // or the one of them that has bindings.
  void bind(VkCommandBuffer cmd, VkPipelineBindPoint bind_point) const;

 private:
  friend class DescriptorSet;
  void write(int index);
  void destroy();
  DescriptorSet& table_;
  std::string name_;
  std::vector<ShaderBinding> bindings_;
  // Sets 0 and kModuleSet: their layouts (set 1's only with set-1 bindings; set 0's always,
  // as a pipeline layout needs one for every set below its highest) and whether any binding
  // is in each.
  VkDescriptorSetLayout layouts_[2] = {};
  bool has_set_[2] = {};
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet sets_[kFramesInFlight + 1][2] = {};
};

// The embedded SPIR-V file `spv_name` as a shader module, for the caller to destroy once its
// pipeline is made; throws RuntimeError when this build does not embed it.
VkShaderModule create_shader_module(VkDevice device, const std::string& spv_name);

// Integer specialization constants 0..n-1 set to `values` (kept by reference: they must outlive
// this), for a pipeline stage's pSpecializationInfo (null when there are none).
class Specialization {
 public:
  explicit Specialization(const std::vector<int32_t>& values);
  Specialization(const Specialization&) = delete;
  Specialization& operator=(const Specialization&) = delete;
  const VkSpecializationInfo* info() const { return entries_.empty() ? nullptr : &info_; }

 private:
  std::vector<VkSpecializationMapEntry> entries_;
  VkSpecializationInfo info_{};
};

// A compute pipeline from the embedded SPIR-V file `spv_name` (e.g. "clouds.comp.spv"),
// with integer specialization constants 0..n-1 set to `specialization`.
class Kernel {
 public:
  Kernel(Context& ctx, DescriptorSet& set, const std::string& spv_name,
         const std::vector<int32_t>& specialization = {});
  // The same from SPIR-V words the caller holds (a test's own shader), named `name` in errors;
  // the words need not outlive the constructor.
  Kernel(Context& ctx, DescriptorSet& set, std::span<const uint32_t> spirv, const std::string& name,
         const std::vector<int32_t>& specialization = {});
  ~Kernel();
  Kernel(const Kernel&) = delete;
  Kernel& operator=(const Kernel&) = delete;
  VkPipeline pipeline() const { return pipeline_; }
  const PassInterface& interface() const { return interface_; }

 private:
  VkDevice device_;
  PassInterface interface_;
  VkPipeline pipeline_ = VK_NULL_HANDLE;
};

// Timestamps around passes of one command buffer.
class PassTimer {
 public:
  PassTimer(Context& ctx, uint32_t max_passes);
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;
  void reset(VkCommandBuffer cmd);
  void begin(VkCommandBuffer cmd, const std::string& name);
  void end(VkCommandBuffer cmd);
  // After the command buffer completed: (name, milliseconds) per pass; empty when the results
  // are not available (a command buffer not submitted, or not yet complete).
  std::vector<std::pair<std::string, double>> results() const;

 private:
  Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t max_passes_;
  std::vector<std::string> names_;
};

// Binds `kernel` with its set of the current slot, dispatches ceil(size / local) groups, adds a
// barrier, and times it: the body of every compute pass.
void dispatch(VkCommandBuffer cmd, const Kernel& kernel, PassTimer& timer, const std::string& name,
              uint32_t size_x, uint32_t size_y, uint32_t size_z, uint32_t local_x, uint32_t local_y,
              uint32_t local_z);
// The same with the dispatch's own values pushed first (DispatchConstants: a shader including
// dispatch_inc.glsl reads them; it must be dispatched through this).
void dispatch(VkCommandBuffer cmd, const Kernel& kernel, PassTimer& timer, const std::string& name,
              uint32_t size_x, uint32_t size_y, uint32_t size_z, uint32_t local_x, uint32_t local_y,
              uint32_t local_z, const DispatchConstants& constants);
// `count` dispatches of one kernel, each after the last (a barrier between them) and timed
// together as one pass, dispatch k with constants(k) pushed first (an iterative solve's
// sweeps).
void dispatch_repeated(VkCommandBuffer cmd, const Kernel& kernel, PassTimer& timer,
                       const std::string& name, int count, glm::uvec3 size, glm::uvec3 local,
                       const std::function<DispatchConstants(int)>& constants);

}  // namespace nephele::gpu

// Compute kernels: one descriptor-set layout shared by every pass (shaders/common/
// bindings_inc.glsl), compute pipelines from embedded SPIR-V, and per-pass timestamps.
#pragma once

#include <vulkan/vulkan.h>

#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/resources.h"

namespace nephele::gpu {

// Bindings of bindings_inc.glsl.
enum Binding : uint32_t {
  kFrameParams = 0,
  kBaseNoiseOut = 1,
  kDetailNoiseOut = 2,
  kWeatherStates = 3,
  kBaseNoise = 4,
  kDetailNoise = 5,
  kWeatherMap = 6,
  kSkyViewOut = 7,
  kSkyView = 8,
  kLightVolumeOut = 9,
  kLightVolume = 10,
  kMarchAOut = 11,
  kMarchBOut = 12,
  kMarchA = 13,
  kMarchB = 14,
  kCloudsAOut = 15,
  kCloudsBOut = 16,
  kCloudsA = 17,
  kCloudsB = 18,
  kHistoryA = 19,
  kHistoryB = 20,
  kColorOut = 21,
  kRangeLo = 22,
  kRangeHi = 23,
  kStars = 24,
  kColor = 25,
  kTransmittanceLutOut = 26,
  kTransmittanceLut = 27,
  kMsLutOut = 28,
  kMsLut = 29,
  kAerialPerspectiveOut = 30,
  kAerialPerspective = 31,
  kReferencePsiOut = 32,
  kReferencePsi = 33,
  kReferenceSkyOut = 34,
  kReferenceSky = 35,
  kCurlNoiseOut = 36,
  kCurlNoise = 37,
  kGroundLightOut = 38,
  kGroundLight = 39,
  kDisplayOut = 40,
  kWeatherMapOut = 41,
  kVoxelAtlas = 42,
  kVoxelPages = 43,
  kPathSum = 44,
  kPathSquares = 45,
  kPathMajorant = 46,
  kMsFieldOut = 47,
  kMsField = 48,
  kMeter = 49,
  kParticles = 50,
  kParticleTextures = 51,
  kParticleLayer = 52,
  kParticleDepth = 53,
  kImpostors = 54,
  kImpostorAtlas = 55,
  kImpostorTileSlots = 56,
  kImpostorScratch = 57,
  kImpostorAtlasOut = 58,
  kImpostorTileJobs = 59,
  kParticleSplats = 60,
  kParticleLightClouds = 61,
  kParticleLights = 62,
  kNishitaVolumeOut = 63,
  kNishitaVolume = 64,
  kPostTemp = 65,
  kLightShaftsOut = 66,
  kLightShafts = 67,
  kTerrainHeights = 68,
  kTerrainOut = 69,
  kTerrain = 70,
  kTerrainAlbedo = 71,
  kHostScene = 72,
  kHostLighting = 73,
  kCloudShadowMapOut = 74,
  kEnvironmentOut = 75,
  kBindingCount
};

// The descriptor type of a binding as bindings_inc.glsl declares it (VK_DESCRIPTOR_TYPE_MAX_ENUM
// past the end).
VkDescriptorType binding_type(Binding binding);

// The stages that read the per-draw push constants (DrawConstants, params_inc.glsl): the raster
// passes' shaders and impostor_tiles.comp.
constexpr VkShaderStageFlags kDrawConstantStages =
    VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;

// How many frames may be in flight at once (nephele::FrameRenderer): each has its own
// descriptor set, frame parameters, timestamps and output images.
constexpr int kFramesInFlight = 2;

// The bindings of every pass, kept as a table on the host and written into one of
// kFramesInFlight + 1 Vulkan descriptor sets when a command buffer starts (use()): a set is
// never updated while a command buffer that uses it may be pending. The last set is for
// one-off work that is submitted and waited for.
class DescriptorSet {
 public:
  static constexpr int kOneOff = kFramesInFlight;
  explicit DescriptorSet(Context& ctx);
  ~DescriptorSet();
  DescriptorSet(const DescriptorSet&) = delete;
  DescriptorSet& operator=(const DescriptorSet&) = delete;

  VkPipelineLayout pipeline_layout() const { return pipeline_layout_; }
  // The set that dispatches bind: the one of the last use().
  VkDescriptorSet set() const { return sets_[current_]; }
  // Writes the table into set `index` (a frame's slot, or kOneOff) and makes it current.
  // The command buffers that used it before must have completed.
  void use(int index);
  void bind_buffer(Binding binding, const Buffer& buffer, VkDescriptorType type);
  void bind_storage_image(Binding binding, const Texture& texture);
  void bind_sampled_image(Binding binding, const Texture& texture);
  // The texture as a storage image at `written` (where a pass writes it) and sampled at `read`.
  void bind_image(Binding written, Binding read, const Texture& texture);

 private:
  VkDevice device_;
  VkDescriptorSetLayout layout_ = VK_NULL_HANDLE;
  VkPipelineLayout pipeline_layout_ = VK_NULL_HANDLE;
  VkDescriptorPool pool_ = VK_NULL_HANDLE;
  VkDescriptorSet sets_[kFramesInFlight + 1] = {};
  int current_ = kOneOff;
  struct Entry {
    VkDescriptorType type{};
    VkDescriptorBufferInfo buffer{};
    VkDescriptorImageInfo image{};
    bool bound = false;
  };
  Entry table_[kBindingCount];
  void set_entry(Binding binding, VkDescriptorType type, const VkDescriptorBufferInfo* buffer,
                 const VkDescriptorImageInfo* image);
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
  Kernel(Context& ctx, const DescriptorSet& set, const std::string& spv_name,
         const std::vector<int32_t>& specialization = {});
  ~Kernel();
  Kernel(const Kernel&) = delete;
  Kernel& operator=(const Kernel&) = delete;
  VkPipeline pipeline() const { return pipeline_; }

 private:
  VkDevice device_;
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

// Binds `kernel` with the shared set, dispatches ceil(size / local) groups, adds a barrier,
// and times it: the body of every pass.
void dispatch(VkCommandBuffer cmd, const Kernel& kernel, const DescriptorSet& set,
              PassTimer& timer, const std::string& name, uint32_t size_x, uint32_t size_y,
              uint32_t size_z, uint32_t local_x, uint32_t local_y, uint32_t local_z);

}  // namespace nephele::gpu

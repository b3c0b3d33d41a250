// The noise module: the cloud shapes' base noise (128^3), detail noise (32^3 and its mip
// levels) and curl noise (128^2), made once per noise seed at the first frame (a host wait,
// about 1.5 s on a CPU: reported by RendererOptions::progress) and kept. The base noise, most
// of that wait, is kept on disk too (render/disk_cache.h) and read back by the next process.
#pragma once

#include <filesystem>
#include <optional>
#include <span>
#include <string>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/render_module.h"

namespace nephele {

constexpr uint32_t kBaseNoiseSize = 128;    // seed 000, 2.2.2: base shape noise 128^3
constexpr uint32_t kDetailNoiseSize = 32;   // detail noise 32^3
constexpr uint32_t kDetailNoiseLevels = 6;  // and its mip levels down to 1^3 (far clouds)
constexpr uint32_t kCurlNoiseSize = 128;    // curl noise 128^2

// The base noise's file in the disk cache: named by what makes its texels, the shader's SPIR-V,
// the device and the seed.
std::string noise_cache_name(std::span<const uint32_t> spirv, const std::string& device,
                             uint32_t seed);

class NoiseModule : public RenderModule {
 public:
  static constexpr int kTextures = 3;  // base, detail, curl

  NoiseModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;
  // Whether the textures are not (yet) those of `seed`.
  bool stale(uint32_t seed) const { return seed_ != seed; }
  // Records texture `i` (0 base, 1 detail with its mip levels, 2 curl) for the seed in the
  // frame parameters (FrameParams::size.w).
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer, int i);
  // The textures recorded have been made for `seed`.
  void made(uint32_t seed) { seed_ = seed; }
  // Fills the base noise texture for `seed` from the disk cache: the file read, or nothing
  // when there is no cache or no valid file in it (then record texture 0).
  std::optional<std::filesystem::path> load_base(uint32_t seed);
  // Keeps the base noise texture, made for `seed`, in the disk cache (where there is one).
  void store_base(uint32_t seed);

  const gpu::Texture& base() const { return base_; }
  const gpu::Texture& detail() const { return detail_; }
  const gpu::Texture& curl() const { return curl_; }

 private:
  // The cache's file for `seed` (empty: no cache).
  std::filesystem::path cache_file(uint32_t seed) const;

  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Kernel base_kernel_, detail_kernel_, curl_kernel_;
  gpu::Texture base_, detail_, curl_;
  std::optional<uint32_t> seed_;
};

}  // namespace nephele

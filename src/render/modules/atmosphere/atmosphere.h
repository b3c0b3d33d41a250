// The atmosphere module: Hillaire's transmittance and multiple-scattering tables and the
// multiple-scattering light field (transmittance_lut.comp, multiscattering_lut.comp,
// ms_field.comp), rebuilt when the atmosphere changes (a
// host wait of about 0.2 s on a CPU) and read back for the lighting computed on the CPU.
#pragma once

#include <memory>
#include <optional>
#include <vector>

#include "gpu/kernel.h"
#include "nephele/scene.h"
#include "render/frame_params.h"
#include "render/render_module.h"

namespace nephele {

class AtmosphereModule : public RenderModule {
 public:
  AtmosphereModule(gpu::Context& ctx, gpu::DescriptorSet& set);
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;
  // Whether the tables are not (yet) those of `atmosphere`.
  bool stale(const AtmosphereParams& atmosphere) const { return built_ != atmosphere; }
  // Records both tables for the atmosphere in the frame parameters.
  void record(VkCommandBuffer cmd, gpu::PassTimer& timer);
  // After the recorded work completed: keeps their copy on the host for `atmosphere`.
  void made(const AtmosphereParams& atmosphere);
  // The host's copy, for the per-frame lighting (make_frame_params).
  const AtmosphereTables& tables() const { return tables_; }

 private:
  gpu::Context& ctx_;
  gpu::DescriptorSet& set_;
  gpu::Kernel transmittance_kernel_, ms_kernel_;
  std::vector<std::unique_ptr<gpu::Kernel>> field_kernels_;  // one per iteration
  gpu::Texture transmittance_, ms_, field_;
  std::optional<AtmosphereParams> built_;
  AtmosphereTables tables_;
};

}  // namespace nephele

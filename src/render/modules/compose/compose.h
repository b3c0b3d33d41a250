// The compose module: the final image from the sky, the cloud layer, the particle layer, the
// terrain (or the host's scene) and the shafts (compose.comp, or compose_reference.comp's sky
// with atmosphere.model = reference), then the stars over it (stars.comp). Its kernels and
// images live in GpuState (passes.h), which the one-off passes share.
#pragma once

#include "render/passes.h"
#include "render/render_module.h"

namespace nephele {

class ComposeModule : public RenderModule {
 public:
  explicit ComposeModule(GpuState& state) : state_(state) {}
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

 private:
  GpuState& state_;
};

// The display module: the exposure meter of the final image (meter.comp) and, when the frame
// wants it, the display image (tonemap.comp).
class DisplayModule : public RenderModule {
 public:
  explicit DisplayModule(GpuState& state) : state_(state) {}
  void add_passes(FrameGraph& graph, const FrameSetup& frame) override;

 private:
  GpuState& state_;
};

}  // namespace nephele

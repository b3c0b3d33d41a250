// The renderer for stills and animations: each frame recorded by the frame API
// (FrameRenderer) into a command buffer of its own context, submitted, waited for, read back.
#include "nephele/renderer.h"

#include "nephele/cloud_query.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "render/frame_renderer_impl.h"

namespace nephele {

struct Renderer::Impl {
  explicit Impl(const RendererOptions& options) : frames(options) {}
  FrameRenderer frames;
};

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {}

Renderer::~Renderer() = default;

const std::string& Renderer::device_name() const { return impl_->frames.device_name(); }

int Renderer::validation_messages() const { return impl_->frames.validation_messages(); }

Frame Renderer::render(const Scene& scene) { return render_frame(scene, true, true); }

FilmLayers Renderer::render_layers(const Scene& scene) {
  FilmLayers layers;
  layers.frame = render(scene);
  FrameRenderer::Impl& f = *impl_->frames.impl_;
  layers.sky = f.compose_layer(scene, 1);
  layers.clouds = f.compose_layer(scene, 2);
  layers.clouds_depth_m = f.compose_layer(scene, 3);
  return layers;
}

Frame Renderer::render_next(const Scene& scene, bool read_back) {
  return render_frame(scene, false, read_back);
}

Frame Renderer::render_frame(const Scene& scene, bool still, bool read_back) {
  const auto start = std::chrono::steady_clock::now();
  FrameRenderer::Impl& f = *impl_->frames.impl_;
  FrameImages images;
  f.ctx.submit_and_wait([&](VkCommandBuffer cmd) { 
    images = f.record_frame(cmd, scene, FrameOptions{still, false});
  });
  f.collect(images.slot);
  Frame frame;
  if (read_back) frame = f.download_last(scene);
  const FrameStats measured = frame.stats;
  frame.stats = *f.completed;
  if (read_back) {
    frame.stats.mean_luminance = measured.mean_luminance;
    frame.stats.cloud_cover_fraction = measured.cloud_cover_fraction;
  }
  if (still && read_back && scene.clouds.model == CloudModel::Nephele) {  // nephele's clouds
    double ms = 0.0;
    frame.stats.sky_cover_fraction = f.measure_sky_cover(f.last_params, scene.quality.mode, ms);
    frame.stats.passes.push_back({"sky_dome", ms});
  }
  frame.stats.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return frame;
}

CloudQuery Renderer::cloud_query(const Scene& scene) { return impl_->frames.cloud_query(scene); }

CloudProfile Renderer::cloud_profile(const Scene& scene) {
  return impl_->frames.impl_->cloud_profile(scene);
}

ReferenceImage Renderer::render_reference(const Scene& scene, const ReferenceOptions& options) {
  return impl_->frames.impl_->render_reference(scene, options);
}

int sky_cover_oktas(double fraction) {
  if (fraction < 0.01) return 0;
  if (fraction > 0.99) return 8;
  return std::clamp(int(std::lround(fraction * 8.0)), 1, 7);
}

}  // namespace nephele

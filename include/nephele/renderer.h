// nephele — the renderer: Vulkan compute passes behind a plain C++ interface.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "nephele/image.h"
#include "nephele/scene.h"

namespace nephele {

struct RendererOptions {
  std::string device;       // substring of the device name to pick; empty = best available
  bool validation = false;  // enable VK_LAYER_KHRONOS_validation; messages are counted
  bool verbose = false;     // print device choice and pass timings to stderr
};

struct PassTiming {
  std::string name;
  double ms = 0.0;
};

struct FrameStats {
  std::string device;            // name of the Vulkan device used
  int width = 0;
  int height = 0;
  double frame_ms = 0.0;         // GPU time of the frame's passes (timestamps)
  double wall_ms = 0.0;          // host wall-clock time of render()
  double mean_luminance = 0.0;   // mean relative luminance of the linear HDR image
  double cloud_cover_fraction = 0.0;  // share of above-horizon pixels with cloud T < 0.5
  std::vector<PassTiming> passes;
};

struct Frame {
  Image color;          // linear HDR radiance (rgb), a = 1
  Image clouds;         // per pixel: rgb in-scattered cloud radiance, a = cloud transmittance
  FrameStats stats;
};

class Renderer {
 public:
  explicit Renderer(const RendererOptions& options = {});
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Validates the scene (throws InputError), then renders one frame.
  // Noise and weather textures are cached and rebuilt only when their parameters change.
  Frame render(const Scene& scene);

  const std::string& device_name() const;
  // Number of validation-layer messages (warnings and errors) seen so far.
  int validation_messages() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace nephele

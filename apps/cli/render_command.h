// `nephele render`: one frame of a scene to PNG or EXR, with optional stats as JSON.
#pragma once

#include <string>

#include "nephele/renderer.h"
#include "scene_flags.h"

namespace CLI {
class App;
}

namespace nephele::cli {

struct RenderOptions {
  SceneFlags scene;
  std::string output = "nephele.png";
  std::string stats_json;  // empty: none; "-": standard output, instead of the image paths
  bool exr_float = false;  // EXR as 32-bit floats (default half, clamped to 65504)
  int frames = 1;          // a sequence: frame i at time_s + i step_s, files numbered _0000 ...
  float step_s = 1.0f;
  std::string device;      // substring of the Vulkan device name
  bool verbose = false;
  bool validation = false;
};

void add_render_flags(CLI::App& cmd, RenderOptions& options);

// The path of frame `index` of a sequence: "_0007" before the extension ("day.png" ->
// "day_0007.png"); `path` itself for a single frame.
std::string frame_path(const std::string& path, int index, int frames);
int run_render(const RenderOptions& options);

// Flags every command that renders shares: --device, --verbose, --validation.
void add_device_flags(CLI::App& cmd, std::string& device, bool& verbose, bool& validation);

// Writes `text` to standard output when `path` is "-", else atomically to the file.
void write_text_output(const std::string& path, const std::string& text);

// The stats of a frame as JSON (image: the image written, device, width, height, frame_ms,
// mean_luminance, cloud_cover_fraction, sky_cover_fraction and oktas for still images,
// wall_ms, passes).
std::string stats_to_json(const FrameStats& stats, const std::string& image_path);

}  // namespace nephele::cli

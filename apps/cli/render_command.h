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
  std::string stats_json;  // empty: none
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

// Throws InputError naming `parameter` if a file cannot be created at `path` (missing or
// unwritable folder, or a folder by that name). Writes nothing.
void check_writable_file(const std::string& path, const std::string& parameter);

// Writes `text` to `path` through a temporary file and a rename: all or nothing.
void write_text_file(const std::string& path, const std::string& text);

// The stats of a frame as JSON (device, width, height, frame_ms, mean_luminance,
// cloud_cover_fraction, sky_cover_fraction and oktas for still images, wall_ms, passes).
std::string stats_to_json(const FrameStats& stats);

}  // namespace nephele::cli

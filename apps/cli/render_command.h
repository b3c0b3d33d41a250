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
  bool layers = false;     // a multi-layer EXR: the image, sky, clouds, clouds.depth_m (film.h)
  bool holdout = false;    // with layers: the image is the sky with the clouds cut out
  int frames = 1;          // a sequence: frame i at time_s + i step_s, files numbered _0000 ...
  float step_s = 1.0f;
  bool frames_given = false, step_given = false;  // whether --frames, --step were typed
  // The first frame's number: frame i of a sequence is numbered start_frame + i and is at that
  // many steps (or 1 / fps) of scene and path time.
  int start_frame = 0;
  // A flight (camera_path.h): frame i has the path's camera at t = (start_frame + i) / fps and
  // the scene at time_s + (start_frame + i) / fps, rendered as an animation (render_next, the
  // temporal history kept) or, with still_frames, each as a still image. Without --frames, up to
  // the path's end.
  std::string camera_path;
  double fps = 30.0;
  bool fps_given = false;
  bool still_frames = false;
  // The reference path tracer (Renderer::render_reference) of the scene's [lab] grid: the mean
  // (PNG tone-mapped, or EXR) and, in an EXR, its variance as the layer "variance".
  bool reference = false;
  int spp = 64;
  double time_limit_s = 0.0;
  int max_bounces = -1;                  // --reference: scatterings after the first (-1 auto)
  std::string majorant_grid = "auto";  // auto, bricks or none (MajorantGrid)
  bool progress = false;   // a progress bar even when standard error is not a terminal
  bool quiet = false;      // no progress and no informational lines on standard error
  std::string device;      // substring of the Vulkan device name
  bool verbose = false;
  bool validation = false;
};

void add_render_flags(CLI::App& cmd, RenderOptions& options);

// The path of frame number `number` of a sequence: `path` with its printf-style %d or %0Nd
// filled in ("out/f_%04d.png" -> "out/f_0007.png", %% is a %), or without one "_0007" before
// the extension ("day.png" -> "day_0007.png"). Throws InputError naming `parameter` for any
// other % conversion, or more than one.
std::string sequence_frame_path(const std::string& path, int number,
                                const std::string& parameter = "--output");
// `path` itself for a single frame (frames <= 1), else sequence_frame_path(path, index).
std::string frame_path(const std::string& path, int index, int frames);
int run_render(const RenderOptions& options);

// Flags every command that renders shares: --device, --verbose, --validation.
void add_device_flags(CLI::App& cmd, std::string& device, bool& verbose, bool& validation);

// --progress and --quiet (which excludes --verbose, registered before).
void add_progress_flags(CLI::App& cmd, bool& progress, bool& quiet);

// Writes `text` to standard output when `path` is "-", else atomically to the file.
void write_text_output(const std::string& path, const std::string& text);

}  // namespace nephele::cli

// `nephele bench`, real-time part: frame rate of the temporal renderer with a still and a
// flying camera, its speed-up over the seed's algorithm, and its error against a
// full-resolution, non-reprojected, high-step-count reference of the same views.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>

#include "nephele/renderer.h"

namespace nephele::cli {

struct RealtimeSettings {
  // Timed frames with a still camera (after two march cycles) and of the flight: 10 s of
  // animation, long enough for the weather to move on five states and the light volume to be
  // rebuilt, so that the percentiles see them.
  int static_frames = 200;
  int moving_frames = 200;
  int error_frames = 3;      // flight frames compared with a reference
  bool errors = true;        // false: no comparison with the reference (errors are null)
  float speed_mps = 100.0f;  // flight speed along the view's heading
  float turn_deg_s = 20.0f;  // yaw rate
  float frame_dt_s = 0.05f;  // animation time per frame (the moving target: 20 frames/s)
  // Called after each of the max(static_frames, moving_frames) timed steps and each of the
  // error_frames comparisons (progress).
  std::function<void()> on_step;
};

// The scene a reference for `scene` is rendered from: every pixel, full resolution,
// 4x the primary steps, every light ray marched with 64 steps (no light volume).
Scene reference_scene(const Scene& scene);

// Runs the measurements on `renderer` (a second renderer draws the references) and returns
// static_fps, moving_fps, static_error, moving_error, speedup_vs_baseline, the underlying
// milliseconds and the device.
nlohmann::json measure_realtime(Renderer& renderer, const RendererOptions& options,
                                const Scene& scene, const RealtimeSettings& settings);

}  // namespace nephele::cli

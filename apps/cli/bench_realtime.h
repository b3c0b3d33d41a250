// `nephele bench`, real-time part: frame rate of the temporal renderer with a still and a
// flying camera, its speed-up over the seed's algorithm, and its error against a
// full-resolution, non-reprojected, high-step-count reference of the same views.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <vector>

#include "nephele/renderer.h"

namespace nephele::cli {

struct RealtimeSettings {
  // Timed frames with a still camera (after two march cycles) and of the flight: 10 s of
  // animation, long enough for the weather to move on five states and the light volume to be
  // rebuilt, so that the percentiles see them.
  int static_frames = 200;
  int moving_frames = 200;
  int error_frames = 3;      // flight frames compared with a reference
  // Frames of a flight from a still, each compared with a still of its moment (the issue's
  // target: none further from its still than twice the mean of the last ten); 0: none.
  int still_flight_frames = 20;
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

// The scene lit as the seed lights clouds and as nephele's default did before issue 42: the
// seed's lighting and optics (clouds.lighting and clouds.optics "seed"), 6 light steps, no
// light shafts (quality.light_shafts "off"). The bench times the still camera with it too,
// for the cost of the physical lighting as a ratio measured in one run (cost_vs_seed_lit;
// issue 42's bound: 1.15 on lavapipe at 900x600).
Scene seed_lit_scene(const Scene& scene);

// seed_lit_scene with the scene's own optics (the droplets' clouds, lit as the seed lights
// them): the bench's cost_vs_seed_lighting, the default's cost over the seed's lighting on
// the same clouds. What cost_vs_seed_lit adds to it is the optics' (clouds of real droplets
// are thinner than the seed's, so the march crosses more of them before they are opaque).
Scene seed_lighting_scene(const Scene& scene);

// The scene in heavy rain (20 mm/h, 3.3 km of visibility in it) falling everywhere under the
// layer (precipitation.shafts off): the bench times the still camera with it too, for the
// rain's cost as a ratio measured in one run (cost_of_rain; issue 43's bound on lavapipe at
// 900x600: 1.2).
Scene heavy_rain_scene(const Scene& scene);

// Runs the measurements on `renderer` (a second renderer draws the references) and returns
// static_fps, moving_fps, static_error, moving_error, speedup_vs_baseline, cost_vs_seed_lit
// (the still camera's median over seed_lit_scene's, seed_lit_ms), cost_vs_seed_lighting (over
// seed_lighting_scene's, seed_lighting_ms), cost_of_rain (heavy_rain_scene's median over the
// still camera's; rain_ms, its percentiles and worst frame), each with its passes' times, the
// underlying milliseconds and the device; with errors, also flight_from_still (each frame's
// luminance_error against a still of its moment, from frame 1) and flight_from_still_ratio
// (the largest over the mean of the last ten).
nlohmann::json measure_realtime(Renderer& renderer, const RendererOptions& options,
                                const Scene& scene, const RealtimeSettings& settings);

// A flight of settings.still_flight_frames frames from a still of `start`, each frame against
// a still of its moment (another renderer's).
struct FlightFromStill {
  std::vector<double> errors;  // frames 1 ... n
  double ratio = 0.0;          // the largest over the mean of the last ten (or all, if fewer)
};
FlightFromStill flight_from_still(const RendererOptions& options, const Scene& start,
                                  const RealtimeSettings& settings);

}  // namespace nephele::cli

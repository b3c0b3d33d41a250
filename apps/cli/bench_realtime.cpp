#include "bench_realtime.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numeric>
#include <vector>
#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "nephele/image_compare.h"

namespace nephele::cli {

namespace {

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Host wall time (ms) of the frames, each submitted and waited for, no read-back, and the
// device time of each pass. Medians: on a shared machine a few frames stall for reasons of
// their own, and the median is what the renderer does; the mean is kept beside it.
struct Timing {
  std::vector<double> wall_ms, gpu_ms;
  std::map<std::string, std::vector<double>> pass_ms;
  void add(const FrameStats& s) {
    wall_ms.push_back(s.wall_ms);
    gpu_ms.push_back(s.frame_ms);
    for (const PassTiming& p : s.passes) pass_ms[p.name].push_back(p.ms);
  }
  double median_wall() const { return median(wall_ms); }
  double mean_wall() const {
    return wall_ms.empty() ? 0.0
                           : std::accumulate(wall_ms.begin(), wall_ms.end(), 0.0) / wall_ms.size();
  }
  double median_gpu() const { return median(gpu_ms); }
  nlohmann::json passes() const {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, ms] : pass_ms) j[name] = median(ms);
    return j;
  }
};

// The camera `t_s` seconds into the flight: straight along the initial heading's horizontal
// part at `speed_mps`, the view turning about the vertical at `turn_deg_s`.
Scene flight_at(const Scene& start, const RealtimeSettings& f, float t_s) {
  Scene s = start;
  glm::vec3 heading(start.camera.view_dir.x, start.camera.view_dir.y, 0.0f);
  if (glm::length(heading) < 1e-6f) heading = glm::vec3(0.0f, 1.0f, 0.0f);
  heading = glm::normalize(heading);
  s.camera.position_m += heading * f.speed_mps * t_s;
  const float yaw = glm::radians(f.turn_deg_s * t_s);
  const glm::vec3 v = start.camera.view_dir;
  s.camera.view_dir = glm::vec3(v.x * std::cos(yaw) - v.y * std::sin(yaw),
                                v.x * std::sin(yaw) + v.y * std::cos(yaw), v.z);
  s.time_s = start.time_s + t_s;
  return s;
}

double error_against_reference(Renderer& reference, const Scene& scene, const Image& image) {
  return luminance_error(image, reference.render(reference_scene(scene)).color);
}

}  // namespace

Scene reference_scene(const Scene& scene) {
  Scene r = scene;
  r.quality.march_stride = 1;
  r.quality.cloud_downsample = 1;
  r.quality.primary_steps = std::min(4 * scene.quality.primary_steps, 1024);
  r.quality.light_steps = 64;    // every light ray marched to the top of the layer,
  r.quality.light_volume_km = 0;  // no light volume
  return r;
}

nlohmann::json measure_realtime(Renderer& renderer, const RendererOptions& options,
                                const Scene& base, const RealtimeSettings& f) {
  Renderer reference(options);
  const int cycle = base.quality.march_stride * base.quality.march_stride;
  nlohmann::json out;

  // Still camera, clouds drifting with the wind: converge for two march cycles, then time.
  Scene scene = base;
  scene.quality.mode = MarchMode::Default;
  renderer.render(scene);
  Timing still;
  for (int i = 0; i < 2 * cycle + f.static_frames; ++i) {
    scene.time_s += f.frame_dt_s;
    const FrameStats stats = renderer.render_next(scene, false).stats;
    if (i >= 2 * cycle) still.add(stats);
  }
  scene.time_s += f.frame_dt_s;
  const double static_error =
      error_against_reference(reference, scene, renderer.render_next(scene).color);

  // The flight: a cycle to fill the history, then timed frames; some frames are read back
  // (untimed) and compared with their references.
  const Scene start = base;
  renderer.render(start);
  Timing moving;
  double moving_error = 0.0;
  int compared = 0;
  const int total = cycle + f.moving_frames;
  const int every = std::max(1, f.moving_frames / std::max(f.error_frames, 1));
  for (int i = 1; i <= total; ++i) {
    const Scene s = flight_at(start, f, float(i) * f.frame_dt_s);
    const bool compare = i > cycle && (i - cycle) % every == 0 && compared < f.error_frames;
    const Frame frame = renderer.render_next(s, compare);
    if (compare) {
      const double e = error_against_reference(reference, s, frame.color);
      std::printf("  flight frame %d: error %.4f\n", i, e);
      moving_error = std::max(moving_error, e);
      ++compared;
    } else if (i > cycle) {
      moving.add(frame.stats);
    }
  }

  // The seed's algorithm on the same still view (every pixel, every frame).
  Scene baseline = base;
  baseline.quality.mode = MarchMode::Baseline;
  renderer.render_next(baseline, false);  // warm-up
  Timing seed;
  for (int i = 0; i < 3; ++i) seed.add(renderer.render_next(baseline, false).stats);

  out["device"] = renderer.device_name();
  out["width"] = base.output.width;
  out["height"] = base.output.height;
  out["static_ms"] = still.median_wall();
  out["static_mean_ms"] = still.mean_wall();
  out["static_gpu_ms"] = still.median_gpu();
  out["static_passes_ms"] = still.passes();
  out["static_fps"] = 1000.0 / still.median_wall();
  out["moving_ms"] = moving.median_wall();
  out["moving_mean_ms"] = moving.mean_wall();
  out["moving_gpu_ms"] = moving.median_gpu();
  out["moving_passes_ms"] = moving.passes();
  out["moving_fps"] = 1000.0 / moving.median_wall();
  out["baseline_ms"] = seed.median_wall();
  out["baseline_fps"] = 1000.0 / seed.median_wall();
  out["speedup_vs_baseline"] = seed.median_wall() / still.median_wall();
  out["static_error"] = static_error;
  out["moving_error"] = moving_error;
  out["flight"] = {{"speed_mps", f.speed_mps},
                   {"turn_deg_s", f.turn_deg_s},
                   {"frame_dt_s", f.frame_dt_s}};
  return out;
}

}  // namespace nephele::cli

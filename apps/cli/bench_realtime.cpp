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
#include "sample_stats.h"

namespace nephele::cli {

namespace {

// Host wall time (ms) of the frames, each submitted and waited for, no read-back, and the
// device time of each pass. Real time means every frame: the median, p95, p99 and the worst
// frame, and every frame's time for the trace.
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
  // Frames in which `pass` ran (a rebuild spread over frames runs in many).
  int frames_with(const std::string& pass) const {
    const auto it = pass_ms.find(pass);
    return it == pass_ms.end() ? 0 : int(it->second.size());
  }
  void write(nlohmann::json& out, const std::string& prefix) const {
    out[prefix + "_ms"] = median_wall();
    out[prefix + "_mean_ms"] = mean_wall();
    out[prefix + "_p50_ms"] = percentile(wall_ms, 0.50);
    out[prefix + "_p95_ms"] = percentile(wall_ms, 0.95);
    out[prefix + "_p99_ms"] = percentile(wall_ms, 0.99);
    out[prefix + "_max_ms"] = percentile(wall_ms, 1.0);
    out[prefix + "_gpu_ms"] = median_gpu();
    out[prefix + "_passes_ms"] = passes();
    out[prefix + "_fps"] = 1000.0 / median_wall();
    out[prefix + "_frames"] = int(wall_ms.size());
    out[prefix + "_light_volume_frames"] = frames_with("light_volume");
    out[prefix + "_weather_frames"] = frames_with("weather");
    out["frame_times_ms"][prefix] = wall_ms;
  }
  // Each pass's device time per frame: the median over the frames where it ran, times the
  // share of frames where it ran (passes such as the sky-view LUT run only now and then).
  nlohmann::json passes() const {
    nlohmann::json j = nlohmann::json::object();
    for (const auto& [name, ms] : pass_ms)
      j[name] = median(ms) * double(ms.size()) / double(wall_ms.size());
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

FlightFromStill flight_from_still(const RendererOptions& options, const Scene& start,
                                  const RealtimeSettings& f) {
  Renderer flight(options);
  Renderer stills(options);
  FlightFromStill out;
  flight.render(start);
  for (int i = 1; i <= f.still_flight_frames; ++i) {
    const Scene s = flight_at(start, f, float(i) * f.frame_dt_s);
    out.errors.push_back(luminance_error(flight.render_next(s).color, stills.render(s).color));
  }
  if (out.errors.empty()) return out;
  const size_t last = std::min<size_t>(10, out.errors.size());
  const double settled =
      std::accumulate(out.errors.end() - long(last), out.errors.end(), 0.0) / double(last);
  out.ratio = *std::max_element(out.errors.begin(), out.errors.end()) / std::max(settled, 1e-12);
  return out;
}

Scene reference_scene(const Scene& scene) {
  Scene r = scene;
  r.quality.march_stride = 1;
  r.quality.cloud_downsample = 1;
  r.quality.primary_steps = std::min(4 * scene.quality.primary_steps, 1024);
  r.quality.light_steps = 64;  // every light ray marched to the top of the layer,
  // no light volume; but the diffusion light's field is built from it (without one the clouds
  // would take the two-stream light), so the reference keeps it and judges the march's steps,
  // its stride and its history against the same field.
  if (scene.clouds.lighting != "diffusion") r.quality.light_volume_km = 0;
  return r;
}

Scene seed_lighting_scene(const Scene& scene) {
  Scene s = scene;
  s.clouds.lighting = "seed";
  s.quality.light_steps = 6;
  s.quality.light_shafts = "off";  // as before issue 42, too
  return s;
}

Scene seed_lit_scene(const Scene& scene) {
  Scene s = seed_lighting_scene(scene);
  s.clouds.optics = "seed";
  return s;
}

Scene heavy_rain_scene(const Scene& scene) {
  Scene s = scene;
  s.precipitation.kind = "rain";
  s.precipitation.rate_mm_per_h = 20.0f;
  s.precipitation.bottom_m = 0.0f;
  s.precipitation.shafts = false;
  return s;
}

// A thunderstorm: the heavy rain under storm cells (clouds.precipitation 1) flashing 30
// times a minute a cell, a third of the flashes to the ground: most frames have a flash in
// range, and the frame's percentiles show what the flashes cost the worst frames.
Scene thunderstorm_scene(const Scene& scene) {
  Scene s = heavy_rain_scene(scene);
  s.clouds.precipitation = 1.0f;
  s.lightning.flashes_per_min = 30.0f;
  s.lightning.ground_share = 0.33f;
  return s;
}

// Three volumetric layers below the cirrus: the scene's own and two more, as a report gives
// them (an altocumulus and a higher stratocumulus deck), each covering half the sky.
Scene three_layer_scene(const Scene& scene) {
  Scene s = scene;
  CloudLayerParams alto;
  alto.genus = "altocumulus";
  alto.base_m = 4500.0f;
  alto.top_m = 5100.0f;
  alto.oktas = 4.0f;
  CloudLayerParams deck = alto;
  deck.genus = "stratocumulus";
  deck.base_m = 6200.0f;
  deck.top_m = 6800.0f;
  s.cloud_layers = {alto, deck};
  return s;
}

nlohmann::json measure_realtime(Renderer& renderer, const RendererOptions& options,
                                const Scene& base, const RealtimeSettings& f) {
  // Eight renderers, one history each: the still camera (`renderer`), the flight, the seed's
  // algorithm, the still camera lit as the seed lights clouds (seed_lit_scene), the same on
  // the droplets (seed_lighting_scene), in heavy rain (heavy_rain_scene), in a thunderstorm
  // (thunderstorm_scene) and under three layers (three_layer_scene). Their timed frames are
  // interleaved, so a slow spell of a shared machine falls on all alike and the ratios between them
  // hold.
  Renderer flight(options);
  Renderer seed_renderer(options);
  Renderer seed_lit_renderer(options);
  Renderer seed_lighting_renderer(options);
  Renderer rain_renderer(options);
  Renderer storm_renderer(options);
  Renderer layers_renderer(options);
  Renderer reference(options);
  const int cycle = base.quality.march_stride * base.quality.march_stride;
  nlohmann::json out;

  // A still camera, clouds drifting with the wind: two march cycles to converge first.
  const auto still_camera = [&](Renderer& r, Scene s) {
    s.quality.mode = MarchMode::Default;
    r.render(s);
    for (int i = 0; i < 2 * cycle; ++i) {
      s.time_s += f.frame_dt_s;
      r.render_next(s, false);
    }
    return s;
  };
  Scene scene = still_camera(renderer, base);
  // The flight: a cycle to fill the history.
  const Scene start = base;
  flight.render(start);
  int flight_frame = 0;
  for (; flight_frame < cycle; ++flight_frame)
    flight.render_next(flight_at(start, f, float(flight_frame + 1) * f.frame_dt_s), false);
  // The seed's algorithm on the still view (every pixel, every frame).
  Scene baseline = base;
  baseline.quality.mode = MarchMode::Baseline;
  seed_renderer.render_next(baseline, false);  // warm-up
  // The still camera lit as the seed lights clouds.
  Scene seed_lit = still_camera(seed_lit_renderer, seed_lit_scene(base));
  Scene seed_lighting = still_camera(seed_lighting_renderer, seed_lighting_scene(base));
  Scene rain = still_camera(rain_renderer, heavy_rain_scene(base));
  Scene storm = still_camera(storm_renderer, thunderstorm_scene(base));
  Scene layers = still_camera(layers_renderer, three_layer_scene(base));

  Timing still, moving, seed, lit_by_seed, lighting_of_seed, in_rain, in_storm, under_layers;
  const int frames = std::max(f.static_frames, f.moving_frames);
  const int seed_every = std::max(1, frames / 8);  // eight of the seed's slow frames
  for (int i = 0; i < frames; ++i) {
    if (i < f.static_frames) {
      scene.time_s += f.frame_dt_s;
      still.add(renderer.render_next(scene, false).stats);
    }
    if (i < f.moving_frames) {
      ++flight_frame;
      moving.add(flight.render_next(flight_at(start, f, float(flight_frame) * f.frame_dt_s), false)
                     .stats);
    }
    if (i % seed_every == seed_every / 2) seed.add(seed_renderer.render_next(baseline, false).stats);
    if (i % 2 == 0 && i < f.static_frames) {  // every other frame: enough for its median
      seed_lit.time_s += 2.0f * f.frame_dt_s;
      lit_by_seed.add(seed_lit_renderer.render_next(seed_lit, false).stats);
    }
    if (i % 2 == 1 && i < f.static_frames) {  // the frames between
      seed_lighting.time_s += 2.0f * f.frame_dt_s;
      lighting_of_seed.add(seed_lighting_renderer.render_next(seed_lighting, false).stats);
    }
    if (i < f.static_frames) {
      rain.time_s += f.frame_dt_s;
      in_rain.add(rain_renderer.render_next(rain, false).stats);
      storm.time_s += f.frame_dt_s;
      in_storm.add(storm_renderer.render_next(storm, false).stats);
      layers.time_s += f.frame_dt_s;
      under_layers.add(layers_renderer.render_next(layers, false).stats);
    }
    if (f.on_step) f.on_step();
  }

  // Errors, untimed: the still view once more, then flight frames spread over a few cycles.
  double static_error = 0.0, moving_error = 0.0;
  if (f.errors) {
    scene.time_s += f.frame_dt_s;
    static_error = error_against_reference(reference, scene, renderer.render_next(scene).color);
  }
  for (int k = 0; f.errors && k < f.error_frames; ++k) {
    for (int i = 0; i < cycle; ++i) {
      ++flight_frame;
      const Scene s = flight_at(start, f, float(flight_frame) * f.frame_dt_s);
      const bool compare = i == cycle - 1;
      const Frame frame = flight.render_next(s, compare);
      if (!compare) continue;
      const double e = error_against_reference(reference, s, frame.color);
      if (f.on_step) f.on_step();
      std::printf("  flight frame %d: error %.4f\n", flight_frame, e);
      moving_error = std::max(moving_error, e);
    }
  }

  if (f.errors && f.still_flight_frames > 0) {
    const FlightFromStill c = flight_from_still(options, start, f);
    out["flight_from_still"] = c.errors;
    out["flight_from_still_ratio"] = c.ratio;
  }
  out["device"] = renderer.device_name();
  out["width"] = base.output.width;
  out["height"] = base.output.height;
  still.write(out, "static");
  moving.write(out, "moving");
  in_rain.write(out, "rain");
  out["cost_of_rain"] = in_rain.median_wall() / still.median_wall();
  in_storm.write(out, "storm");
  out["storm_p99_over_median"] = percentile(in_storm.wall_ms, 0.99) / in_storm.median_wall();
  under_layers.write(out, "layers");
  out["cost_of_three_layers"] = under_layers.median_wall() / still.median_wall();
  out["baseline_ms"] = seed.median_wall();
  out["baseline_fps"] = 1000.0 / seed.median_wall();
  out["speedup_vs_baseline"] = seed.median_wall() / still.median_wall();
  out["seed_lit_ms"] = lit_by_seed.median_wall();
  out["cost_vs_seed_lit"] = still.median_wall() / lit_by_seed.median_wall();
  out["seed_lit_passes_ms"] = lit_by_seed.passes();
  out["seed_lighting_ms"] = lighting_of_seed.median_wall();
  out["cost_vs_seed_lighting"] = still.median_wall() / lighting_of_seed.median_wall();
  out["seed_lighting_passes_ms"] = lighting_of_seed.passes();
  out["static_error"] = f.errors ? nlohmann::json(static_error) : nlohmann::json();
  out["moving_error"] = f.errors ? nlohmann::json(moving_error) : nlohmann::json();
  out["feature_variants"] = options.feature_variants;
  out["flight"] = {{"speed_mps", f.speed_mps},
                   {"turn_deg_s", f.turn_deg_s},
                   {"frame_dt_s", f.frame_dt_s}};
  return out;
}

}  // namespace nephele::cli

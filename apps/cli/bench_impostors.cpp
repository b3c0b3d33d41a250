#include "bench_impostors.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <vector>

#include <glm/geometric.hpp>
#include <glm/trigonometric.hpp>

#include "nephele/exposure.h"
#include "nephele/image.h"
#include "particles/particle_field.h"
#include "particles/particle_lighting.h"
#include "render/particle_light_timing.h"
#include "sample_stats.h"

namespace nephele::cli {

namespace {

constexpr const char* kMethods[] = {"off", "direct", "tiles"};
constexpr float kSpeedMps = 120.0f;  // a light aircraft's cruise
constexpr float kTurnDegS = 3.0f;    // a gentle turn: impostors seen from a changing angle
constexpr float kFrameDtS = 1.0f / 30.0f;

Scene flight_at(const Scene& start, float t_s) {
  Scene s = start;
  const float yaw = glm::radians(kTurnDegS * t_s);
  const glm::vec3 v = start.camera.view_dir;
  s.camera.view_dir = glm::vec3(v.x * std::cos(yaw) - v.y * std::sin(yaw),
                                v.x * std::sin(yaw) + v.y * std::cos(yaw), v.z);
  glm::vec3 heading(s.camera.view_dir.x, s.camera.view_dir.y, 0.0f);
  s.camera.position_m += glm::normalize(heading) * kSpeedMps * t_s;
  s.time_s = start.time_s + t_s;
  return s;
}

// GPU time of the passes that draw the particle clouds.
double particle_ms(const FrameStats& stats) {
  double ms = 0.0;
  for (const PassTiming& p : stats.passes)
    if (p.name == "particles" || p.name.rfind("impostor", 0) == 0) ms += p.ms;
  return ms;
}

// Mean |L_a - L_b| over the mean of L_b.
double mean_change(const Image& a, const Image& b) {
  double diff = 0.0, sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    diff += std::abs(double(luminance(a.pixels[i])) - luminance(b.pixels[i]));
    sum += luminance(b.pixels[i]);
  }
  return sum > 0.0 ? diff / sum : 0.0;
}

nlohmann::json atlas_json(const ParticleCloudStats& p) {
  return {{"occupancy", p.atlas_occupancy},
          {"wasted", p.atlas_wasted},
          {"fragmentation", p.atlas_fragmentation},
          {"defragmentations", p.atlas_defragmentations},
          {"defragmentations_per_s", p.atlas_defragmentations_per_s},
          {"downsized", p.atlas_downsized},
          {"failed", p.atlas_failed},
          {"resolution_scale", p.impostor_resolution_scale},
          {"waiting", p.impostors_waiting},
          {"mean_op_us", p.atlas_mean_op_us},
          {"max_op_us", p.atlas_max_op_us}};
}

}  // namespace

Scene impostor_bench_scene(const Scene& base) {
  Scene s = base;
  s.clouds.coverage = 0.0f;
  s.high_clouds.coverage = 0.0f;
  s.cirrus.coverage = 0.0f;
  s.camera.position_m = glm::vec3(0.0f, -12000.0f, 3200.0f);
  s.camera.view_dir = glm::vec3(0.0f, 1.0f, -0.08f);
  s.camera.fov_deg = 50.0f;
  ParticleCloudParams& p = s.particle_clouds;
  if (p.coverage <= 0.0f) {
    p.coverage = 0.25f;
    p.field_radius_m = 20000.0f;
    p.cell_m = 150.0f;
    p.particle_radius_m = 200.0f;
    p.impostor_distance_m = 4000.0f;
  }
  s.output.auto_exposure = false;
  s.output.ev100 = 15.0f;
  return s;
}

nlohmann::json run_impostor_bench(const RendererOptions& options, const Scene& scene, int frames,
                                  const std::string& image_path) {
  constexpr int kCount = int(std::size(kMethods));
  std::vector<std::unique_ptr<Renderer>> renderers;
  for (int m = 0; m < kCount; ++m) renderers.push_back(std::make_unique<Renderer>(options));
  const auto scene_for = [&](int m, float t_s) {
    Scene s = flight_at(scene, t_s);
    s.particle_clouds.impostors = kMethods[m];
    return s;
  };
  // Warm-up: a still (every impostor drawn), then a third of a second of flight.
  const int warmup = 10;
  for (int m = 0; m < kCount; ++m) renderers[m]->render(scene_for(m, 0.0f));
  for (int f = 1; f <= warmup; ++f)
    for (int m = 0; m < kCount; ++m) renderers[m]->render_next(scene_for(m, f * kFrameDtS), false);

  std::vector<double> ms[kCount], wall[kCount], changes[kCount];
  std::map<std::string, std::vector<double>> passes[kCount];  // the particle passes, each
  Image previous[kCount];
  Frame last[kCount];
  for (int f = 0; f < frames; ++f) {
    const float t = float(warmup + 1 + f) * kFrameDtS;
    for (int m = 0; m < kCount; ++m) {
      Frame frame = renderers[m]->render_next(scene_for(m, t), true);
      ms[m].push_back(particle_ms(frame.stats));
      for (const PassTiming& p : frame.stats.passes)
        if (p.name == "particles" || p.name.rfind("impostor", 0) == 0) passes[m][p.name].push_back(p.ms);
      wall[m].push_back(frame.stats.wall_ms);
      if (!previous[m].pixels.empty()) changes[m].push_back(mean_change(frame.color, previous[m]));
      previous[m] = frame.color;
      last[m] = std::move(frame);
    }
  }

  // The lighting of the whole field at once (the frames relight only what changed), on the
  // CPU and by the same splat on the device, for both buffer sizes: the seed's claim that the
  // CPU is two orders of magnitude faster.
  const ParticleCloudParams& pc = scene.particle_clouds;
  const particles::ParticleField field = particles::generate_field(pc, scene.time_s);
  const glm::vec3 light = glm::normalize(glm::vec3(0.3f, -0.4f, 0.8f));
  ParticleLightTiming lighting[2];
  for (int b = 0; b < 2; ++b) {
    ParticleCloudParams p = pc;
    p.light_buffer = b == 0 ? 32 : 64;
    lighting[b] = measure_particle_lighting(options, field, p, light, 5);
  }
  const double lighting_ms = lighting[0].cpu_ms;

  nlohmann::json out;
  out["device"] = renderers[0]->device_name();
  out["width"] = scene.output.width;
  out["height"] = scene.output.height;
  out["frames"] = frames;
  out["particles"] = field.particles();
  out["clouds"] = field.clouds.size();
  out["flight"] = {{"speed_mps", kSpeedMps}, {"turn_deg_s", kTurnDegS}, {"frame_dt_s", kFrameDtS}};
  const char* keys[kCount] = {"all_particles", "impostors_direct", "impostors_tiles"};
  double median_ms[kCount];
  for (int m = 0; m < kCount; ++m) {
    const std::string k = keys[m];
    median_ms[m] = percentile(ms[m], 0.5);
    out[k + "_ms"] = median_ms[m];
    out[k + "_p95_ms"] = percentile(ms[m], 0.95);
    out[k + "_p99_ms"] = percentile(ms[m], 0.99);
    out[k + "_max_ms"] = percentile(ms[m], 1.0);
    out[k + "_wall_ms"] = percentile(wall[m], 0.5);
    out[k + "_wall_max_ms"] = percentile(wall[m], 1.0);
    out["max_frame_change_" + std::string(kMethods[m])] =
        changes[m].empty() ? 0.0 : percentile(changes[m], 1.0);
    const ParticleCloudStats& p = *last[m].stats.particle_clouds;
    out[k + "_drawn_particles"] = p.drawn;
    for (const auto& [name, v] : passes[m]) out[k + "_passes_ms"][name] = percentile(v, 0.5);
    out[k + "_impostors"] = p.impostors;
    if (m > 0) out["atlas_" + std::string(kMethods[m])] = atlas_json(p);
  }
  out["speedup_direct"] = median_ms[0] / std::max(median_ms[1], 1e-9);
  out["speedup_tiles"] = median_ms[0] / std::max(median_ms[2], 1e-9);
  const double l0 = last[0].stats.mean_luminance;
  const double d1 = std::abs(last[1].stats.mean_luminance / l0 - 1.0);
  const double d2 = std::abs(last[2].stats.mean_luminance / l0 - 1.0);
  out["luminance_difference_direct"] = d1;
  out["luminance_difference_tiles"] = d2;
  out["luminance_difference"] = std::max(d1, d2);
  out["cpu_lighting_ms"] = lighting_ms;
  for (const ParticleLightTiming& t : lighting) {
    const std::string b = std::to_string(t.buffer);
    out["lighting_" + b] = {{"cpu_ms", t.cpu_ms},
                            {"gpu_ms", t.gpu_ms},
                            {"gpu_wall_ms", t.gpu_wall_ms},
                            {"gpu_prepare_ms", t.gpu_prepare_ms},
                            {"cpu_over_gpu", t.cpu_ms / std::max(t.gpu_ms, 1e-9)},
                            {"max_difference", t.max_difference},
                            {"differing", t.differing}};
  }
  out["gpu_lighting_ms"] = lighting[0].gpu_ms;
  out["gpu_lighting_wall_ms"] = lighting[0].gpu_prepare_ms + lighting[0].gpu_wall_ms;
  out["cpu_lighting_us_per_particle"] = 1000.0 * lighting_ms / double(std::max<size_t>(field.particles(), 1));
  out["image"] = image_path;

  // The last frames side by side: all particles, direct, tiles.
  const int w = scene.output.width, h = scene.output.height;
  Image strip(w * kCount, h);
  for (int m = 0; m < kCount; ++m)
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) strip.at(m * w + x, y) = last[m].color.at(x, y);
  write_image(strip, image_path, still_exposure(scene.output, strip));

  std::printf("impostors (seed 003): %dx%d, %zu particles in %zu clouds, %d frames of a flight at "
              "%g m/s on %s\n",
              w, h, field.particles(), field.clouds.size(), frames, kSpeedMps,
              renderers[0]->device_name().c_str());
  std::printf("  %-16s %9s %9s %9s %9s %8s %10s %11s\n", "particle passes", "median", "p95", "p99",
              "max", "speed-up", "drawn", "impostors");
  for (int m = 0; m < kCount; ++m) {
    const std::string k = keys[m];
    std::printf("  %-16s %9.2f %9.2f %9.2f %9.2f %7.1fx %10zu %11d\n", kMethods[m],
                out[k + "_ms"].get<double>(), out[k + "_p95_ms"].get<double>(),
                out[k + "_p99_ms"].get<double>(), out[k + "_max_ms"].get<double>(),
                median_ms[0] / std::max(median_ms[m], 1e-9), out[k + "_drawn_particles"].get<size_t>(),
                out[k + "_impostors"].get<int>());
  }
  for (int m = 0; m < kCount; ++m) {
    std::printf("  %-16s", kMethods[m]);
    for (const auto& [name, v] : out[std::string(keys[m]) + "_passes_ms"].items())
      std::printf(" %s %.2f", name.c_str(), v.get<double>());
    std::printf(" (median ms)\n");
  }
  std::printf("  mean luminance against all particles: direct %+.2f%%, tiles %+.2f%%; largest "
              "frame-to-frame change: all %.2f%%, direct %.2f%%, tiles %.2f%%\n",
              100.0 * (last[1].stats.mean_luminance / l0 - 1.0),
              100.0 * (last[2].stats.mean_luminance / l0 - 1.0),
              100.0 * out["max_frame_change_off"].get<double>(),
              100.0 * out["max_frame_change_direct"].get<double>(),
              100.0 * out["max_frame_change_tiles"].get<double>());
  for (const char* method : {"direct", "tiles"}) {
    const nlohmann::json& a = out["atlas_" + std::string(method)];
    std::printf("  atlas %-6s occupancy %.3f, wasted %.3f, fragmentation %.3f, %d "
                "defragmentations (%.2f/s), %d downsized, %d failed, %.2f us per operation (max "
                "%.1f); images at %.2f of impostor_resolution, %d far clouds waiting for one\n",
                method, a["occupancy"].get<double>(), a["wasted"].get<double>(),
                a["fragmentation"].get<double>(), a["defragmentations"].get<int>(),
                a["defragmentations_per_s"].get<double>(), a["downsized"].get<int>(),
                a["failed"].get<int>(), a["mean_op_us"].get<double>(), a["max_op_us"].get<double>(),
                a["resolution_scale"].get<double>(), a["waiting"].get<int>());
  }
  for (const ParticleLightTiming& t : lighting)
    std::printf("  lighting of the whole field, %dx%d buffer: CPU %.1f ms (%.3f us a particle); the "
                "same splat on the device %.1f ms (timestamps), %.1f ms with the host's sort, "
                "upload and read-back; CPU / device %.2f; %zu particles' lights differ (by at "
                "most %.4f)\n",
                t.buffer, t.buffer, t.cpu_ms, 1000.0 * t.cpu_ms / double(std::max<size_t>(t.particles, 1)),
                t.gpu_ms, t.gpu_prepare_ms + t.gpu_wall_ms, t.cpu_ms / std::max(t.gpu_ms, 1e-9),
                t.differing, t.max_difference);
  std::printf("  image: %s\n", image_path.c_str());
  std::fflush(stdout);
  return out;
}

}  // namespace nephele::cli

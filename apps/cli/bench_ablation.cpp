#include "bench_ablation.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_realtime.h"
#include "nephele/exposure.h"
#include "nephele/image.h"
#include "sample_stats.h"

namespace nephele::cli {

namespace {

struct Variant {
  const char* key;    // its JSON name, "<key>_ms"
  const char* label;  // the seed's name for it
  VoxelMarch march;
  VoxelShadow shadow;
};

constexpr Variant kVariants[] = {
    {"baseline", "plain march + light march (seed baseline)", VoxelMarch::Plain, VoxelShadow::LightMarch},
    {"sdf_march", "SDF march + light march", VoxelMarch::ThreePhase, VoxelShadow::LightMarch},
    {"sdf_shadow", "plain march + SDF shadows", VoxelMarch::Plain, VoxelShadow::SdfCone},
    {"sdf_both", "SDF march + SDF shadows", VoxelMarch::ThreePhase, VoxelShadow::SdfCone},
};

double clouds_pass_ms(const FrameStats& stats) {
  double ms = 0.0;
  for (const PassTiming& p : stats.passes)
    if (p.name == "clouds") ms += p.ms;
  return ms;
}

}  // namespace

Scene ablation_scene(const Scene& base) {
  Scene s = base;
  if (!s.voxel_clouds.empty()) return s;
  // From below the cloud base, a cluster of voxel cumulus 1.7 to 3.4 km ahead filling most of
  // the sky in view, a congestus among them, noise cumulus around and behind.
  s.camera.position_m = {0.0f, 0.0f, 900.0f};
  s.camera.view_dir = {0.0f, 1.0f, 0.12f};
  s.camera.fov_deg = 60.0f;
  s.clouds.coverage = 0.3f;
  struct Placed {
    const char* preset;
    uint32_t seed;
    glm::vec3 position_m;
  };
  const Placed placed[] = {
      {"cumulus-congestus", 3, {0.0f, 3400.0f, 1200.0f}},
      {"cumulus", 1, {-1300.0f, 2300.0f, 1200.0f}},
      {"cumulus", 2, {1300.0f, 2400.0f, 1250.0f}},
      {"cumulus-mesh", 0, {-500.0f, 1800.0f, 1150.0f}},
      {"cumulus", 5, {900.0f, 1700.0f, 1100.0f}},
  };
  for (const Placed& p : placed) {
    VoxelCloudParams c;
    c.preset = p.preset;
    c.seed = p.seed;
    c.position_m = p.position_m;
    s.voxel_clouds.push_back(c);
  }
  return s;
}

Scene ablation_reference(const Scene& scene) {
  Scene s = reference_scene(scene);
  s.quality.voxel_march = VoxelMarch::Plain;
  s.quality.voxel_shadow = VoxelShadow::LightMarch;
  return s;
}

nlohmann::json run_ablation(Renderer& renderer, const Scene& scene, int rounds,
                            const std::string& image_path) {
  constexpr int kCount = int(std::size(kVariants));
  std::vector<double> ms[kCount];
  double luminance[kCount] = {};
  Image strip(scene.output.width * kCount, scene.output.height);
  for (int round = -1; round < rounds; ++round) {  // round -1 warms up (textures, pipelines)
    for (int v = 0; v < kCount; ++v) {
      Scene s = scene;
      s.quality.voxel_march = kVariants[v].march;
      s.quality.voxel_shadow = kVariants[v].shadow;
      const Frame frame = renderer.render(s);
      if (round < 0) {
        luminance[v] = frame.stats.mean_luminance;
        for (int y = 0; y < frame.color.height; ++y)
          for (int x = 0; x < frame.color.width; ++x)
            strip.at(v * scene.output.width + x, y) = frame.color.at(x, y);
        continue;
      }
      ms[v].push_back(clouds_pass_ms(frame.stats));
    }
  }
  write_image(strip, image_path, still_exposure(scene.output, strip));

  const Scene reference = ablation_reference(scene);
  const double reference_luminance = renderer.render(reference).stats.mean_luminance;

  nlohmann::json out;
  out["device"] = renderer.device_name();
  out["width"] = scene.output.width;
  out["height"] = scene.output.height;
  out["voxel_clouds"] = scene.voxel_clouds.size();
  out["rounds"] = rounds;
  out["reference_mean_luminance"] = reference_luminance;
  double medians[kCount];
  double max_difference = 0.0;
  for (int v = 0; v < kCount; ++v) {
    const std::string key = kVariants[v].key;
    medians[v] = median(ms[v]);
    out[key + "_ms"] = medians[v];
    out[key + "_mean_luminance"] = luminance[v];
    out[key + "_reference_difference"] = luminance[v] / reference_luminance - 1.0;
    if (v > 0)
      max_difference = std::max(max_difference, std::abs(luminance[v] - luminance[0]) / luminance[0]);
  }
  out["speedup_sdf_march"] = medians[0] / medians[1];
  out["speedup_sdf_shadow"] = medians[0] / medians[2];
  out["speedup_sdf_both"] = medians[0] / medians[3];
  out["max_luminance_difference"] = max_difference;
  out["image"] = image_path;

  std::printf("ablation (seed 002), %dx%d, %zu voxel clouds, clouds pass, median of %d on %s:\n",
              scene.output.width, scene.output.height, scene.voxel_clouds.size(), rounds,
              renderer.device_name().c_str());
  for (int v = 0; v < kCount; ++v)
    std::printf("  %-44s %9.1f ms  %5.2fx  mean luminance %+.2f%% (%+.2f%% from the reference)\n",
                kVariants[v].label, medians[v], medians[0] / medians[v],
                100.0 * (luminance[v] - luminance[0]) / luminance[0],
                100.0 * (luminance[v] / reference_luminance - 1.0));
  std::printf("  reference (plain march, %d primary and %d light steps, no light volume): mean "
              "luminance %.4f\n",
              reference.quality.primary_steps, reference.quality.light_steps, reference_luminance);
  std::printf("  images: %s\n", image_path.c_str());
  return out;
}

}  // namespace nephele::cli

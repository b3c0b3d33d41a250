// The reference path tracer's driver (issue 21): the lab's grid placed as voxel cloud 0, or the
// planet's frame as the fast mode prepares it; path_trace.comp dispatched pass after pass, each
// adding samples to every pixel, until the samples or the time asked for; then the mean and
// the variance of the mean per pixel.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <numeric>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "render/frame_renderer_impl.h"
#include "render/lab_scene.h"
#include "render/passes.h"
#include "render/path_majorant.h"

namespace nephele {

namespace {

// The invocations a dispatch of the path tracer should have to keep a GPU busy (an H200 holds
// about 270,000 threads at once).
constexpr int kBusyInvocations = 1 << 18;

// The lab's grid as the voxel clouds module places clouds: its anchor where the file has it,
// its densities as the file has them (sigma_t = density x sigma_t_per_m, path_medium.x).
Scene lab_as_voxel_cloud(const Scene& scene) {
  Scene s = scene;
  s.clouds.coverage = 0.0f;
  s.high_clouds.coverage = 0.0f;
  s.cirrus.coverage = 0.0f;
  s.voxel_clouds = {lab_voxel_cloud(scene)};
  return s;
}

}  // namespace

// The lab's parameters: its grid as voxel cloud 0 in the lab's own frame.
gpu::FrameParams FrameRenderer::Impl::lab_reference_params(const Scene& scene,
                                                           const ReferenceOptions& options) {
  Scene s = lab_as_voxel_cloud(scene);
  update_atmosphere_luts(s);
  gpu::FrameParams params = make_frame_params(s, 0, sky_lights(s), atmosphere.tables());
  const voxel::VoxelGrid& grid = voxel_clouds.grid(s.voxel_clouds[0]);
  s.voxel_clouds[0].position_m = grid.file_anchor_m;
  voxel_clouds.prepare(s, params);
  // The grid's densities as the file has them: what the import scaled into [0, 1] scales back.
  params.voxel_clouds[0].anchor_m.w = grid.file_density_scale;
  // The lab's own frame (x east, y north, z up, from the grid's anchor): the camera and the
  // grid's axes there, without the planet frame's large coordinates.
  gpu::VoxelCloudGpu& c = params.voxel_clouds[0];
  for (int k = 0; k < 3; ++k) {
    glm::vec3 axis(0.0f);
    axis[k] = 1.0f / grid.voxel_m;
    (k == 0 ? c.to_grid_x : k == 1 ? c.to_grid_y : c.to_grid_z) =
        glm::vec4(axis, -grid.origin_m[k] / grid.voxel_m);
  }
  // The brick grid (MajorantGrid).
  const VoxelCloudMemory& memory = voxel_clouds.memory()[0];
  const bool brick_grid =
      options.majorant_grid == MajorantGrid::kBricks ||
      (options.majorant_grid == MajorantGrid::kAuto && memory.stored_bricks < memory.total_bricks / 4);
  params.path_eye_m =
      glm::vec4(scene.camera.position_m - grid.file_anchor_m, brick_grid ? 1.0f : 0.0f);
  if (brick_grid)
    path_tracer.upload_majorant(
        lab_brick_majorants(grid.density, grid.dims,
                            grid.file_density_scale * scene.lab.sigma_t_per_m),
        glm::ivec3(c.bricks));
  const float peak = *std::max_element(grid.density.begin(), grid.density.end());
  // Trilinear interpolation never exceeds the largest voxel: a majorant.
  const float majorant = std::max(peak * grid.file_density_scale * scene.lab.sigma_t_per_m, 1e-6f);
  params.path_medium = glm::vec4(scene.lab.sigma_t_per_m, scene.lab.albedo, scene.lab.g, majorant);
  params.path_light = glm::vec4(
      sun_direction_from_angles(scene.lab.sun_elevation_deg, scene.lab.sun_azimuth_deg),
      scene.lab.sun_irradiance);
  return params;
}

// The planet's parameters: the fast mode's frame (its atmosphere, lights, camera, noise and
// voxel clouds, weather map), and the voxel clouds' shell and density bound for the majorant
// grid (path_trace.comp).
gpu::FrameParams FrameRenderer::Impl::planet_reference_params(const Scene& scene,
                                                              const ReferenceOptions& options) {
  if (scene.cirrus.coverage > 0.0f)
    throw InputError("cirrus.coverage " + std::to_string(scene.cirrus.coverage) +
                     ": the reference path tracer has no cirrus sheet; must be 0 for --reference");
  if (scene.conditions.mode != ConditionsMode::Off)
    throw InputError("conditions.mode: the reference path tracer renders the physical model; "
                     "must be \"off\" for --reference");
  update_atmosphere_luts(scene);
  gpu::FrameParams params = make_frame_params(scene, 0, sky_lights(scene), atmosphere.tables());
  voxel_clouds.prepare(scene, params);
  update_noise(scene, params);
  weather.prepare(scene, params);
  const float planet_m = params.radii_m.x;
  glm::vec4 voxels(0.0f, 1.0f, 0.0f, 0.0f);  // no voxel clouds: an empty shell
  for (int i = 0; i < params.voxel_info.x; ++i) {
    const VoxelCloudParams& c = scene.voxel_clouds[size_t(i)];
    const voxel::VoxelGrid& g = voxel_clouds.grid(c);
    const float bottom_m = planet_m + c.position_m.z + g.origin_m.z * c.scale;
    const float top_m = bottom_m + g.extent_m().z * c.scale;
    // The density field is at most 1 x density (x the voxel clouds' share of cloud_shape.z).
    voxels.x += params.voxel_clouds[i].anchor_m.w * params.cloud_shape.z;
    voxels.y = i == 0 ? bottom_m : std::min(voxels.y, bottom_m);
    voxels.z = std::max(voxels.z, top_m);
  }
  // Padded: an upright box's corners lie a little higher than its top's centre.
  if (params.voxel_info.x > 0) voxels += glm::vec4(0.0f, -100.0f, 100.0f, 0.0f);
  params.path_voxels = voxels;
  // The noise clouds' majorant grid, from the base noise's bounds (the default march's field;
  // a flow map displaces the noise by more than the grid allows for, so then none).
  params.path_grid = glm::vec4(0.0f);
  const auto has_noise = [](const gpu::CloudLayerGpu& l) { return l.shape.x > 0.0f || l.shape.w > 0.0f; };
  if (options.majorant_grid != MajorantGrid::kNone && scene.quality.mode == MarchMode::Default &&
      params.cloud_flow.x == 0.0f &&
      std::any_of(std::begin(params.cloud_layers), std::end(params.cloud_layers), has_noise)) {
    if (noise_bounds_seed != scene.noise_seed) {
      const gpu::Texture& base = noise.base();
      const size_t bytes = size_t(base.width()) * base.height() * base.depth() * 4;
      gpu::Buffer staging(ctx, VkDeviceSize(bytes), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
      ctx.submit_and_wait([&](VkCommandBuffer cmd) { base.record_download(cmd, staging); });
      const auto* data = static_cast<const uint8_t*>(staging.data());
      noise_bounds = noise_block_bounds(std::vector<uint8_t>(data, data + bytes), int(base.width()));
      noise_bounds_seed = scene.noise_seed;
    }
    constexpr float kCellM = 500.0f;
    const glm::vec2 corner = glm::vec2(params.camera_pos_m) - 0.5f * kCellM * float(gpu::PATH_GRID_XY);
    path_tracer.upload_majorant(
        noise_majorant_grid(params, noise_bounds, corner, kCellM),
        glm::ivec3(gpu::PATH_GRID_XY, gpu::PATH_GRID_XY, gpu::CLOUD_LAYERS * gpu::PATH_GRID_BINS));
    params.path_grid = glm::vec4(corner, kCellM, 1.0f);
  }
  return params;
}

ReferenceImage FrameRenderer::Impl::render_reference(const Scene& scene,
                                                     const ReferenceOptions& options) {
  validate_scene(scene);
  if (options.spp < 1 || options.spp > 1000000)
    throw InputError("ReferenceOptions::spp " + std::to_string(options.spp) +
                     ": must be in [1, 1000000]");
  if (!(options.time_limit_s >= 0.0 && std::isfinite(options.time_limit_s)))
    throw InputError("ReferenceOptions::time_limit_s: must be a finite number of seconds, at "
                     "least 0 (0 = none)");
  if (options.max_bounces < -1 || options.max_bounces > kMaxReferenceBounces)
    throw InputError("ReferenceOptions::max_bounces " + std::to_string(options.max_bounces) +
                     ": must be in [0, " + std::to_string(kMaxReferenceBounces) + "] or -1 (auto)");
  if (options.iterations_per_pass < 0 || options.iterations_per_pass > 65536)
    throw InputError("ReferenceOptions::iterations_per_pass " +
                     std::to_string(options.iterations_per_pass) +
                     ": must be in [0, 65536] (0 = auto)");
  if (options.invocations_per_pixel < 0 || options.invocations_per_pixel > 64)
    throw InputError("ReferenceOptions::invocations_per_pixel " +
                     std::to_string(options.invocations_per_pixel) +
                     ": must be in [0, 64] (0 = auto)");
  if (options.undo_cut_iteration < -1 || options.undo_cut_iteration > 1)
    throw InputError("ReferenceOptions::undo_cut_iteration " +
                     std::to_string(options.undo_cut_iteration) + ": must be -1 (auto), 0 or 1");
  const auto start = std::chrono::steady_clock::now();
  const bool planet = scene.lab.grid.empty();
  gpu::FrameParams params =
      planet ? planet_reference_params(scene, options) : lab_reference_params(scene, options);
  const int max_bounces = options.max_bounces >= 0 ? options.max_bounces
                          : planet                 ? kMaxReferenceBounces
                                                   : scene.lab.max_bounces;
  const int width = scene.output.width, height = scene.output.height;
  int slots = options.invocations_per_pixel;
  // On a GPU, enough for kBusyInvocations: 1, 3, 9 or 27 (a power of three, so that a pass
  // stopped early leaves every channel as many samples: path_hero).
  if (slots == 0 && !ctx.is_cpu()) {
    const int wanted = (kBusyInvocations + width * height - 1) / (width * height);
    slots = 1;
    while (slots < wanted && slots < 27) slots *= 3;
  }
  slots = std::max(slots, 1);
  // Slot k of S takes samples k, k + S, ... and the planet's paths take their hero channel in
  // turn (path_trace.comp): the samples a pixel takes are a multiple of S and, on the planet,
  // of three, so that every slot takes as many and every channel leads a third.
  const int step = std::lcm(planet ? 3 : 1, slots);
  const auto round_up = [step](long long n) { return int((n + step - 1) / step * step); };
  const int spp = round_up(options.spp);
  int reported = 0;
  path_tracer.resize(width, height, slots);
  path_tracer.set_undo_cut_iteration(
      options.undo_cut_iteration < 0 ? ctx.is_cpu() : options.undo_cut_iteration == 1);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { path_tracer.clear(cmd); });

  // Passes of a bounded number of iterations an invocation (path_trace.comp), grown while a
  // pass takes under a quarter of a second, so that a time limit is kept to within about a
  // pass and progress is reported often: until no invocation has samples to take. At the time
  // limit, each finishes the sample it is on and takes its samples to a multiple of three, so
  // that every channel has as many; pixels then differ in their samples. That takes as long as
  // the longest of those samples, which at a low sun runs into minutes on a GPU (hundreds of
  // bounces through cloud, each with a shadow ray along the layer towards the horizon: an
  // H200's 85 s sunset reference ran on past 125 s): after a tenth of the limit more, the
  // samples still in flight are left out (ReferenceImage::abandoned).
  const long long pixels = (long long)(width)*height;
  // A CPU device's loop limit (65535 iterations an invocation's batch, in all its loops): an
  // iteration runs a few short loops of its own, and a pass the limit ends early lowers this.
  int max_iterations = ctx.is_cpu() ? 2048 : 1 << 14;
  int iterations = options.iterations_per_pass > 0 ? options.iterations_per_pass : 64;
  bool weather_built = false, stopping = false;
  FramePlan plan;
  plan.volumetric = true;
  plan.measure = FramePlan::Measure::kReference;
  plan.planet_reference = planet;
  const FrameGraph graph = frame_graph(scene, params, plan);
  PathTracerModule::Counts counts;
  long long abandoned = 0;
  for (bool first = true; first || counts.running > 0; first = false) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!stopping && counts.finished > 0 && options.time_limit_s > 0.0 &&
        elapsed >= options.time_limit_s)
      stopping = true;
    if (stopping && elapsed >= 1.1 * options.time_limit_s) {
      abandoned = counts.running;
      break;
    }
    path_tracer.set_paths(int(options.seed), max_bounces);
    path_tracer.set_samples(stopping ? 0 : spp, iterations);
    path_tracer.reset_running();
    const auto pass_start = std::chrono::steady_clock::now();
    // The first pass after what the paths read (the planet's weather map), then alone.
    state.run_once(params, [&](VkCommandBuffer cmd) {
      record_measure(cmd, graph, "path_trace", !weather_built);
    });
    weather_built = true;
    const double pass_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - pass_start).count();
    const uint32_t limited = counts.limited;
    counts = path_tracer.counts();
    // A pass the loop limit ended early lost nothing (its last iteration is done again) but
    // ran fewer iterations than asked: shorter ones.
    if (counts.limited > limited && options.iterations_per_pass == 0)
      iterations = max_iterations = std::max(iterations / 2, 16);
    else if (pass_s < 0.25 && options.iterations_per_pass == 0)
      iterations = std::min(iterations * 2, max_iterations);
    const int done = int((long long)(counts.finished) / std::max(pixels, 1LL));
    if (options.progress && done > reported) options.progress("reference", done, spp);
    reported = done;
  }

  // Each pixel's sums over its slots.
  const auto add_slots = [&](const Image& slotted) {
    Image total(width, height);
    for (size_t i = 0; i < total.pixels.size(); ++i) {
      glm::dvec4 t(0.0);
      for (int k = 0; k < slots; ++k)
        t += glm::dvec4(slotted.pixels[size_t(k) * total.pixels.size() + i]);
      total.pixels[i] = glm::vec4(t);
    }
    return total;
  };
  const Image sum = add_slots(download(ctx, path_tracer.sum(), false));
  const Image squares = add_slots(download(ctx, path_tracer.squares(), false));
  ReferenceImage out;
  out.mean = Image(width, height);
  out.variance = Image(width, height);
  for (size_t i = 0; i < sum.pixels.size(); ++i) {
    const double n = sum.pixels[i].a;
    for (int c = 0; c < 3; ++c) {
      const double mean = n > 0.0 ? sum.pixels[i][c] / n : 0.0;
      // The sample variance (sum of squared deviations over n - 1) over n: the variance of
      // the mean, (sum x^2 / n - mean^2) / (n - 1).
      const double var = n > 1.0 ? std::max(squares.pixels[i][c] / n - mean * mean, 0.0) / (n - 1.0) : 0.0;
      out.mean.pixels[i][c] = float(mean);
      out.variance.pixels[i][c] = float(var);
    }
    out.mean.pixels[i].a = 1.0f;
    out.variance.pixels[i].a = 1.0f;
  }
  // The mean over the pixels (all alike unless a time limit stopped the passes).
  out.spp = int((long long)(counts.finished) / std::max(pixels, 1LL));
  out.cut_loops = counts.cut;
  out.abandoned = abandoned;
  out.majorant_violations = counts.violations;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace nephele

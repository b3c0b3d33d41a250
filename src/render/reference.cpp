// The reference path tracer's driver (issue 21): the lab scene's grid placed as voxel cloud 0,
// path_trace.comp dispatched pass after pass, each adding samples to every pixel, until the
// samples or the time asked for; then the mean and the variance of the mean per pixel.
#include <algorithm>
#include <chrono>
#include <cmath>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "render/frame_renderer_impl.h"
#include "render/passes.h"

namespace nephele {

namespace {

// The lab's grid as the voxel clouds module places clouds: its anchor where the file has it,
// its densities as the file has them (sigma_t = density x sigma_t_per_m, path_medium.x).
Scene lab_as_voxel_cloud(const Scene& scene) {
  Scene s = scene;
  s.clouds.coverage = 0.0f;
  s.high_clouds.coverage = 0.0f;
  s.cirrus.coverage = 0.0f;
  VoxelCloudParams cloud;
  cloud.file = scene.lab.grid;
  cloud.density = 1.0f;
  cloud.follow_wind = false;
  cloud.resolution = voxel::kMaxGridDim;
  s.voxel_clouds = {cloud};
  return s;
}

}  // namespace

ReferenceImage FrameRenderer::Impl::render_reference(const Scene& scene,
                                                     const ReferenceOptions& options) {
  validate_scene(scene);
  if (scene.lab.grid.empty())
    throw InputError("lab.grid: \"\" is empty: render --reference needs a [lab] grid (.vdb or .nvdb)");
  if (options.spp < 1 || options.spp > 1000000)
    throw InputError("ReferenceOptions::spp " + std::to_string(options.spp) +
                     ": must be in [1, 1000000]");
  if (!(options.time_limit_s >= 0.0 && std::isfinite(options.time_limit_s)))
    throw InputError("ReferenceOptions::time_limit_s: must be a finite number of seconds, at "
                     "least 0 (0 = none)");
  const auto start = std::chrono::steady_clock::now();
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
  const float peak = *std::max_element(grid.density.begin(), grid.density.end());
  // Trilinear interpolation never exceeds the largest voxel: a majorant.
  const float majorant = std::max(peak * grid.file_density_scale * scene.lab.sigma_t_per_m, 1e-6f);
  params.path_medium = glm::vec4(scene.lab.sigma_t_per_m, scene.lab.albedo, scene.lab.g, majorant);
  params.path_light = glm::vec4(
      sun_direction_from_angles(scene.lab.sun_elevation_deg, scene.lab.sun_azimuth_deg),
      scene.lab.sun_irradiance);
  const int width = scene.output.width, height = scene.output.height;
  path_tracer.resize(width, height);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { path_tracer.clear(cmd); });

  // Passes of a few samples each, doubled while a pass takes under half a second, so a time
  // limit is kept to within about a pass and progress is reported often.
  int taken = 0, per_pass = 1;
  while (taken < options.spp) {
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (taken > 0 && options.time_limit_s > 0.0 && elapsed >= options.time_limit_s) break;
    const int n = std::min(per_pass, options.spp - taken);
    params.path_info = glm::ivec4(taken, n, int(options.seed), scene.lab.max_bounces);
    const auto pass_start = std::chrono::steady_clock::now();
    state.run_once(params, [&](VkCommandBuffer cmd) { path_tracer.record(cmd, *state.timer); });
    const double pass_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - pass_start).count();
    taken += n;
    if (pass_s < 0.5) per_pass = std::min(per_pass * 2, 64);
    if (options.progress) options.progress("reference", taken, options.spp);
  }

  const Image sum = download(ctx, path_tracer.sum(), false);
  const Image squares = download(ctx, path_tracer.squares(), false);
  ReferenceImage out;
  out.mean = Image(width, height);
  out.variance = Image(width, height);
  for (size_t i = 0; i < sum.pixels.size(); ++i) {
    const double n = sum.pixels[i].a;
    for (int c = 0; c < 3; ++c) {
      const double mean = sum.pixels[i][c] / n;
      // The sample variance (sum of squared deviations over n - 1) over n: the variance of
      // the mean, (sum x^2 / n - mean^2) / (n - 1).
      const double var = n > 1.0 ? std::max(squares.pixels[i][c] / n - mean * mean, 0.0) / (n - 1.0) : 0.0;
      out.mean.pixels[i][c] = float(mean);
      out.variance.pixels[i][c] = float(var);
    }
    out.mean.pixels[i].a = 1.0f;
    out.variance.pixels[i].a = 1.0f;
  }
  out.spp = taken;
  out.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace nephele

// The frame: orders the passes of a frame, caches what does not change, records into the
// host's command buffer (nephele/frame.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <glm/gtc/packing.hpp>
#include <optional>

#include "nephele/error.h"
#include "nephele/frame.h"
#include "nephele/scene_io.h"
#include "nephele/sky.h"
#include "render/frame_params.h"
#include "render/frame_renderer_impl.h"
#include "render/lab_scene.h"
#include "render/passes.h"

namespace nephele {

// Reads an RGBA image of 32-bit (or, with `half`, 16-bit) float texels back to the host.
Image download(gpu::Context& ctx, const gpu::Texture& texture, bool half) {
  Image image(int(texture.width()), int(texture.height()));
  const size_t n = image.pixels.size();
  gpu::Buffer staging(ctx, VkDeviceSize(n * (half ? 8 : 16)), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { texture.record_download(cmd, staging); });
  if (!half) {
    std::memcpy(image.pixels.data(), staging.data(), n * 16);
    return image;
  }
  const auto* src = static_cast<const uint32_t*>(staging.data());
  for (size_t i = 0; i < n; ++i)
    image.pixels[i] =
        glm::vec4(glm::unpackHalf2x16(src[2 * i]), glm::unpackHalf2x16(src[2 * i + 1]));
  return image;
}

namespace {

// Bilinear resampling to width x height, both grids spanning the same field of view (as
// compose.comp reads the cloud buffer).
Image resample(const Image& src, int width, int height) {
  if (src.width == width && src.height == height) return src;
  Image out(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float gx = glm::clamp((x + 0.5f) * src.width / width - 0.5f, 0.0f, src.width - 1.0f);
      const float gy = glm::clamp((y + 0.5f) * src.height / height - 0.5f, 0.0f, src.height - 1.0f);
      const int x0 = int(gx), y0 = int(gy);
      const int x1 = std::min(x0 + 1, src.width - 1), y1 = std::min(y0 + 1, src.height - 1);
      const float fx = gx - x0, fy = gy - y0;
      out.at(x, y) = glm::mix(glm::mix(src.at(x0, y0), src.at(x1, y0), fx),
                              glm::mix(src.at(x0, y1), src.at(x1, y1), fx), fy);
    }
  return out;
}

// Pixel of each stride x stride block marched in frame k of a cycle: the order of the
// Bayer matrix, so consecutive frames fill the block evenly.
glm::ivec2 march_offset(int stride, long long k) {
  static const int kBayer4[16] = {0, 8, 2, 10, 12, 4, 14, 6, 3, 11, 1, 9, 15, 7, 13, 5};
  static const int kBayer2[4] = {0, 2, 3, 1};
  const int n = stride * stride;
  const int rank = int(k % n);
  for (int i = 0; i < n; ++i)
    if ((stride == 4 ? kBayer4[i] : stride == 2 ? kBayer2[i] : 0) == rank)
      return {i % stride, i / stride};
  return {0, 0};
}

// The camera's side of the cloud layer: -1 below, 0 inside, 1 above.
int layer_side(const Scene& scene) {
  const float z = scene.camera.position_m.z;
  const glm::vec2 shell_m = cloud_shell_m(scene);
  return z < shell_m.x ? -1 : z > shell_m.y ? 1 : 0;
}

// `light_dir` and `previous_light_dir`: the key lights (sky_lights) of the two frames.
bool history_usable(const Scene& scene, const Scene& previous, const glm::vec3& light_dir,
                    const glm::vec3& previous_light_dir) {
  const float cos_sun = glm::dot(light_dir, previous_light_dir);
  return cos_sun > std::cos(glm::radians(0.5f)) &&
         scene.sun.illuminance_lux == previous.sun.illuminance_lux &&
         glm::distance(scene.camera.position_m, previous.camera.position_m) < 1000.0f &&
         layer_side(scene) == layer_side(previous);
}

}  // namespace

double cloud_cover_fraction(const Scene& scene, const Image& clouds) {
  const CameraBasis basis = camera_basis(scene.camera);
  const float tan_half_fov = std::tan(glm::radians(vertical_fov_deg(scene)) * 0.5f);
  const float aspect = float(clouds.width) / float(clouds.height);
  const glm::vec3 up = glm::normalize(planet_from_enu(scene, scene.camera.position_m));
  size_t above = 0, covered = 0;
  for (int y = 0; y < clouds.height; ++y)
    for (int x = 0; x < clouds.width; ++x) {
      glm::vec3 dir =
          glsl::camera_ray(basis.forward, basis.right, basis.up, tan_half_fov, aspect, float(x),
                           float(y), float(clouds.width), float(clouds.height));
      if (glm::dot(dir, up) <= 0.0f) continue;
      ++above;
      if (clouds.at(x, y).a < 0.5f) ++covered;
    }
  return above == 0 ? 0.0 : double(covered) / double(above);
}

void FrameRenderer::Impl::print_timings(const std::vector<std::pair<std::string, double>>& results,
                                        const char* note) const {
  if (verbose)
    for (const auto& [name, ms] : results)
      std::fprintf(stderr, "nephele: pass %-12s %8.2f ms%s\n", name.c_str(), ms, note);
}

void FrameRenderer::Impl::update_noise(const Scene& scene, const gpu::FrameParams& params) {
  if (!noise.stale(scene.noise_seed)) return;
  // The base noise from the disk cache where an earlier process made it.
  const std::optional<std::filesystem::path> cached = noise.load_base(scene.noise_seed);
  if (cached && verbose)
    std::fprintf(stderr, "nephele: pass noise_base read from %s\n", cached->string().c_str());
  const int first = cached ? 1 : 0;
  const auto record_all = [&](VkCommandBuffer cmd) {
    for (int i = first; i < NoiseModule::kTextures; ++i) noise.record(cmd, *state.timer, i);
  };
  if (!progress) {
    print_timings(state.run_once(params, record_all), " (made once for its seed)");
  } else {  // one submission a texture, each reported
    progress("noise", 0, NoiseModule::kTextures);
    if (cached) progress("noise", 1, NoiseModule::kTextures);
    for (int i = first; i < NoiseModule::kTextures; ++i) {
      print_timings(
          state.run_once(params, [&](VkCommandBuffer cmd) { noise.record(cmd, *state.timer, i); }),
          " (made once for its seed)");
      progress("noise", i + 1, NoiseModule::kTextures);
    }
  }
  if (!cached) noise.store_base(scene.noise_seed);
  noise.made(scene.noise_seed);
}

// The frame graph's barrier between passes.
static void graph_barrier(VkCommandBuffer cmd) {
  gpu::pass_barrier(cmd);
}

std::vector<std::string> FrameRenderer::Impl::march_in_bands(const FrameGraph& graph,
                                                             const Scene& scene,
                                                             const gpu::FrameParams& params) {
  const int block_rows = (clouds.height() + clouds.stride() - 1) / clouds.stride();
  const int bands = std::clamp(block_rows / 16, 1, 40);
  band_timings.clear();
  const auto keep = [&](const std::vector<std::pair<std::string, double>>& results) {
    for (const auto& [name, ms] : results) {
      auto it = std::find_if(band_timings.begin(), band_timings.end(),
                             [&](const PassTiming& p) { return p.name == name; });
      if (it == band_timings.end())
        band_timings.push_back({name, ms});
      else
        it->ms += ms;
    }
  };
  const std::vector<std::string> before = graph.dependencies_of("march");
  progress("clouds", 0, bands + 1);
  keep(state.run_once(params,
                      [&](VkCommandBuffer cmd) { graph.execute(cmd, graph_barrier, before); }));
  progress("clouds", 1, bands + 1);
  for (int b = 0; b < bands; ++b) {
    const int first = block_rows * b / bands, rows = block_rows * (b + 1) / bands - first;
    keep(state.run_once(params, [&](VkCommandBuffer cmd) {
      clouds.record_march(cmd, *state.timer, scene.quality.mode, params, rows, first);
    }));
    progress("clouds", b + 2, bands + 1);
  }
  std::vector<std::string> rest;
  for (const FrameGraph::Step& step : graph.steps())
    if (step.pass != "march" && std::find(before.begin(), before.end(), step.pass) == before.end())
      rest.push_back(step.pass);
  return rest;
}

FrameGraph FrameRenderer::Impl::frame_graph(const Scene& scene, const gpu::FrameParams& params,
                                            const FramePlan& plan) {
  FrameGraph graph;
  graph.import(FrameGraph::kView);
  const FrameSetup setup{scene, params, plan, [this]() -> gpu::PassTimer& { return *state.timer; }};
  for (RenderModule* module : frame_modules()) module->add_passes(graph, setup);
  graph.compile();
  return graph;
}

void FrameRenderer::Impl::update_atmosphere_luts(const Scene& scene) {
  if (!atmosphere.stale(scene.atmosphere)) return;
  gpu::FrameParams params{};
  set_atmosphere(params, scene);
  print_timings(
      state.run_once(params, [&](VkCommandBuffer cmd) { atmosphere.record(cmd, *state.timer); }),
      " (cached until the atmosphere changes)");
  atmosphere.made(scene.atmosphere);
  sky_view.invalidate();
}

void FrameRenderer::Impl::render_reference_sky(gpu::FrameParams params) {
  if (state.reference_sky.width() != uint32_t(state.width) ||
      state.reference_sky.height() != uint32_t(2 * state.height))
    ctx.wait_queue_idle();
  state.resize_reference_sky(state.width, state.height);
  double ms = 0.0;
  for (int y = 0; y < state.height; y += gpu::REFERENCE_TILE)
    for (int x = 0; x < state.width; x += gpu::REFERENCE_TILE) {
      for (const auto& [name, pass_ms] : state.run_once(params, [&](VkCommandBuffer cmd) {
             pass_reference_sky(cmd, state, glm::ivec2(x, y));
           }))
        ms += pass_ms;
    }
  if (verbose) std::fprintf(stderr, "nephele: pass %-12s %8.2f ms\n", "reference", ms);
}

Image FrameRenderer::Impl::compose_layer(const Scene& scene, int layer) {
  const gpu::FrameParams& params = last_params;
  FramePlan plan = last_plan;
  plan.film_layer = layer;
  // Compose alone over the last frame's layers, and the stars for the sky, which they are in.
  const FrameGraph graph = frame_graph(scene, params, plan);
  std::vector<std::string> passes{"compose"};
  if (layer == 1) passes.push_back("stars");
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    state.begin(cmd, last_slot, params);
    graph.execute(cmd, graph_barrier, passes);
    gpu::frame_end_barrier(cmd, ctx.has_graphics());
  });
  return download(ctx, state.color[last_slot], false);
}

void FrameRenderer::Impl::record_measure(VkCommandBuffer cmd, const FrameGraph& graph,
                                         const std::string& pass, bool with_needs) const {
  std::vector<std::string> passes =
      with_needs ? graph.dependencies_of(pass) : std::vector<std::string>{};
  passes.push_back(pass);
  graph.execute(cmd, graph_barrier, passes);
}

double FrameRenderer::Impl::measure_sky_cover(const Scene& scene, double& ms) {
  gpu::FrameParams params = last_params;
  params.steps.w = gpu::PROJECTION_SKY_DOME;
  params.cloud_shape.x = 0.0f;  // the detail noise's finest level, as an observer sees it
  params.cloud_grid = glm::ivec4(kSkyDomeSize, kSkyDomeSize, 1, 0);
  params.march_offset = glm::ivec4(0, 0, 0, 1);
  params.output_image.z = params.output_image.w = 0.0f;  // the dome's own pixels, whatever window
  FramePlan plan = last_plan;
  plan.measure = FramePlan::Measure::kSkyDome;
  const FrameGraph graph = frame_graph(scene, params, plan);
  clouds.bind_march(true);
  // The dome alone: what it reads (the weather map, the light volume) is the last frame's.
  const auto results = state.run_once(
      params, [&](VkCommandBuffer cmd) { record_measure(cmd, graph, "sky_dome", false); });
  clouds.bind_march(false);
  ms = 0.0;
  for (const auto& [name, pass_ms] : results) ms += pass_ms;
  const Image dome = download(ctx, clouds.dome(), false);
  const auto covered = std::count_if(dome.pixels.begin(), dome.pixels.end(),
                                     [](const glm::vec4& p) { return p.a < 0.5f; });
  return double(covered) / double(dome.pixels.size());
}

CloudProfile FrameRenderer::Impl::cloud_profile(const Scene& scene) {
  validate_scene(scene);
  update_atmosphere_luts(scene);
  gpu::FrameParams params = make_frame_params(scene, 0, sky_lights(scene), atmosphere.tables());
  voxel_clouds.prepare(scene, params);
  params.cloud_shape.y = 0.5f * scene.clouds.weather_period_m;
  update_noise(scene, params);
  weather.prepare(scene, params);
  FramePlan plan;
  plan.volumetric = true;
  plan.measure = FramePlan::Measure::kCloudProfile;
  const FrameGraph graph = frame_graph(scene, params, plan);
  clouds.bind_march(true);
  state.run_once(params, [&](VkCommandBuffer cmd) {
    record_measure(cmd, graph, "cloud_profile", true);  // the weather map first
  });
  clouds.bind_march(false);
  const Image sums = download(ctx, clouds.dome(), false);
  // The shell the profile spans (voxel clouds may widen it beyond the layers).
  const glm::vec2 shell_m = glm::vec2(params.radii_m.z, params.radii_m.w) - params.radii_m.x;
  CloudProfile profile;
  for (int bin = 0; bin < sums.height; ++bin) {
    glm::dvec4 total(0.0);
    for (int x = 0; x < sums.width; ++x) total += glm::dvec4(sums.at(x, bin));
    profile.altitude_m.push_back(glm::mix(shell_m.x, shell_m.y, (bin + 0.5f) / sums.height));
    profile.density.push_back(float(total.x / total.w));
    profile.cloud_fraction.push_back(float(total.z / total.w));
  }
  return profile;
}

FrameRenderer::Impl::Impl(const RendererOptions& options)
    : Impl(std::make_unique<gpu::Context>(
               gpu::ContextOptions{options.device, options.validation, options.verbose}),
           options) {}

FrameRenderer::Impl::Impl(const HostVulkan& host, const RendererOptions& options)
    : Impl(std::make_unique<gpu::Context>(
               gpu::HostDevice{host.instance, host.physical_device, host.device, host.queue_family,
                               host.queue},
               options.verbose),
           options) {}

FrameRenderer::Impl::Impl(std::unique_ptr<gpu::Context> context, const RendererOptions& options)
    : owned_ctx(std::move(context)),
      ctx(*owned_ctx),
      state(ctx),
      verbose(options.verbose),
      progress(options.progress),
      noise(ctx, state.set),
      atmosphere(ctx, state.set),
      weather(ctx, state.set),
      light_volume(ctx, state.set),
      voxel_clouds(ctx, state.set),
      sky_view(ctx, state.set),
      clouds(ctx, state.set),
      particles(ctx, state.set, state.layers),
      classic_clouds(ctx, state.set),
      post(ctx, state.set),
      light_shafts(ctx, state.set),
      terrain(ctx, state.set, state.layers),
      host_scene(ctx, state.set),
      host_lighting(ctx, state.set),
      particle_light(ctx, state.set),
      path_tracer(ctx, state.set) {
  for (const RegisteredModule& module : registered_modules())
    registered.push_back(module.make(ModuleContext{ctx, state.set, state.layers}));
  ctx.set_feature_variants(options.feature_variants);
}

FrameRenderer::FrameRenderer(const RendererOptions& options)
    : impl_(std::make_unique<Impl>(options)) {}

FrameRenderer::FrameRenderer(const HostVulkan& host, const RendererOptions& options)
    : impl_(std::make_unique<Impl>(host, options)) {}

FrameRenderer::~FrameRenderer() = default;

int FrameRenderer::frames_in_flight() const {
  return gpu::kFramesInFlight;
}

const std::string& FrameRenderer::device_name() const {
  return impl_->ctx.device_name();
}

int FrameRenderer::validation_messages() const {
  return impl_->ctx.validation_messages();
}

const std::optional<FrameStats>& FrameRenderer::completed_stats() const {
  return impl_->completed;
}

const std::optional<HostLighting>& FrameRenderer::completed_lighting() const {
  return impl_->completed_lighting;
}

FrameImages FrameRenderer::record_frame(VkCommandBuffer cmd, const Scene& scene,
                                        const FrameOptions& options) {
  if (cmd == VK_NULL_HANDLE)
    throw InputError(
        "FrameRenderer::record_frame: cmd is VK_NULL_HANDLE; a command buffer in "
        "the recording state is needed");
  return impl_->record_frame(cmd, scene, options);
}

Frame FrameRenderer::read_back() {
  if (impl_->last_slot < 0 || !impl_->previous)
    throw InputError("FrameRenderer::read_back: no frame has been recorded yet");
  impl_->ctx.wait_queue_idle();
  impl_->collect(impl_->last_slot);
  Frame frame = impl_->download_last(*impl_->previous);
  if (impl_->completed) {
    const double mean = frame.stats.mean_luminance, cover = frame.stats.cloud_cover_fraction;
    frame.stats = *impl_->completed;
    frame.stats.mean_luminance = mean;
    frame.stats.cloud_cover_fraction = cover;
  }
  return frame;
}

void FrameRenderer::Impl::collect(int slot) {
  if (slot < 0 || !pending[slot]) return;
  for (RenderModule* module : prepare_order()) module->finished(slot);
  completed_lighting = host_lighting.collect(slot);
  FrameStats stats = std::move(*pending[slot]);
  pending[slot].reset();
  stats.metered_luminance = metered_luminance(state, slot);
  for (const auto& [name, ms] : state.timers[slot]->results()) {
    stats.passes.push_back({name, ms});
    stats.frame_ms += ms;
  }
  if (verbose)
    for (const PassTiming& p : stats.passes)
      std::fprintf(stderr, "nephele: pass %-12s %8.2f ms%s\n", p.name.c_str(), p.ms,
                   p.name == "sky_view"
                       ? " (cached until the sun, the camera position or the atmosphere change)"
                       : "");
  completed = std::move(stats);
}

Frame FrameRenderer::Impl::download_last(const Scene& scene) {
  Frame frame;
  frame.color = download(ctx, state.color[last_slot], false);
  frame.clouds = resample(download(ctx, clouds.cloud_buffer(), false), state.width, state.height);
  double sum = 0.0;
  for (const glm::vec4& p : frame.color.pixels) sum += luminance(p);
  frame.stats.mean_luminance = sum / double(frame.color.pixels.size());
  frame.stats.cloud_cover_fraction = cloud_cover_fraction(scene, frame.clouds);
  return frame;
}

FrameImages FrameRenderer::Impl::record_frame(VkCommandBuffer cmd, const Scene& requested,
                                              const FrameOptions& options) {
  validate_scene(requested);
  // Every argument is checked before any module changes its state: a refused call leaves the
  // renderer as it was.
  if (options.host_scene)
    if (const std::string problem = host_scene_problem(*options.host_scene, requested);
        !problem.empty())
      throw InputError("FrameRenderer::record_frame: " + problem);
  if (const std::string problem = host_lighting_problem(options.lighting); !problem.empty())
    throw InputError("FrameRenderer::record_frame: " + problem);
  // A lab (a grid in vacuum) is drawn as the scene lab_fast_scene makes of it.
  std::optional<Scene> lab;
  if (!requested.lab.grid.empty())
    lab = lab_fast_scene(requested, voxel_clouds.grid(lab_voxel_cloud(requested)));
  const Scene& scene = lab ? *lab : requested;
  const bool still = options.still;
  // The seed's algorithm (baseline) is run as written: every pixel, every frame. A still image
  // marches every pixel at full resolution.
  const bool baseline = scene.quality.mode == MarchMode::Baseline;
  const int downsample = baseline || still ? 1 : scene.quality.cloud_downsample;
  const int stride = still || baseline ? 1 : scene.quality.march_stride;
  const std::string key = history_key(scene);
  // A paused view (FrameOptions::reuse_settled): the last frame again, once settled. The same
  // scene: the same history key and what the key leaves out.
  const bool reusable =
      options.reuse_settled && !still && !options.host_scene && !options.lighting.enabled;
  const bool unchanged = reusable && previous_reusable && key == previous_key &&
                         scene.camera == previous->camera && scene.sun == previous->sun &&
                         scene.time_s == previous->time_s &&
                         scene.output.ev100 == previous->output.ev100 &&
                         scene.output.auto_exposure == previous->output.auto_exposure;
  const long long settled = stride == 1 ? 1 : 2LL * stride * stride;
  if (unchanged && unchanged_frames >= settled && !last_plan.building &&
      (previous_display || !options.display)) {
    FrameImages images = frame_images(last_slot, false);
    images.reused = true;
    return images;
  }
  const auto start = std::chrono::steady_clock::now();
  const int slot = int(frames_recorded % gpu::kFramesInFlight);
  collect(slot);  // the host has waited for the frame recorded there before
  const int cloud_w = (scene.output.width + downsample - 1) / downsample;
  const int cloud_h = (scene.output.height + downsample - 1) / downsample;
  const SkyLights lights = sky_lights(scene);  // the ephemeris and key light, once a frame
  const bool image_resized =
      state.width != scene.output.width || state.height != scene.output.height;
  const bool resized = image_resized || clouds.width() != cloud_w || clouds.height() != cloud_h;
  const bool continues = !still && stride > 1 && previous && key == previous_key &&
                         history_usable(scene, *previous, lights.key.direction, previous_light_dir);
  // An animation after a still of the same image continues from the still: its cloud buffer,
  // box-filtered down to the animation's, is the history (CloudsModule::resize).
  const bool from_still = continues && resized && !image_resized && previous_still;
  const bool history = continues && (!resized || from_still);
  if (!history) frame_counter = 0;
  update_atmosphere_luts(scene);

  GpuState& s = state;
  if (resized) ctx.wait_queue_idle();  // the frames in flight use the images replaced
  s.resize(scene.output.width, scene.output.height);
  clouds.resize(cloud_w, cloud_h, from_still);
  clouds.set_stride(stride);
  gpu::FrameParams params = make_frame_params(scene, int(frame_counter), lights,
                                              atmosphere.tables(), window ? &*window : nullptr);
  if (history) set_previous_frame(params, scene, *previous);
  const glm::ivec2 offset = march_offset(stride, frame_counter);
  // After a build for an edit relit the clouds, each pixel's next march (stride^2 frames)
  // starts its mean afresh rather than take in the new light an eighth at a time.
  if (last_plan.relit) relit_frames_left = stride * stride;
  params.cloud_grid =
      glm::ivec4(cloud_w, cloud_h, stride, !history ? 0 : (relit_frames_left > 0 ? 2 : 1));
  if (relit_frames_left > 0) --relit_frames_left;
  params.cloud_shape.x = 2.0f * params.camera_pos_m.w / float(cloud_h);  // detail noise's LOD
  params.march_offset = glm::ivec4(offset, int(frame_counter / (stride * stride)), downsample);
  // A classical model (seed 004) draws instead of the march; a sky without volumetric clouds
  // (clear, or particle clouds only) skips it.
  FramePlan plan;
  plan.classic = scene.clouds.model != CloudModel::Nephele;
  plan.volumetric =
      !plan.classic && (scene.clouds.coverage > 0.0f || volumetric_layers(scene).size() > 1 ||
                        !scene.voxel_clouds.empty());
  plan.display = options.display;
  FramePrepare prepare{scene, params, slot, still, s.width, s.height, &options, &lights};
  for (RenderModule* module : prepare_order()) module->prepare(prepare, plan);
  if (verbose)
    for (const std::string& read : plan.cache_reads)
      std::fprintf(stderr, "nephele: pass %s\n", read.c_str());
  if (lab) params.voxel_light.z = 0.0f;  // the grid as the file has it: no surface erosion
  if (scene.atmosphere.model == SkyModel::Reference) render_reference_sky(params);
  update_noise(scene, params);
  // Measured again once a light volume or a diffusion field is completed (the modules' prepare
  // says so): the clouds' bases take their light from below by it (clouds.comp).
  plan.ground_light =
      plan.ground_light || light_volume.completed() || params.light_volume.w == 0.0f;
  const FrameGraph graph = frame_graph(scene, params, plan);
  if (verbose && frames_recorded == 0)
    std::fprintf(stderr, "nephele: frame graph\n%s", graph.describe().c_str());
  // Bands are submitted now, before the host's commands that draw its scene.
  const bool in_bands = still && progress && plan.volumetric && !plan.host_scene;
  band_timings.clear();
  std::vector<std::string> passes;
  if (in_bands) passes = march_in_bands(graph, scene, params);
  s.begin(cmd, slot, params);
  if (in_bands)
    graph.execute(cmd, graph_barrier, passes);
  else
    graph.execute(cmd, graph_barrier);
  gpu::frame_end_barrier(cmd, ctx.has_graphics());

  previous = scene;
  previous_key = key;
  // Settled 2 stride^2 frames after the last change, or after the last frame that built.
  unchanged_frames = unchanged && !plan.building ? unchanged_frames + 1 : 1;
  previous_reusable = reusable;
  previous_display = options.display;
  previous_still = still;
  previous_light_dir = lights.key.direction;
  ++frame_counter;
  last_params = params;
  last_plan = plan;

  FrameStats stats = frame_stats(scene, lights);
  stats.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  for (const PassTiming& p : band_timings) {
    stats.passes.push_back(p);
    stats.frame_ms += p.ms;
  }
  pending[slot] = std::move(stats);
  ++frames_recorded;
  last_slot = slot;
  return frame_images(slot, plan.host_lighting);
}

FrameStats FrameRenderer::Impl::frame_stats(const Scene& scene, const SkyLights& lights) const {
  FrameStats stats;
  stats.device = ctx.device_name();
  stats.width = state.width;
  stats.height = state.height;
  stats.ephemeris = lights.ephemeris;
  stats.voxel_clouds = voxel_clouds.memory();
  stats.voxel_bytes = scene.voxel_clouds.empty() ? 0 : voxel_clouds.device_bytes();
  if (scene.particle_clouds.coverage > 0.0f) stats.particle_clouds = particles.frame_stats();
  if (stats.ephemeris && scene.sun.from_time) {
    stats.sun = stats.ephemeris->sun;
  } else {
    const glm::vec3 sun = scene_sun_direction(scene, std::nullopt);
    const SunAngles angles = sun_angles_from_direction(sun);
    stats.sun = {angles.elevation_deg, angles.azimuth_deg, 0.0, sun};
  }
  return stats;
}

FrameImages FrameRenderer::Impl::frame_images(int slot, bool host_lighting_images) const {
  const GpuState& s = state;
  FrameImages images{slot,
                     uint32_t(s.width),
                     uint32_t(s.height),
                     s.color[slot].image(),
                     s.color[slot].view(),
                     s.display[slot].image(),
                     s.display[slot].view()};
  if (host_lighting_images) {
    images.cloud_shadow = host_lighting.shadow_map().image();
    images.cloud_shadow_view = host_lighting.shadow_map().view();
    images.world_to_cloud_shadow = host_lighting.world_to_shadow_map();
    images.environment = host_lighting.environment().image();
    images.environment_view = host_lighting.environment().view();
  }
  return images;
}

}  // namespace nephele

// The renderer: orders the passes of a frame, caches what does not change, reads back.
#include "nephele/renderer.h"
#include "nephele/sky.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <optional>

#include <glm/gtc/packing.hpp>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "render/frame_params.h"
#include "render/passes.h"

namespace nephele {

struct Renderer::Impl {
  explicit Impl(const RendererOptions& options)
      : ctx({options.device, options.validation, options.verbose}), state(ctx) {}

  gpu::Context ctx;
  GpuState state;
  bool verbose = false;
  std::optional<uint32_t> noise_seed_built;  // noise textures are valid for this seed
  std::optional<std::string> weather_built;  // key of the weather map in the texture
  std::optional<Scene> previous;             // the scene of the last frame rendered
  std::string previous_key;                  // its history_key()
  glm::vec3 previous_light_dir{0.0f};        // its key light (sky_lights)
  long long frame_counter = 0;               // frames since the history (re)started
  // The light volume in the buffer: what it was built for.
  struct LightVolumeKey {
    std::string clouds;    // history_key() of the scene
    glm::vec3 sun{0.0f};
    glm::vec2 centre_m{0.0f};  // in cloud space
    float drift_m = 0.0f;      // cloud_relative_drift_m
  };
  std::optional<LightVolumeKey> light_volume_built;

  // Sets params.light_volume; true when the volume must be rebuilt this frame.
  bool plan_light_volume(const Scene& scene, const std::string& key, gpu::FrameParams& params);

  // Inputs of the sky-view LUT in the texture and the LUT frame it was built in.
  struct SkyViewBuilt {
    SkyViewKey key;
    glm::vec4 up, forward;
  };
  std::optional<SkyViewBuilt> sky_view_built;
  // Hillaire's transmittance and multiple-scattering tables: what they were built for, and
  // their copy on the host for the lighting computed on the CPU.
  std::optional<AtmosphereParams> luts_built;
  AtmosphereTables tables;
  void update_atmosphere_luts(const Scene& scene);
  // The brute-force reference sky, tile by tile (one submission each), into state.reference_sky.
  void render_reference_sky(gpu::FrameParams params);

  Frame render_frame(const Scene& scene, bool still, bool read_back);
  // The clouds pass over the sky dome (after a frame, with its parameters and textures):
  // the share of the observer's upper hemisphere with cloud T < 0.5, and the pass's time.
  double measure_sky_cover(gpu::FrameParams params, MarchMode mode, double& ms);

  void update_textures(const Scene& scene);
  void upload_weather_png(const std::string& path);
  void resize_weather_map(uint32_t width, uint32_t height);
};

namespace {

// The weather map's inputs: a file, or the seed and the weather's time (weather_time).
std::string weather_key(const Scene& scene) {
  return scene.clouds.weather_map.empty() ? "procedural:" + std::to_string(scene.noise_seed) +
                                                "@" + std::to_string(weather_time(scene))
                                          : "file:" + scene.clouds.weather_map;
}

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
    image.pixels[i] = glm::vec4(glm::unpackHalf2x16(src[2 * i]), glm::unpackHalf2x16(src[2 * i + 1]));
  return image;
}

// Bilinear resampling to width x height, both grids spanning the same field of view (as
// compose.comp reads the cloud buffer).
Image resample(const Image& src, int width, int height) {
  if (src.width == width && src.height == height) return src;
  Image out(width, height);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float gx = glm::clamp((x + 0.5f) * src.width / width - 0.5f, 0.0f, src.width - 1.0f);
      const float gy =
          glm::clamp((y + 0.5f) * src.height / height - 0.5f, 0.0f, src.height - 1.0f);
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

// Everything but the camera, the time and the sun: when it changes, the history is stale.
std::string history_key(Scene scene) {
  scene.camera = CameraParams{};
  scene.sun = SunParams{};
  scene.time_s = 0.0f;
  scene.output.exposure = 1.0f;
  return scene_to_toml(scene);
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
  return cos_sun > std::cos(glm::radians(0.5f)) && scene.sun.illuminance == previous.sun.illuminance &&
         glm::distance(scene.camera.position_m, previous.camera.position_m) < 1000.0f &&
         layer_side(scene) == layer_side(previous);
}

// Share of above-horizon pixels (view ray rising above the camera's local horizontal) whose
// cloud transmittance is below 0.5.
double cloud_cover_fraction(const Scene& scene, const Image& clouds) {
  const CameraBasis basis = camera_basis(scene.camera);
  const float tan_half_fov = std::tan(glm::radians(scene.camera.fov_deg) * 0.5f);
  const float aspect = float(clouds.width) / float(clouds.height);
  const glm::vec3 up = glm::normalize(planet_from_enu(scene, scene.camera.position_m));
  size_t above = 0, covered = 0;
  for (int y = 0; y < clouds.height; ++y)
    for (int x = 0; x < clouds.width; ++x) {
      glm::vec3 dir = glsl::camera_ray(basis.forward, basis.right, basis.up, tan_half_fov, aspect,
                                       float(x), float(y), float(clouds.width),
                                       float(clouds.height));
      if (glm::dot(dir, up) <= 0.0f) continue;
      ++above;
      if (clouds.at(x, y).a < 0.5f) ++covered;
    }
  return above == 0 ? 0.0 : double(covered) / double(above);
}

}  // namespace

// A PNG weather map of another size replaces the texture (and its descriptors).
void Renderer::Impl::resize_weather_map(uint32_t width, uint32_t height) {
  if (state.weather_map.width() == width && state.weather_map.height() == height) return;
  state.weather_map = gpu::Texture(ctx, width, height, 1, VK_FORMAT_R8G8B8A8_UNORM);
  state.set.bind_image(gpu::kWeatherOut, gpu::kWeatherMap, state.weather_map);
}

void Renderer::Impl::upload_weather_png(const std::string& path) {
  Image png = read_image(path);
  resize_weather_map(uint32_t(png.width), uint32_t(png.height));
  gpu::Buffer staging(ctx, VkDeviceSize(png.pixels.size()) * 4, VK_BUFFER_USAGE_TRANSFER_SRC_BIT);
  auto* bytes = static_cast<unsigned char*>(staging.data());
  for (size_t i = 0; i < png.pixels.size(); ++i)
    for (int c = 0; c < 4; ++c)
      bytes[4 * i + c] =
          static_cast<unsigned char>(glm::clamp(png.pixels[i][c], 0.0f, 1.0f) * 255.0f + 0.5f);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) { state.weather_map.record_upload(cmd, staging); });
}

void Renderer::Impl::update_textures(const Scene& scene) {
  const std::string key = weather_key(scene);
  const bool noise_stale = noise_seed_built != scene.noise_seed;
  if (!scene.clouds.weather_map.empty() && weather_built != key) {
    upload_weather_png(scene.clouds.weather_map);
    weather_built = key;
  }
  const bool weather_stale = weather_built != key;
  if (!noise_stale && !weather_stale) return;
  if (weather_stale) resize_weather_map(kWeatherMapSize, kWeatherMapSize);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    state.timer.reset(cmd);
    if (noise_stale) {
      pass_noise_base(cmd, state);
      pass_noise_detail(cmd, state);
      pass_noise_curl(cmd, state);
    }
    if (weather_stale) pass_weather(cmd, state);
  });
  if (verbose)
    for (const auto& [name, ms] : state.timer.results())
      std::fprintf(stderr, "nephele: pass %-12s %8.2f ms (cached until its parameters change)\n",
                   name.c_str(), ms);
  noise_seed_built = scene.noise_seed;
  weather_built = key;
}

void Renderer::Impl::update_atmosphere_luts(const Scene& scene) {
  if (luts_built == scene.atmosphere) return;
  gpu::FrameParams params{};
  set_atmosphere(params, scene);
  std::memcpy(state.frame_params.data(), &params, sizeof(params));
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    state.timer.reset(cmd);
    pass_atmosphere_luts(cmd, state);
  });
  if (verbose)
    for (const auto& [name, ms] : state.timer.results())
      std::fprintf(stderr, "nephele: pass %-12s %8.2f ms (cached until the atmosphere changes)\n",
                   name.c_str(), ms);
  tables.transmittance = download(ctx, state.transmittance_lut, false).pixels;
  tables.multiple_scattering = download(ctx, state.ms_lut, false).pixels;
  luts_built = scene.atmosphere;
  sky_view_built.reset();
}

void Renderer::Impl::render_reference_sky(gpu::FrameParams params) {
  state.resize_reference_sky(state.width, state.height);
  double ms = 0.0;
  for (int y = 0; y < state.height; y += gpu::REFERENCE_TILE)
    for (int x = 0; x < state.width; x += gpu::REFERENCE_TILE) {
      params.reference_tile = glm::ivec4(x, y, gpu::REFERENCE_TILE, gpu::REFERENCE_SAMPLES);
      std::memcpy(state.frame_params.data(), &params, sizeof(params));
      ctx.submit_and_wait([&](VkCommandBuffer cmd) {
        state.timer.reset(cmd);
        pass_reference_sky(cmd, state);
      });
      for (const auto& [name, pass_ms] : state.timer.results()) ms += pass_ms;
    }
  if (verbose) std::fprintf(stderr, "nephele: pass %-12s %8.2f ms\n", "reference", ms);
}

bool Renderer::Impl::plan_light_volume(const Scene& scene, const std::string& key,
                                       gpu::FrameParams& params) {
  const float half_m = float(scene.quality.light_volume_km) * 1000.0f;
  if (half_m <= 0.0f || scene.quality.mode == MarchMode::Baseline) {
    params.light_volume = glm::vec4(0.0f);
    return false;
  }
  const glm::vec3 sun(params.sun_dir);  // the key light
  const glm::vec2 camera_cloud_m = glm::vec2(scene.camera.position_m) - glm::vec2(params.wind_offset_m);
  const LightVolumeKey* built = light_volume_built ? &*light_volume_built : nullptr;
  // Rebuilt when the clouds or the sun (by 0.25 deg) change, when the camera has moved 1/20 of
  // the half extent from the centre in cloud space (where the voxels are finest), or when the
  // clouds' features have moved 100 m against the volume's frame (shear, detail wind, the high
  // layer's wind, the flow).
  const float drift_m = cloud_relative_drift_m(scene);
  const bool stale = !built || built->clouds != key ||
                     glm::dot(built->sun, sun) < std::cos(glm::radians(0.25f)) ||
                     glm::distance(built->centre_m, camera_cloud_m) > 0.05f * half_m ||
                     std::abs(drift_m - built->drift_m) > 100.0f;
  if (stale) light_volume_built = LightVolumeKey{key, sun, camera_cloud_m, drift_m};
  params.light_volume = glm::vec4(light_volume_built->centre_m, half_m, 1.0f);
  return stale;
}

double Renderer::Impl::measure_sky_cover(gpu::FrameParams params, MarchMode mode, double& ms) {
  params.steps.w = gpu::PROJECTION_SKY_DOME;
  params.cloud_shape.x = 0.0f;  // the detail noise's finest level, as an observer sees it
  params.cloud_grid = glm::ivec4(kSkyDomeSize, kSkyDomeSize, 1, 0);
  params.march_offset = glm::ivec4(0, 0, 0, 1);
  std::memcpy(state.frame_params.data(), &params, sizeof(params));
  state.bind_march(true);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    state.timer.reset(cmd);
    pass_sky_dome(cmd, state, mode);
  });
  state.bind_march(false);
  ms = 0.0;
  for (const auto& [name, pass_ms] : state.timer.results()) ms += pass_ms;
  const Image dome = download(ctx, state.dome_a, false);
  const auto covered = std::count_if(dome.pixels.begin(), dome.pixels.end(),
                                     [](const glm::vec4& p) { return p.a < 0.5f; });
  return double(covered) / double(dome.pixels.size());
}

CloudProfile Renderer::cloud_profile(const Scene& scene) {
  validate_scene(scene);
  Impl& impl = *impl_;
  impl.update_atmosphere_luts(scene);
  gpu::FrameParams params = make_frame_params(scene, 0, sky_lights(scene), impl.tables);
  params.cloud_weather.w = 0.5f * scene.clouds.weather_period_m;
  std::memcpy(impl.state.frame_params.data(), &params, sizeof(params));
  impl.update_textures(scene);
  impl.state.bind_march(true);
  impl.ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    impl.state.timer.reset(cmd);
    pass_cloud_profile(cmd, impl.state);
  });
  impl.state.bind_march(false);
  const Image sums = download(impl.ctx, impl.state.dome_a, false);
  const glm::vec2 shell_m = cloud_shell_m(scene);
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

int sky_cover_oktas(double fraction) {
  if (fraction < 0.01) return 0;
  if (fraction > 0.99) return 8;
  return std::clamp(int(std::lround(fraction * 8.0)), 1, 7);
}

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {
  impl_->verbose = options.verbose;
}

Renderer::~Renderer() = default;

const std::string& Renderer::device_name() const { return impl_->ctx.device_name(); }

int Renderer::validation_messages() const { return impl_->ctx.validation_messages(); }

Frame Renderer::render(const Scene& scene) { return impl_->render_frame(scene, true, true); }

Frame Renderer::render_next(const Scene& scene, bool read_back) {
  return impl_->render_frame(scene, false, read_back);
}

Frame Renderer::Impl::render_frame(const Scene& scene, bool still, bool read_back) {
  validate_scene(scene);
  const auto start = std::chrono::steady_clock::now();
  // The seed's algorithm (baseline) is run as written: every pixel, every frame. A still image
  // marches every pixel at full resolution.
  const bool baseline = scene.quality.mode == MarchMode::Baseline;
  const int downsample = baseline || still ? 1 : scene.quality.cloud_downsample;
  const int stride = still || baseline ? 1 : scene.quality.march_stride;
  const int cloud_w = (scene.output.width + downsample - 1) / downsample;
  const int cloud_h = (scene.output.height + downsample - 1) / downsample;
  const std::string key = history_key(scene);
  const SkyLights lights = sky_lights(scene);  // the ephemeris and key light, once a frame
  const bool resized = state.width != scene.output.width || state.height != scene.output.height ||
                       state.cloud_width != cloud_w || state.cloud_height != cloud_h;
  const bool history = !still && stride > 1 && !resized && previous && key == previous_key &&
                       history_usable(scene, *previous, lights.key.direction, previous_light_dir);
  if (!history) frame_counter = 0;
  update_atmosphere_luts(scene);

  GpuState& s = state;
  s.resize(scene.output.width, scene.output.height, cloud_w, cloud_h);
  s.stride = stride;
  gpu::FrameParams params = make_frame_params(scene, int(frame_counter), lights, tables);
  if (history) set_previous_frame(params, scene, *previous);
  const glm::ivec2 offset = march_offset(stride, frame_counter);
  params.cloud_grid = glm::ivec4(cloud_w, cloud_h, stride, history ? 1 : 0);
  params.cloud_shape.x = 2.0f * params.camera_pos_m.w / float(cloud_h);  // detail noise's LOD
  params.march_offset = glm::ivec4(offset, int(frame_counter / (stride * stride)), downsample);
  const bool build_light_volume = plan_light_volume(scene, key + weather_key(scene), params);
  // The sky-view LUT depends on the sun, the camera's position and the atmosphere only: a
  // camera turning or clouds changing reuse it, and so does a camera that moved a little
  // (sky_view_reusable), sampled in the frame the LUT was built in.
  const SkyViewKey sky_key = sky_view_key(params);
  const bool sky_stale = !sky_view_built || !sky_view_reusable(sky_view_built->key, sky_key);
  if (!sky_stale) {
    params.sky_view_up = sky_view_built->up;
    params.sky_view_forward = sky_view_built->forward;
  }
  if (scene.atmosphere.model == SkyModel::Reference) render_reference_sky(params);
  std::memcpy(s.frame_params.data(), &params, sizeof(params));  // the noise passes read it too
  update_textures(scene);
  s.swap_history();

  if (sky_stale) sky_view_built.reset();  // until the command buffer below has completed
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    s.timer.reset(cmd);
    if (sky_stale) pass_sky_view(cmd, s);
    if (build_light_volume) pass_light_volume(cmd, s);
    pass_clouds(cmd, s, scene.quality.mode);
    pass_march_range(cmd, s);
    pass_resolve(cmd, s);
    // The ground's light changes as slowly as the light volume's (3.9 ms on lavapipe).
    if (build_light_volume || params.light_volume.w == 0.0f)
      pass_ground_light(cmd, s, scene.quality.mode);
    pass_compose(cmd, s, scene.atmosphere.model);
    pass_stars(cmd, s);
  });
  previous = scene;
  previous_key = key;
  previous_light_dir = lights.key.direction;
  ++frame_counter;
  if (sky_stale) sky_view_built = SkyViewBuilt{sky_key, params.sky_view_up, params.sky_view_forward};

  Frame frame;
  FrameStats& stats = frame.stats;
  stats.device = ctx.device_name();
  stats.width = s.width;
  stats.height = s.height;
  stats.ephemeris = lights.ephemeris;
  if (stats.ephemeris && scene.sun.from_time) {
    stats.sun = stats.ephemeris->sun;
  } else {
    const glm::vec3 sun = scene_sun_direction(scene, std::nullopt);
    const SunAngles angles = sun_angles_from_direction(sun);
    stats.sun = {angles.elevation_deg, angles.azimuth_deg, 0.0, sun};
  }
  for (const auto& [name, ms] : s.timer.results()) {
    stats.passes.push_back({name, ms});
    stats.frame_ms += ms;
  }
  if (read_back) {
    frame.color = download(ctx, s.color, false);
    frame.clouds = resample(download(ctx, s.clouds_a[s.current], false), s.width, s.height);
    double sum = 0.0;
    for (const glm::vec4& p : frame.color.pixels) sum += luminance(p);
    stats.mean_luminance = sum / double(frame.color.pixels.size());
    stats.cloud_cover_fraction = cloud_cover_fraction(scene, frame.clouds);
  }
  if (still && read_back) {
    double ms = 0.0;
    stats.sky_cover_fraction = measure_sky_cover(params, scene.quality.mode, ms);
    stats.passes.push_back({"sky_dome", ms});
  }
  stats.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (verbose)
    for (const PassTiming& p : stats.passes)
      std::fprintf(stderr, "nephele: pass %-12s %8.2f ms%s\n", p.name.c_str(), p.ms,
                   p.name == "sky_view"
                       ? " (cached until the sun, the camera position or the atmosphere change)"
                       : "");
  return frame;
}

}  // namespace nephele

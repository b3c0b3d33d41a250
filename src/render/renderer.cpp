// The renderer: orders the passes of a frame, caches what does not change, reads back.
#include "nephele/renderer.h"

#include <chrono>
#include <cstdio>
#include <cstring>
#include <optional>

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
  std::optional<SkyViewKey> sky_view_built;  // inputs of the sky-view LUT in the texture

  void update_textures(const Scene& scene);
  void upload_weather_png(const std::string& path);
  void resize_weather_map(uint32_t width, uint32_t height);
};

namespace {

std::string weather_key(const Scene& scene) {
  return scene.clouds.weather_map.empty() ? "procedural:" + std::to_string(scene.noise_seed)
                                          : "file:" + scene.clouds.weather_map;
}

// Reads one vec4 per pixel from a buffer holding `stride` vec4s per pixel.
Image read_buffer(const gpu::Buffer& buffer, int width, int height, int stride = 1) {
  Image image(width, height);
  const auto* src = static_cast<const glm::vec4*>(buffer.data());
  for (size_t i = 0; i < image.pixels.size(); ++i) image.pixels[i] = src[i * size_t(stride)];
  return image;
}

// Share of above-horizon pixels (view ray rising above the camera's local horizontal) whose
// cloud transmittance is below 0.5.
double cloud_cover_fraction(const Scene& scene, const Image& clouds) {
  const CameraBasis basis = camera_basis(scene.camera.view_dir);
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
  state.set.bind_storage_image(gpu::kWeatherOut, state.weather_map);
  state.set.bind_sampled_image(gpu::kWeatherMap, state.weather_map);
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

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {
  impl_->verbose = options.verbose;
}

Renderer::~Renderer() = default;

const std::string& Renderer::device_name() const { return impl_->ctx.device_name(); }

int Renderer::validation_messages() const { return impl_->ctx.validation_messages(); }

Frame Renderer::render(const Scene& scene) {
  validate_scene(scene);
  const auto start = std::chrono::steady_clock::now();
  GpuState& s = impl_->state;
  s.resize(scene.output.width, scene.output.height);
  const gpu::FrameParams params = make_frame_params(scene, 0);
  std::memcpy(s.frame_params.data(), &params, sizeof(params));
  impl_->update_textures(scene);

  // The sky-view LUT depends on the sun, the camera's position and the atmosphere only: a
  // camera turning or clouds changing reuse it.
  const SkyViewKey sky_key = sky_view_key(params);
  const bool sky_stale = impl_->sky_view_built != sky_key;
  impl_->sky_view_built.reset();  // until the command buffer below has completed
  impl_->ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    s.timer.reset(cmd);
    if (sky_stale) pass_sky_view(cmd, s);
    pass_clouds(cmd, s, scene.quality.mode);
    pass_compose(cmd, s);
  });
  impl_->sky_view_built = sky_key;

  Frame frame;
  frame.color = read_buffer(s.color_buffer, s.width, s.height);
  frame.clouds = read_buffer(s.cloud_buffer, s.width, s.height, 2);
  FrameStats& stats = frame.stats;
  stats.device = impl_->ctx.device_name();
  stats.width = s.width;
  stats.height = s.height;
  for (const auto& [name, ms] : s.timer.results()) {
    stats.passes.push_back({name, ms});
    stats.frame_ms += ms;
  }
  double sum = 0.0;
  for (const glm::vec4& p : frame.color.pixels) sum += luminance(p);
  stats.mean_luminance = sum / double(frame.color.pixels.size());
  stats.cloud_cover_fraction = cloud_cover_fraction(scene, frame.clouds);
  stats.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (impl_->verbose)
    for (const PassTiming& p : stats.passes)
      std::fprintf(stderr, "nephele: pass %-12s %8.2f ms%s\n", p.name.c_str(), p.ms,
                   p.name == "sky_view"
                       ? " (cached until the sun, the camera position or the atmosphere change)"
                       : "");
  return frame;
}

}  // namespace nephele

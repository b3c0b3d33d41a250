// The renderer for stills and animations: each frame recorded by the frame API
// (FrameRenderer) into a command buffer of its own context, submitted, waited for, read back.
#include "nephele/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "nephele/cloud_query.h"
#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele/scene_io.h"
#include "render/frame_renderer_impl.h"
#include "render/modules/light_shafts/light_shafts.h"

namespace nephele {

namespace {

// Strips as wide as the image unless they would be thinner than this; then square tiles.
constexpr int kMinStripRows = 64;

// Each tile is drawn with this many pixels more on every side, then cropped: what reads its
// neighbours (the light shafts, drawn at an eighth of the resolution and interpolated) sees
// the same neighbours as in the whole image.
constexpr int kTileMarginPx = 2 * kLightShaftsDownsample;
// Tiles start on multiples of this: the shafts' coarse pixels fall where the image's do.
constexpr int kTileAlignPx = kLightShaftsDownsample;
// The smallest tile budget: a square window of four margins a side, half of it the tile.
constexpr int64_t kMinTilePixels = int64_t(16) * kTileMarginPx * kTileMarginPx;

int64_t checked_max_tile_pixels(const RendererOptions& options) {
  if (options.max_tile_pixels == 0) return kDefaultMaxTilePixels;
  if (options.max_tile_pixels < kMinTilePixels)
    throw InputError(
        "RendererOptions::max_tile_pixels = " + std::to_string(options.max_tile_pixels) +
        ": must be 0 (the default, " + std::to_string(kDefaultMaxTilePixels) + ") or at least " +
        std::to_string(kMinTilePixels));
  return options.max_tile_pixels;
}

// What tiles drawn one at a time cannot show: effects that reach across the image, and
// particle clouds (drawn by a raster pipeline of their own).
std::string untileable_feature(const Scene& scene) {
  if (scene.output.bloom_strength > 0.0f) return "bloom (output.bloom_strength > 0)";
  if (scene.quality.light_shafts == "screen")
    return "screen-space light shafts (quality.light_shafts = \"screen\")";
  if (scene.particle_clouds.coverage > 0.0f) return "particle clouds (particle_clouds.coverage > 0)";
  return "";
}

// Copies the w x h pixels of `drawn` from (from_x, from_y) into `image` at (x, y).
void place(Image& image, const Image& drawn, int from_x, int from_y, int w, int h, int x, int y) {
  for (int row = 0; row < h; ++row)
    std::copy_n(drawn.pixels.begin() + ptrdiff_t(from_y + row) * drawn.width + from_x, w,
                image.pixels.begin() + ptrdiff_t(y + row) * image.width + x);
}

}  // namespace

struct Renderer::Impl {
  explicit Impl(const RendererOptions& options)
      : max_tile_pixels(checked_max_tile_pixels(options)), frames(options) {}
  int64_t max_tile_pixels;
  FrameRenderer frames;
};

Renderer::Renderer(const RendererOptions& options) : impl_(std::make_unique<Impl>(options)) {}

Renderer::~Renderer() = default;

const std::string& Renderer::device_name() const { return impl_->frames.device_name(); }

int Renderer::validation_messages() const { return impl_->frames.validation_messages(); }

Renderer::Tiling Renderer::tiling(const Scene& scene) const {
  const int w = scene.output.width, h = scene.output.height;
  VkPhysicalDeviceProperties properties;
  vkGetPhysicalDeviceProperties(impl_->frames.impl_->ctx.physical_device(), &properties);
  const int64_t side = properties.limits.maxImageDimension2D;
  const int64_t pixels = impl_->max_tile_pixels;
  Tiling t{1, 1, w, h};
  if (w <= side && h <= side && int64_t(w) * h <= pixels) return t;
  // A tile is drawn with kTileMarginPx more on each side (within the image): its window.
  const auto window = [&](int64_t core, int64_t whole) {
    return std::min(core + 2 * kTileMarginPx, whole);
  };
  // Strips as wide as the image (or the device) where they are thick enough; else squares.
  int64_t core_w = std::min<int64_t>(w, side - 2 * kTileMarginPx);
  if (pixels / window(core_w, w) < std::min<int64_t>(h, kMinStripRows) + 2 * kTileMarginPx)
    core_w = std::min<int64_t>(core_w, int64_t(std::sqrt(double(pixels))) - 2 * kTileMarginPx);
  const auto aligned = [](int64_t n) { return n / kTileAlignPx * kTileAlignPx; };
  const auto share = [](int64_t whole, int64_t parts) {  // rounded up to the alignment
    return int((whole + parts - 1) / parts + kTileAlignPx - 1) / kTileAlignPx * kTileAlignPx;
  };
  core_w = aligned(core_w);
  t.columns = int((w + core_w - 1) / core_w);
  t.tile_width = std::min<int>(share(w, t.columns), w);
  const int64_t window_w = window(t.tile_width, w);
  const int64_t core_h = aligned(std::min<int64_t>(side, pixels / window_w) - 2 * kTileMarginPx);
  t.rows = int((h + core_h - 1) / core_h);
  t.tile_height = std::min<int>(share(h, t.rows), h);
  t.columns = (w + t.tile_width - 1) / t.tile_width;
  t.rows = (h + t.tile_height - 1) / t.tile_height;
  return t;
}

Frame Renderer::render(const Scene& scene) {
  validate_scene(scene);
  const Tiling t = tiling(scene);
  if (t.columns * t.rows > 1) return render_tiles(scene, t, false).frame;
  return render_frame(scene, true, true);
}

// A still too large for one frame, a window at a time: each window is a frame of its own (a
// still of the same camera whose rays are the whole image's there: frame_params.h,
// ImageWindow), read back into its place. The exposure is the CLI's, from the whole image;
// the stats are the whole image's.
FilmLayers Renderer::render_tiles(const Scene& scene, const Tiling& t, bool layers) {
  if (const std::string feature = untileable_feature(scene); !feature.empty())
    throw InputError("output.width x output.height = " + std::to_string(scene.output.width) +
                     " x " + std::to_string(scene.output.height) + ": larger than one frame on " +
                     device_name() + " (at most " + std::to_string(impl_->max_tile_pixels) +
                     " pixels, " + std::to_string(t.tile_width) +
                     " a side here), so it renders in tiles, which " + feature +
                     " cannot be drawn in; render it smaller or without them");
  const auto start = std::chrono::steady_clock::now();
  FrameRenderer::Impl& f = *impl_->frames.impl_;
  const int w = scene.output.width, h = scene.output.height;
  FilmLayers out;
  out.frame.color = Image(w, h);
  out.frame.clouds = Image(w, h);
  if (layers) out.sky = Image(w, h), out.clouds = Image(w, h), out.clouds_depth_m = Image(w, h);
  // The tiles report as one stage; each tile's own stages stay quiet.
  const ProgressCallback progress = std::move(f.progress);
  f.progress = nullptr;
  struct Restore {
    FrameRenderer::Impl& f;
    ProgressCallback progress;
    ~Restore() {
      f.window.reset();
      f.progress = std::move(progress);
    }
  } restore{f, progress};
  const int tiles = t.columns * t.rows;
  if (progress) progress("tiles", 0, tiles);
  FrameStats stats;
  for (int i = 0; i < tiles; ++i) {
    // The tile [x0, x1) x [y0, y1), drawn as the window [wx0, wx1) x [wy0, wy1) around it.
    const int x0 = (i % t.columns) * t.tile_width, y0 = (i / t.columns) * t.tile_height;
    const int x1 = std::min(x0 + t.tile_width, w), y1 = std::min(y0 + t.tile_height, h);
    const int wx0 = std::max(x0 - kTileMarginPx, 0), wy0 = std::max(y0 - kTileMarginPx, 0);
    Scene tile = scene;
    tile.output.width = std::min(x1 + kTileMarginPx, w) - wx0;
    tile.output.height = std::min(y1 + kTileMarginPx, h) - wy0;
    f.window = ImageWindow{wx0, wy0, w, h};
    const auto keep = [&](Image& image, const Image& drawn) {
      place(image, drawn, x0 - wx0, y0 - wy0, x1 - x0, y1 - y0, x0, y0);
    };
    const Frame frame = render_frame(tile, true, true, /*sky_cover=*/false);
    keep(out.frame.color, frame.color);
    keep(out.frame.clouds, frame.clouds);
    if (layers) {
      keep(out.sky, f.compose_layer(tile, 1));
      keep(out.clouds, f.compose_layer(tile, 2));
      keep(out.clouds_depth_m, f.compose_layer(tile, 3));
    }
    if (i == 0) stats = frame.stats;
    else {
      stats.frame_ms += frame.stats.frame_ms;
      for (const PassTiming& pass : frame.stats.passes) {
        auto it = std::find_if(stats.passes.begin(), stats.passes.end(),
                               [&](const PassTiming& p) { return p.name == pass.name; });
        if (it == stats.passes.end()) stats.passes.push_back(pass);
        else it->ms += pass.ms;
      }
    }
    if (progress) progress("tiles", i + 1, tiles);
  }
  f.window.reset();
  stats.width = w;
  stats.height = h;
  double sum = 0.0;
  for (const glm::vec4& p : out.frame.color.pixels) sum += luminance(p);
  stats.mean_luminance = sum / double(out.frame.color.pixels.size());
  stats.metered_luminance = metered_luminance(out.frame.color);
  stats.cloud_cover_fraction = cloud_cover_fraction(scene, out.frame.clouds);
  if (scene.clouds.model == CloudModel::Nephele) {  // the sky dome, once: the same for every tile
    double ms = 0.0;
    stats.sky_cover_fraction = f.measure_sky_cover(scene, ms);
    stats.passes.push_back({"sky_dome", ms});
  }
  stats.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  out.frame.stats = std::move(stats);
  return out;
}

FilmLayers Renderer::render_layers(const Scene& scene) {
  validate_scene(scene);
  const Tiling t = tiling(scene);
  if (t.columns * t.rows > 1) return render_tiles(scene, t, true);
  FilmLayers layers;
  layers.frame = render(scene);
  FrameRenderer::Impl& f = *impl_->frames.impl_;
  layers.sky = f.compose_layer(scene, 1);
  layers.clouds = f.compose_layer(scene, 2);
  layers.clouds_depth_m = f.compose_layer(scene, 3);
  return layers;
}

Frame Renderer::render_next(const Scene& scene, bool read_back) {
  validate_scene(scene);
  const Tiling t = tiling(scene);
  if (t.columns * t.rows > 1)
    throw InputError("output.width x output.height = " + std::to_string(scene.output.width) +
                     " x " + std::to_string(scene.output.height) +
                     ": an animation frame must fit one frame on " + device_name() + " (at most " +
                     std::to_string(impl_->max_tile_pixels) +
                     " pixels); stills (render()) this large render in tiles");
  return render_frame(scene, false, read_back);
}

Frame Renderer::render_frame(const Scene& scene, bool still, bool read_back, bool sky_cover) {
  const auto start = std::chrono::steady_clock::now();
  FrameRenderer::Impl& f = *impl_->frames.impl_;
  FrameImages images;
  f.ctx.submit_and_wait([&](VkCommandBuffer cmd) { 
    images = f.record_frame(cmd, scene, FrameOptions{still, false});
  });
  f.collect(images.slot);
  Frame frame;
  if (read_back) frame = f.download_last(scene);
  const FrameStats measured = frame.stats;
  frame.stats = *f.completed;
  if (read_back) {
    frame.stats.mean_luminance = measured.mean_luminance;
    frame.stats.cloud_cover_fraction = measured.cloud_cover_fraction;
  }
  if (sky_cover && still && read_back && scene.clouds.model == CloudModel::Nephele) {
    double ms = 0.0;
    frame.stats.sky_cover_fraction = f.measure_sky_cover(scene, ms);
    frame.stats.passes.push_back({"sky_dome", ms});
  }
  frame.stats.wall_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  return frame;
}

CloudQuery Renderer::cloud_query(const Scene& scene) { return impl_->frames.cloud_query(scene); }

CloudProfile Renderer::cloud_profile(const Scene& scene) {
  return impl_->frames.impl_->cloud_profile(scene);
}

ReferenceImage Renderer::render_reference(const Scene& scene, const ReferenceOptions& options) {
  return impl_->frames.impl_->render_reference(scene, options);
}

int sky_cover_oktas(double fraction) {
  if (fraction < 0.01) return 0;
  if (fraction > 0.99) return 8;
  return std::clamp(int(std::lround(fraction * 8.0)), 1, 7);
}

}  // namespace nephele

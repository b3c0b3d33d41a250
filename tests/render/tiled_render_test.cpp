// Issue 40, case 12: a still larger than the device holds renders in tiles, the same image as
// one frame would be. The tests force tiling at a small size by lowering the tile limit
// (RendererOptions::max_tile_pixels) and compare against the shared renderer's single frame.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

namespace {

using nephele::Image;
using nephele::Scene;

// A renderer whose frames hold at most 4096 pixels (the least allowed): 96 x 64 draws as 3 x 2
// tiles of 32 x 32, each drawn with 16 pixels more around it (within the image).
nephele::Renderer& tiled_renderer() {
  static std::unique_ptr<nephele::Renderer> renderer = [] {
    nephele::RendererOptions options = validated();
    options.max_tile_pixels = 4096;
    return std::make_unique<nephele::Renderer>(options);
  }();
  return *renderer;
}

class TiledRender : public RenderTest {
 protected:
  void TearDown() override {
    RenderTest::TearDown();
    EXPECT_EQ(tiled_renderer().validation_messages(), 0) << "Vulkan validation messages";
  }
};

// Without the light volume (seconds to build on lavapipe, once per renderer and scene; the
// clouds then march their light): what the tiles must agree on is the view's rays.
Scene small(const std::string& preset) {
  Scene s = nephele::load_preset(preset);
  s.output.width = 96;
  s.output.height = 64;
  s.quality.light_volume_km = 0;
  return s;
}

struct Difference {
  double mean_relative = 0.0;  // of the luminance, over the image
  double worst_relative = 0.0;
};

Difference compare(const Image& a, const Image& b) {
  EXPECT_EQ(a.width, b.width);
  EXPECT_EQ(a.height, b.height);
  Difference d;
  double sum_diff = 0.0, sum = 0.0;
  for (size_t i = 0; i < a.pixels.size() && i < b.pixels.size(); ++i) {
    const double la = nephele::luminance(a.pixels[i]), lb = nephele::luminance(b.pixels[i]);
    EXPECT_TRUE(std::isfinite(lb));
    sum_diff += std::abs(la - lb);
    sum += std::abs(la);
    d.worst_relative = std::max(d.worst_relative, std::abs(la - lb) / std::max(std::abs(la), 1e-3));
  }
  d.mean_relative = sum_diff / std::max(sum, 1e-30);
  return d;
}

}  // namespace

TEST_F(TiledRender, TheLimitSplitsTheImageIntoAGridOfTiles) {
  const auto t = tiled_renderer().tiling(small("default"));
  EXPECT_EQ(t.columns, 3);
  EXPECT_EQ(t.rows, 2);
  EXPECT_EQ(t.tile_width, 32);
  EXPECT_EQ(t.tile_height, 32);
  // The advertised largest still on this device, in strips within the default limit.
  Scene huge = small("default");
  huge.output.width = huge.output.height = 16384;
  const auto h = shared_renderer().tiling(huge);
  EXPECT_GT(h.columns * h.rows, 1);
  EXPECT_LE(int64_t(h.tile_width) * h.tile_height, nephele::kDefaultMaxTilePixels);
  EXPECT_GE(h.columns * h.tile_width, 16384);
  EXPECT_GE(h.rows * h.tile_height, 16384);
  // What fits is one frame.
  const auto one = shared_renderer().tiling(small("default"));
  EXPECT_EQ(one.columns * one.rows, 1);
}

// The mountains at sunset under broken cumulus with volumetric light shafts, and a voxel
// cloud: the tiles' rays and jitter are the whole image's, and the shafts (drawn at an eighth
// of the resolution) see their neighbours through the tiles' margins. What differs is the
// float rounding of the rays at a few edge pixels.
TEST_F(TiledRender, TilesGiveTheImageOfOneFrame) {
  for (const std::string& preset : {"mountains", "voxel-cumulus"}) {
    Scene scene = small(preset);
    const nephele::Frame whole = render(scene);
    const nephele::Frame tiled = tiled_renderer().render(scene);
    const Difference colour = compare(whole.color, tiled.color);
    EXPECT_LT(colour.mean_relative, 2e-3) << preset;
    EXPECT_LT(colour.worst_relative, 0.05) << preset;
    EXPECT_LT(compare(whole.clouds, tiled.clouds).mean_relative, 2e-3) << preset;
    EXPECT_EQ(tiled.stats.width, 96);
    EXPECT_EQ(tiled.stats.height, 64);
    EXPECT_NEAR(tiled.stats.mean_luminance, whole.stats.mean_luminance,
                2e-3 * whole.stats.mean_luminance)
        << preset;
    EXPECT_NEAR(tiled.stats.cloud_cover_fraction, whole.stats.cloud_cover_fraction, 0.02) << preset;
    ASSERT_TRUE(tiled.stats.sky_cover_fraction && whole.stats.sky_cover_fraction);
    EXPECT_NEAR(*tiled.stats.sky_cover_fraction, *whole.stats.sky_cover_fraction, 0.01) << preset;
  }
}

TEST_F(TiledRender, FilmLayersTileToo) {
  const Scene scene = small("sunset");
  const nephele::FilmLayers whole = shared_renderer().render_layers(scene);
  const nephele::FilmLayers tiled = tiled_renderer().render_layers(scene);
  EXPECT_LT(compare(whole.sky, tiled.sky).mean_relative, 2e-3);
  EXPECT_LT(compare(whole.clouds, tiled.clouds).mean_relative, 2e-3);
  EXPECT_LT(compare(whole.clouds_depth_m, tiled.clouds_depth_m).mean_relative, 2e-3);
}

// What tiles cannot draw is refused in one line before any work; an animation frame must fit
// one frame; the limit itself is checked.
TEST_F(TiledRender, WhatTilesCannotDrawIsRefused) {
  Scene bloom = small("default");
  bloom.output.bloom_strength = 0.1f;
  try {
    tiled_renderer().render(bloom);
    ADD_FAILURE() << "bloom rendered in tiles";
  } catch (const nephele::InputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("96 x 64"), std::string::npos) << m;
    EXPECT_NE(m.find("bloom (output.bloom_strength > 0)"), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
  Scene shafts = small("default");
  shafts.quality.light_shafts = "screen";
  EXPECT_THROW(tiled_renderer().render(shafts), nephele::InputError);
  EXPECT_THROW(tiled_renderer().render_next(small("default")), nephele::InputError);
  nephele::RendererOptions tiny = validated();
  tiny.max_tile_pixels = 4095;
  EXPECT_THROW(nephele::Renderer{tiny}, nephele::InputError);
}

// The passes compiled for a frame's features (RendererOptions::feature_variants: compose,
// the march, the light volume) draw exactly what their full shaders draw, scene by scene: each
// variant leaves out only code whose feature the frame does not use.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

namespace {

using nephele::Scene;

nephele::Renderer& full_shaders_renderer() {
  static nephele::Renderer renderer([] {
    nephele::RendererOptions options = validated();
    options.feature_variants = false;
    return options;
  }());
  return renderer;
}

Scene small(const std::string& preset) {
  Scene s = nephele::load_preset(preset);
  s.output.width = 48;
  s.output.height = 32;
  return s;
}

class FeatureVariantsTest : public RenderTest {};

TEST_F(FeatureVariantsTest, EachSceneDrawsWhatTheFullShadersDraw) {
  Scene voxels = small("voxel-cumulus");  // voxel clouds, lit by the two-stream light
  voxels.clouds.lighting = "two-stream";
  Scene artist = small("mountains");  // terrain and shafts, under the keyframes' sky and fog
  artist.conditions.mode = nephele::ConditionsMode::Artist;
  artist.conditions.hour = 18.5f;
  artist.cirrus.coverage = 0.4f;
  artist.clouds.flow_speed_mps = 20.0f;
  // Between them the scenes switch each feature on and off: voxel clouds, either cloud light,
  // keyframes, shafts, terrain, cirrus, the flow map and particles.
  const std::pair<std::string, Scene> scenes[] = {{"default", small("default")},
                                                  {"voxel-cumulus, two-stream", voxels},
                                                  {"mountains, artist, cirrus, flow", artist},
                                                  {"particle-cumulus", small("particle-cumulus")}};
  const int messages_before = full_shaders_renderer().validation_messages();
  for (const auto& [name, scene] : scenes) {
    const nephele::Image variant = render(scene).color;
    const nephele::Image full = full_shaders_renderer().render(scene).color;
    ASSERT_EQ(variant.pixels.size(), full.pixels.size());
    // The same arithmetic, which the compiler may order differently around the code it left
    // out: a float's rounding (1.2e-7 measured), where a feature left out wrongly changes a
    // pixel by percents.
    double worst = 0.0;
    for (size_t i = 0; i < full.pixels.size(); ++i)
      for (int c = 0; c < 4; ++c)
        worst = std::max(worst, std::abs(double(variant.pixels[i][c]) - full.pixels[i][c]) /
                                    std::max(std::abs(double(full.pixels[i][c])), 1e-3));
    EXPECT_LT(worst, 1e-5) << name << ": the largest relative difference from the full shaders";
  }
  EXPECT_EQ(full_shaders_renderer().validation_messages(), messages_before);
}

}  // namespace

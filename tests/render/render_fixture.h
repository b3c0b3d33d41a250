// A renderer shared by the device tests of one process, with the validation layer on: a test
// fails on any validation message.
#pragma once

#include <gtest/gtest.h>

#include <memory>

#include "nephele/exposure.h"
#include "nephele/image.h"
#include "nephele/renderer.h"

// The options of every device test's renderer: the validation layer on.
inline nephele::RendererOptions validated() {
  nephele::RendererOptions options;
  options.validation = true;
  return options;
}

inline nephele::Renderer& shared_renderer() {
  static std::unique_ptr<nephele::Renderer> shared = std::make_unique<nephele::Renderer>(validated());
  return *shared;
}

inline nephele::Frame render(const nephele::Scene& scene) {
  return shared_renderer().render(scene);
}

// A clear, long winter night over Paris (2026-12-21 22:00 UTC) looking north, 31 degrees up,
// with the time-of-day keyframes' overlay at their night key, whose star_visibility scales the
// stars (conditions.good.keys[0]).
inline nephele::Scene starry_night(int width, int height) {
  nephele::Scene s;
  s.clouds.coverage = 0.0f;
  s.output.width = width;
  s.output.height = height;
  s.time = "2026-12-21T22:00:00Z";
  s.sun.from_time = true;
  s.location = {48.85f, 2.35f, 0.0f};
  s.camera.view_dir = {0.0f, 1.0f, 0.6f};
  s.conditions.mode = nephele::ConditionsMode::Overlay;
  s.conditions.hour = 0.0f;  // the night key exactly
  return s;
}

// The sum over the pixels of a's luminance less b's (cd/m^2).
inline double luminance_excess(const nephele::Image& a, const nephele::Image& b) {
  double excess = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    excess += nephele::luminance(a.pixels[i]) - nephele::luminance(b.pixels[i]);
  return excess;
}

class RenderTest : public ::testing::Test {
 protected:
  void SetUp() override { messages_before_ = shared_renderer().validation_messages(); }
  void TearDown() override {
    EXPECT_EQ(shared_renderer().validation_messages(), messages_before_)
        << "Vulkan validation messages (printed above)";
  }

 private:
  int messages_before_ = 0;
};

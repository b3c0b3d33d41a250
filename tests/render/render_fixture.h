// A renderer shared by the device tests of one process, with the validation layer on: a test
// fails on any validation message.
#pragma once

#include <gtest/gtest.h>

#include <memory>

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

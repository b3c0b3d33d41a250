// The renderer's own set-up passes the validation layer: its one descriptor-set layout stays
// within the device's per-stage limits (lavapipe: 32 samplers, 32 storage images a stage). The
// device tests' shared renderer counts messages from after its construction, so a message made
// while it is built (the pipeline layout's) is checked here.
#include <gtest/gtest.h>

#include "nephele/renderer.h"

TEST(RendererValidation, BuildingTheRendererMakesNoValidationMessage) {
  nephele::RendererOptions options;
  options.validation = true;
  nephele::Renderer renderer(options);
  EXPECT_EQ(renderer.validation_messages(), 0) << "Vulkan validation messages (printed above)";
}

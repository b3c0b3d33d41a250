#include "render/modules/compose.h"

namespace nephele {

void ComposeModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("reference_sky");  // made before the frame, when the scene asks for it
  graph.output("color");
  const SkyModel sky = frame.scene.atmosphere.model;
  graph.add_pass("compose",
                 {"atmosphere", "sky_view", "cloud_layer", "ground_light", "shafts",
                  "particle_layer", "terrain", "reference_sky"},
                 {"color"}, [this, sky](VkCommandBuffer cmd) { pass_compose(cmd, state_, sky); });
  graph.add_pass("stars", {"color", "cloud_layer", "particle_layer", "terrain", "atmosphere"},
                 {"color"}, [this](VkCommandBuffer cmd) { pass_stars(cmd, state_); });
}

void DisplayModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.output("meter");
  graph.output("display");
  graph.add_pass("meter", {"color"}, {"meter"},
                 [this](VkCommandBuffer cmd) { pass_meter(cmd, state_); });
  if (frame.plan.display)
    graph.add_pass("tonemap", {"color"}, {"display"},
                   [this](VkCommandBuffer cmd) { pass_tonemap(cmd, state_); });
}

}  // namespace nephele

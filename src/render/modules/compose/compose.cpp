#include "render/modules/compose/compose.h"

namespace nephele {

void ComposeModule::add_passes(FrameGraph& graph, const FrameSetup& frame) {
  graph.import("reference_sky");  // made before the frame, when the scene asks for it
  graph.output("color");
  const std::vector<int32_t> variant = compose_variant(frame.params, frame.scene.atmosphere.model,
                                                       frame.plan.layers, frame.plan.media);
  graph.add_pass("compose",
                 {"atmosphere", "sky_view", "cloud_layer", "ground_light", "shafts", "layers",
                  "terrain", "reference_sky", "media", FrameGraph::kView},
                 {"color"}, [this, variant, layer = frame.plan.film_layer](VkCommandBuffer cmd) {
                   pass_compose(cmd, state_, variant, layer);
                 });
  graph.add_pass(
      "stars",
      {"color", "cloud_layer", "layers", "terrain", "atmosphere", "media", FrameGraph::kView},
      {"color"}, [this, layer = frame.plan.film_layer](VkCommandBuffer cmd) {
        pass_stars(cmd, state_, layer);
      });
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

// The frame's graph as its modules declare it (render/render_module.h), on a device with the
// validation layer on: several views of one eye point (display channels) share the passes that
// only the camera's position decides (the weather, the sky view, the light volume, the ground's
// light), and each view records those that draw its pixels (FrameGraph::per_view).
#include <gtest/gtest.h>

#include <map>
#include <sstream>
#include <string>

#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render_fixture.h"

namespace {

// The passes of the first frame's graph as a verbose renderer prints it ("nephele: frame
// graph", then a line a pass, " [view]" after a per-view one), each with whether it is per view.
std::map<std::string, bool> printed_graph(const std::string& log) {
  std::map<std::string, bool> passes;
  std::istringstream lines(log.substr(log.find("nephele: frame graph\n") + 21));
  std::string line;
  while (std::getline(lines, line) && line.rfind("nephele:", 0) != 0) {
    if (line.rfind("  barrier", 0) == 0) continue;
    passes[line.substr(0, line.find(':'))] =
        line.size() > 7 && line.substr(line.size() - 7) == " [view]";
  }
  return passes;
}

TEST(FrameGraphRender, ViewsShareWhatOnlyTheEyePointDecides) {
  nephele::RendererOptions options = validated();
  options.verbose = true;
  nephele::Scene scene = nephele::load_preset("default");
  scene.output.width = 64;
  scene.output.height = 48;
  testing::internal::CaptureStderr();
  int messages = 0;
  {
    nephele::Renderer renderer(options);
    renderer.render(scene);
    messages = renderer.validation_messages();
  }
  const std::string log = testing::internal::GetCapturedStderr();
  EXPECT_EQ(messages, 0) << "Vulkan validation messages";
  ASSERT_NE(log.find("nephele: frame graph\n"), std::string::npos) << log;
  const std::map<std::string, bool> passes = printed_graph(log);
  for (const char* shared : {"weather", "sky_view", "light_volume", "ground_light"}) {
    ASSERT_TRUE(passes.count(shared)) << shared << " not in the graph:\n" << log;
    EXPECT_FALSE(passes.at(shared)) << shared;
  }
  for (const char* view : {"march", "clouds", "compose", "stars", "meter"}) {
    ASSERT_TRUE(passes.count(view)) << view << " not in the graph:\n" << log;
    EXPECT_TRUE(passes.at(view)) << view;
  }
}

}  // namespace

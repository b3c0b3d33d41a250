// A host of the installed nephele: a preset rendered small on the Vulkan device (the shaders
// and presets come embedded in the library), its pixels checked to be finite and lit.
#include <cmath>
#include <cstdio>

#include "nephele/renderer.h"
#include "nephele/scene_io.h"

int main() {
  nephele::Scene scene = nephele::load_preset("default");
  scene.output.width = 16;
  scene.output.height = 10;
  nephele::Renderer renderer;
  const nephele::Frame frame = renderer.render(scene);
  double sum = 0.0;
  for (const auto& p : frame.color.pixels) {
    if (!std::isfinite(p.r) || !std::isfinite(p.g) || !std::isfinite(p.b)) return 1;
    sum += p.g;
  }
  std::printf("rendered %dx%d on %s, mean green %.1f\n", frame.color.width, frame.color.height,
              renderer.device_name().c_str(), sum / double(frame.color.pixels.size()));
  return sum > 0.0 ? 0 : 1;
}

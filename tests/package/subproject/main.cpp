// The host program of the subproject test: a scene from a preset, validated.
#include "nephele/scene_io.h"

int main() {
  nephele::Scene scene = nephele::load_preset("mountains");
  nephele::validate_scene(scene);
  return scene.terrain.preset == "mountains" ? 0 : 1;
}

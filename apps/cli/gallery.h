// `nephele gallery`: the sky-cover presets rendered side by side in one labelled image.
#pragma once

#include <string>
#include <vector>

#include "nephele/scene.h"

namespace CLI {
class App;
}

namespace nephele::cli {

// The presets of the gallery, in its order: the okta presets from clear to overcast, then the
// named skies.
const std::vector<std::string>& gallery_presets();
// The scenes the gallery shows after those: the particle-cloud presets (their labels say
// impostors: the sky cover is measured on the volumetric clouds) and the mountains at sunset.
const std::vector<std::string>& gallery_scene_presets();

// The okta range [lo, hi] a gallery preset stands for (sky_cover_oktas): clear 0, few 1-2,
// scattered 3-4, broken 5-7, overcast 8; the named skies have their own.
struct OktaRange {
  int lo = 0, hi = 8;
};
OktaRange gallery_okta_range(const std::string& preset);

// The classical models' gallery (`--classic`, seed 004): each model on the default scene (the
// same camera, sun and cloud layer), nephele's own last: its tiles' names and scenes.
struct ClassicTile {
  std::string name;  // a model, or a model and its variant ("gardner-stratus")
  Scene scene;
};
std::vector<ClassicTile> classic_gallery_tiles(int tile_width, int tile_height);

struct GalleryOptions {
  std::string output = "gallery.png";
  bool classic = false;  // the classical models instead of the presets
  std::string json;      // --classic: {"models": {name: frame_ms}} here
  bool exr_float = false;  // EXR as 32-bit floats
  int tile_width = 400, tile_height = 250, columns = 3;
  std::vector<std::string> presets;  // the tiles, in order; empty: the sky-cover presets, then
                                     // the particle ones
  std::string device;
  bool verbose = false;
  bool validation = false;
  bool progress = false;  // progress on standard error even when it is not a terminal
  bool quiet = false;     // no progress
};

void add_gallery_flags(CLI::App& cmd, GalleryOptions& options);
int run_gallery(const GalleryOptions& options);

}  // namespace nephele::cli

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
  std::string metar;  // a file of METAR or SPECI reports, one a line: a tile each instead
  std::string device;
  bool verbose = false;
  bool validation = false;
  bool progress = false;  // progress on standard error even when it is not a terminal
  bool quiet = false;     // no progress
};

// The reports of a --metar file: one a line, blank lines and lines from '#' skipped, a final
// '=' dropped. Throws InputError naming the file and line for one that cannot be read.
struct MetarTile {
  int line = 0;
  std::string report;
  Scene scene;                       // the default scene under the report
  int oktas_min = 0, oktas_max = 0;  // the sky cover it reports
};
std::vector<MetarTile> metar_gallery_tiles(const std::string& path, int tile_width,
                                           int tile_height);

void add_gallery_flags(CLI::App& cmd, GalleryOptions& options);
int run_gallery(const GalleryOptions& options);

}  // namespace nephele::cli

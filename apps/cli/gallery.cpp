#include "gallery.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "label.h"
#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele/image.h"
#include "nephele/output_file.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "progress.h"
#include "render_command.h"
#include "sample_stats.h"
#include "weather/metar_weather.h"

namespace nephele::cli {

namespace {

struct GalleryEntry {
  const char* preset;
  OktaRange oktas;
};

const std::vector<GalleryEntry>& entries() {
  static const std::vector<GalleryEntry> table = {
      {"clear", {0, 0}},     {"few", {1, 2}},     {"scattered", {3, 4}},
      {"broken", {5, 7}},    {"overcast", {8, 8}}, {"stratus", {7, 8}},
      {"cumulonimbus-storm", {4, 8}}, {"cirrus", {1, 6}}, {"sunset-cumulus", {3, 4}},
      {"voxel-cumulus", {1, 3}},      {"voxel-above", {0, 0}}};
  return table;
}

// The median GPU time of an animation frame of `scene` (after the still that starts its
// history): what a real-time host would pay each frame.
double animation_frame_ms(Renderer& renderer, const Scene& scene) {
  std::vector<double> ms;
  for (int f = 1; f <= 3; ++f) {
    Scene next = scene;
    next.time_s += float(f) / 30.0f;
    ms.push_back(renderer.render_next(next, false).stats.frame_ms);
  }
  return median(ms);
}

}  // namespace

std::vector<ClassicTile> classic_gallery_tiles(int tile_width, int tile_height) {
  Scene base = load_preset("default");
  base.output.width = tile_width;
  base.output.height = tile_height;
  std::vector<ClassicTile> tiles;
  const auto add = [&](const std::string& name, CloudModel model, const std::string& gardner) {
    Scene s = base;
    s.clouds.model = model;
    s.classic.gardner_clouds = gardner;
    tiles.push_back({name, s});
  };
  add("blinn", CloudModel::Blinn, "cumulus");
  add("gardner", CloudModel::Gardner, "cumulus");
  add("gardner-stratus", CloudModel::Gardner, "stratus");
  add("gardner-cirrus", CloudModel::Gardner, "cirrus");
  add("gardner-quadrics", CloudModel::GardnerQuadrics, "cumulus");
  add("kajiya", CloudModel::Kajiya, "cumulus");
  add("nishita", CloudModel::Nishita, "cumulus");
  add("nephele", CloudModel::Nephele, "cumulus");
  return tiles;
}

const std::vector<std::string>& gallery_presets() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const GalleryEntry& e : entries()) out.push_back(e.preset);
    return out;
  }();
  return names;
}

const std::vector<std::string>& gallery_scene_presets() {
  static const std::vector<std::string> names = {"particle-cumulus", "particle-cockpit", "mountains"};
  return names;
}

OktaRange gallery_okta_range(const std::string& preset) {
  for (const GalleryEntry& e : entries())
    if (preset == e.preset) return e.oktas;
  throw InputError("'" + preset + "' is not a gallery preset");
}

void add_gallery_flags(CLI::App& cmd, GalleryOptions& options) {
  cmd.add_option("-o,--output", options.output, "image to write: .png or .exr")
      ->capture_default_str();
  cmd.add_flag("--exr-float", options.exr_float,
               "write EXR as 32-bit floats; the default half floats clamp at 65504");
  cmd.add_option("--tile-width", options.tile_width, "width of each preset's tile (pixels), [16, 4096]")
      ->capture_default_str();
  cmd.add_option("--tile-height", options.tile_height, "height of each tile (pixels), [16, 4096]")
      ->capture_default_str();
  cmd.add_option("--columns", options.columns, "tiles per row, [1, 16]")->capture_default_str();
  cmd.add_option("--presets", options.presets,
                 "the presets to show, in this order, separated by commas (default: the "
                 "sky-cover presets, clear to overcast, stratus, storm, cirrus, sunset, then the "
                 "particle clouds'); not with --classic")
      ->delimiter(',');
  cmd.add_option("--metar", options.metar,
                 "a file of METAR or SPECI reports, one a line ('#' comments): a tile for each, "
                 "the default scene under the report, labelled with the report, the oktas measured "
                 "and the oktas it reports; not with --classic or --presets");
  cmd.add_flag("--classic", options.classic,
               "the classical cloud models of seed 004 (blinn, gardner cumulus, stratus and cirrus, gardner-quadrics, kajiya, nishita) "
               "and nephele's own on one scene, each labelled with its frame time on this device");
  cmd.add_option("--json", options.json,
                 "with --classic: write {\"models\": {name: frame_ms}} (the median GPU time of "
                 "an animation frame) to this file, or to standard output with -");
  add_device_flags(cmd, options.device, options.verbose, options.validation);
  add_progress_flags(cmd, options.progress, options.quiet);
}

std::vector<MetarTile> metar_gallery_tiles(const std::string& path, int tile_width,
                                           int tile_height) {
  std::ifstream in(path);
  if (!in) throw InputError("--metar " + shorten_path_for_message(path) + ": cannot be read");
  std::vector<MetarTile> tiles;
  std::string line;
  for (int number = 1; std::getline(in, line); ++number) {
    const size_t first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos || line[first] == '#') continue;
    std::string report = line.substr(first, line.find_last_not_of(" \t\r=") + 1 - first);
    MetarTile tile{number, report, load_preset("default")};
    tile.scene.output.width = tile_width;
    tile.scene.output.height = tile_height;
    tile.scene.weather.metar = report;
    try {
      const weather::MetarReport parsed = weather::parse_metar(report);
      const weather::ReportWeather drawn =
          weather::weather_from_metar(parsed, weather::weather_state(tile.scene));
      tile.oktas_min = drawn.oktas_min;
      tile.oktas_max = drawn.oktas_max;
      weather::apply_metar(tile.scene);
      validate_scene(tile.scene);
    } catch (const InputError& e) {
      std::string what = e.what();
      if (what.starts_with("weather.metar: ")) what = what.substr(15);
      throw InputError("--metar " + shorten_path_for_message(path) + " line " +
                       std::to_string(number) + ": " + what);
    }
    tiles.push_back(std::move(tile));
    if (tiles.size() > 256)
      throw InputError("--metar " + shorten_path_for_message(path) + ": more than 256 reports");
  }
  if (tiles.empty())
    throw InputError("--metar " + shorten_path_for_message(path) + ": holds no report");
  return tiles;
}

int run_gallery(const GalleryOptions& options) {
  const auto check = [](const char* flag, int value, int lo, int hi) {
    if (value < lo || value > hi)
      throw InputError(std::string(flag) + " " + std::to_string(value) + ": must be in [" +
                       std::to_string(lo) + ", " + std::to_string(hi) + "]");
  };
  check("--tile-width", options.tile_width, 16, 4096);
  check("--tile-height", options.tile_height, 16, 4096);
  check("--columns", options.columns, 1, 16);
  check_output_path(options.output, "--output");
  if (!options.json.empty() && !options.classic)
    throw InputError("--json " + options.json + ": only with --classic (the models' frame times)");
  if (options.classic && !options.presets.empty())
    throw InputError("--presets: not with --classic (its tiles are the classical models)");
  if (!options.metar.empty() && (options.classic || !options.presets.empty()))
    throw InputError("--metar " + options.metar + ": not with " +
                     (options.classic ? "--classic" : "--presets") +
                     " (its tiles are the reports)");
  if (!options.json.empty()) {
    check_output_file(options.json, "--json", true);
    check_distinct_outputs({{"--output", options.output}, {"--json", options.json}});
  }

  std::vector<std::string> names;
  std::vector<Scene> scenes;  // all checked before the first is rendered
  std::vector<MetarTile> reports;
  if (!options.metar.empty()) {
    reports = metar_gallery_tiles(options.metar, options.tile_width, options.tile_height);
    for (const MetarTile& tile : reports) {
      names.push_back(tile.report);
      scenes.push_back(tile.scene);
    }
  } else if (options.classic) {
    for (ClassicTile& tile : classic_gallery_tiles(options.tile_width, options.tile_height)) {
      names.push_back(tile.name);
      scenes.push_back(std::move(tile.scene));
    }
  } else {
    names = options.presets;
    if (names.empty()) {
      names = gallery_presets();
      for (const std::string& name : gallery_scene_presets()) names.push_back(name);
    }
    for (const std::string& name : names) {
      try {
        scenes.push_back(load_preset(name));
      } catch (const InputError& e) {
        throw InputError(std::string("--presets: ") + e.what());
      }
      scenes.back().output.width = options.tile_width;
      scenes.back().output.height = options.tile_height;
    }
  }
  for (const Scene& scene : scenes) validate_scene(scene);
  const int columns = std::min(options.columns, int(names.size()));
  const int rows = (int(names.size()) + columns - 1) / columns;
  const int gap = 4;
  Image gallery(columns * options.tile_width + (columns - 1) * gap,
                rows * options.tile_height + (rows - 1) * gap);
  for (glm::vec4& p : gallery.pixels) p = glm::vec4(0.0f, 0.0f, 0.0f, 1.0f);
  const int scale = options.tile_height >= 200 ? 2 : 1;

  Renderer renderer({options.device, options.validation, options.verbose, {}});
  // A step a preset (--verbose prints a line a preset instead, unless --progress).
  Progress progress("gallery", int(names.size()),
                    progress_wanted(options.progress, options.quiet, options.verbose));
  // One exposure for every tile, the first's (auto exposure would brighten an overcast to the
  // clear sky's grey), so that the covers compare as the eye would see them side by side.
  std::optional<float> exposure;
  nlohmann::json models = nlohmann::json::object();
  for (size_t i = 0; i < names.size(); ++i) {
    const Scene& scene = scenes[i];
    const Frame frame = renderer.render(scene);
    if (!exposure) exposure = still_exposure(scene.output, frame.color);
    const int x0 = int(i % columns) * (options.tile_width + gap);
    const int y0 = int(i / columns) * (options.tile_height + gap);
    for (int y = 0; y < options.tile_height; ++y)
      for (int x = 0; x < options.tile_width; ++x)
        gallery.at(x0 + x, y0 + y) = glm::vec4(glm::vec3(frame.color.at(x, y)) * *exposure, 1.0f);
    const double cover = frame.stats.sky_cover_fraction.value_or(0.0);
    char label[160];
    if (options.classic) {
      const double ms = animation_frame_ms(renderer, scene);
      models[names[i]] = ms;
      std::snprintf(label, sizeof label, "%s  %.1f ms", names[i].c_str(), ms);
    } else if (!reports.empty()) {  // the report on one line, the oktas on the next
      std::snprintf(label, sizeof label, "measured %d/8 (%.2f), reported %d-%d",
                    sky_cover_oktas(cover), cover, reports[i].oktas_min, reports[i].oktas_max);
      std::string report = names[i];
      while (report.size() > 4 && label_width(report, scale) > options.tile_width)
        report = report.substr(0, report.size() - 4) + "...";
      draw_label(gallery, x0, y0, report, scale);
      draw_label(gallery, x0, y0 + 12 * scale, label, scale);
      progress.clear();
      if (options.verbose)
        std::fprintf(stderr, "nephele: gallery %s: %s\n", names[i].c_str(), label);
      progress.advance();
      continue;
    } else if (const auto& p =
                   frame.stats.particle_clouds)  // the sky cover counts volumetric clouds
      std::snprintf(label, sizeof label, "%s  %d impostors", names[i].c_str(), p->impostors);
    else
      std::snprintf(label, sizeof label, "%s  %d/8 (%.2f)", names[i].c_str(),
                    sky_cover_oktas(cover), cover);
    draw_label(gallery, x0, y0, label, scale);
    progress.clear();
    if (options.verbose) std::fprintf(stderr, "nephele: gallery %s\n", label);
    progress.advance();
  }
  progress.finish();
  if (options.validation && renderer.validation_messages() > 0) {
    std::fprintf(stderr, "nephele: %d Vulkan validation messages\n", renderer.validation_messages());
    return 1;
  }
  write_image(gallery, options.output, 1.0f,
              options.exr_float ? ExrPixels::kFloat : ExrPixels::kHalf);
  std::cout << options.output << "\n";
  if (!options.json.empty()) {
    const nlohmann::json out = {{"device", renderer.device_name()},
                                {"width", options.tile_width},
                                {"height", options.tile_height},
                                {"models", models}};
    write_text_output(options.json, out.dump(2) + "\n");
    if (options.json != "-") std::cout << options.json << "\n";
  }
  return 0;
}

}  // namespace nephele::cli

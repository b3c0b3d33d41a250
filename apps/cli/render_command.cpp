#include "render_command.h"

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>

#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/output_file.h"
#include "nephele/scene_io.h"

namespace nephele::cli {

namespace fs = std::filesystem;

void add_device_flags(CLI::App& cmd, std::string& device, bool& verbose, bool& validation) {
  cmd.add_option("--device", device, "use the Vulkan device whose name contains this text");
  cmd.add_flag("--verbose,-v", verbose, "print the resolved scene, device and pass timings");
  cmd.add_flag("--validation", validation, "enable the Khronos validation layer");
}

void add_render_flags(CLI::App& cmd, RenderOptions& options) {
  add_scene_flags(cmd, options.scene);
  cmd.add_option("--output,-o", options.output, "image to write: .png (tone-mapped) or .exr (HDR)")
      ->capture_default_str();
  cmd.add_option("--stats-json", options.stats_json,
                 "write frame statistics as JSON to this file, or to standard output with -");
  cmd.add_flag("--exr-float", options.exr_float,
               "write EXR as 32-bit floats (the sun's true radiance); the default half floats "
               "clamp at 65504");
  cmd.add_option("--frames", options.frames,
                 "render a sequence of N frames, numbered name_0000.png ... (default 1)");
  cmd.add_option("--step", options.step_s,
                 "seconds of scene time between frames of a sequence (the clock and the wind)");
  add_device_flags(cmd, options.device, options.verbose, options.validation);
}

void write_text_output(const std::string& path, const std::string& text) {
  if (path == kStandardOutput) {
    std::cout << text << std::flush;
    if (!std::cout) throw RuntimeError("cannot write to standard output");
    return;
  }
  write_file_atomically(path, text);
}

std::string stats_to_json(const FrameStats& stats, const std::string& image_path) {
  nlohmann::json j;
  j["image"] = image_path;
  j["device"] = stats.device;
  j["width"] = stats.width;
  j["height"] = stats.height;
  j["frame_ms"] = stats.frame_ms;
  j["wall_ms"] = stats.wall_ms;
  j["mean_luminance"] = stats.mean_luminance;
  j["cloud_cover_fraction"] = stats.cloud_cover_fraction;
  if (stats.sky_cover_fraction) {  // still images
    j["sky_cover_fraction"] = *stats.sky_cover_fraction;
    j["sky_cover_oktas"] = sky_cover_oktas(*stats.sky_cover_fraction);
  }
  // Topocentric, geometric (no refraction), azimuth from north through east.
  j["sun_elevation_deg"] = stats.sun.elevation_deg;
  j["sun_azimuth_deg"] = stats.sun.azimuth_deg;
  if (stats.ephemeris) {  // the moon needs a date
    j["moon_elevation_deg"] = stats.ephemeris->moon.elevation_deg;
    j["moon_azimuth_deg"] = stats.ephemeris->moon.azimuth_deg;
    j["moon_illuminated_fraction"] = stats.ephemeris->moon_illuminated_fraction;
  }
  nlohmann::json passes = nlohmann::json::object();
  for (const PassTiming& p : stats.passes) passes[p.name] = p.ms;
  j["passes_ms"] = passes;
  return j.dump(2) + "\n";
}

std::string frame_path(const std::string& path, int index, int frames) {
  if (frames <= 1) return path;
  const fs::path p(path);
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "_%04d", index);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

namespace {

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// Scene time of frame `index` of a sequence.
float frame_time_s(const Scene& scene, const RenderOptions& options, int index) {
  return scene.time_s + float(index) * options.step_s;
}

// Everything about the sequence that can be checked before the first frame: the frame count,
// the step, every frame's time (its ends bound the rest), and the outputs.
void check_sequence(const Scene& scene, const RenderOptions& options) {
  if (options.frames < 1 || options.frames > 100000)
    throw InputError("--frames " + std::to_string(options.frames) + ": must be in [1, 100000]");
  if (!std::isfinite(options.step_s))
    throw InputError("--step " + number_text(options.step_s) +
                     ": must be a finite number of seconds");
  Scene last = scene;
  last.time_s = frame_time_s(scene, options, options.frames - 1);
  try {
    validate_scene(last);
  } catch (const InputError& e) {
    throw InputError("--frames " + std::to_string(options.frames) + " --step " +
                     number_text(options.step_s) + ": the last frame's " + e.what());
  }
  // A sequence's names are the longest: check the first frame's (frame_path).
  const std::string image = frame_path(options.output, 0, options.frames);
  check_output_path(image, "--output");
  std::vector<std::pair<std::string, std::string>> outputs = {{"--output", image}};
  if (!options.stats_json.empty()) {
    const std::string stats = options.stats_json == kStandardOutput
                                  ? options.stats_json
                                  : frame_path(options.stats_json, 0, options.frames);
    check_output_file(stats, "--stats-json", true);
    outputs.emplace_back("--stats-json", stats);
  }
  check_distinct_outputs(outputs);
}

}  // namespace

int run_render(const RenderOptions& options) {
  // Everything the user typed is checked before any work, so a bad flag writes nothing.
  const Scene scene = resolve_scene(options.scene);
  check_sequence(scene, options);
  if (options.verbose) std::cerr << "# resolved scene\n" << scene_to_toml(scene);

  const bool stats_to_stdout = options.stats_json == kStandardOutput;
  const ExrPixels exr = options.exr_float ? ExrPixels::kFloat : ExrPixels::kHalf;
  Renderer renderer({options.device, options.validation, options.verbose});
  for (int i = 0; i < options.frames; ++i) {
    Scene frame_scene = scene;
    frame_scene.time_s = frame_time_s(scene, options, i);
    const Frame frame = renderer.render(frame_scene);
    const float exposure = scene.output.auto_exposure
                               ? auto_exposure(scene.output.exposure, frame.stats.mean_luminance)
                               : scene.output.exposure;
    const std::string path = frame_path(options.output, i, options.frames);
    write_image(frame.color, path, exposure, exr);
    if (!options.stats_json.empty())
      write_text_output(stats_to_stdout ? options.stats_json
                                        : frame_path(options.stats_json, i, options.frames),
                        stats_to_json(frame.stats, path));
    if (options.verbose)
      std::fprintf(stderr, "nephele: %dx%d on %s: %.1f ms GPU, %.1f ms wall, exposure %g\n",
                   frame.stats.width, frame.stats.height, frame.stats.device.c_str(),
                   frame.stats.frame_ms, frame.stats.wall_ms, exposure);
    if (options.validation && renderer.validation_messages() > 0) {
      std::fprintf(stderr, "nephele: %d Vulkan validation messages\n",
                   renderer.validation_messages());
      return 1;
    }
    if (!stats_to_stdout) std::cout << path << "\n";
  }
  return 0;
}

}  // namespace nephele::cli

#include "render_command.h"

#include <CLI/CLI.hpp>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <optional>

#include "nephele/camera_path.h"
#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele/film.h"
#include "nephele/image.h"
#include "nephele/output_file.h"
#include "nephele/scene_io.h"
#include "progress.h"
#include "weather/grib.h"
#include "weather/metar_weather.h"

namespace nephele::cli {

namespace fs = std::filesystem;

void add_device_flags(CLI::App& cmd, std::string& device, bool& verbose, bool& validation) {
  cmd.add_option("--device", device, "use the Vulkan device whose name contains this text");
  cmd.add_flag("--verbose,-v", verbose, "print the resolved scene, device and pass timings");
  cmd.add_flag("--validation", validation, "enable the Khronos validation layer");
}

void add_progress_flags(CLI::App& cmd, bool& progress, bool& quiet) {
  cmd.add_flag("--progress", progress,
               "show progress and the time left on standard error even when it is not a terminal "
               "(a line every few seconds)");
  CLI::Option* quiet_flag =
      cmd.add_flag("--quiet,-q", quiet, "no progress and no informational lines on standard error");
  if (CLI::Option* verbose = cmd.get_option_no_throw("--verbose")) quiet_flag->excludes(verbose);
}

void add_render_flags(CLI::App& cmd, RenderOptions& options) {
  add_scene_flags(cmd, options.scene);
  cmd.add_option("--output,-o", options.output,
                 "image to write: .png (tone-mapped) or .exr (HDR); a sequence's frames are "
                 "name_0000.png ..., or numbered where a %d or %0Nd in the name says "
                 "(out/f_%04d.png)")
      ->capture_default_str();
  cmd.add_option("--stats-json", options.stats_json,
                 "write frame statistics as JSON to this file, or to standard output with -; "
                 "a sequence writes a file a frame, numbered as "
                 "--output's (stats_0000.json ...)");
  cmd.add_flag("--exr-float", options.exr_float,
               "write EXR as 32-bit floats (the sun's true radiance); the default half floats "
               "clamp at 65504");
  cmd.add_flag("--layers", options.layers,
               "write a multi-layer EXR for compositing: the image (R, G, B, A), sky (what is "
               "behind the clouds), clouds (premultiplied, A = 1 - transmittance) and "
               "clouds.depth_m, with the camera, place, time and exposure in the header; each "
               "frame a still");
  cmd.add_flag("--holdout", options.holdout,
               "with --layers: the image is the sky with the clouds cut out ((1 - clouds.A) "
               "sky, A = 1 - clouds.A), for clouds composited over it");
  cmd.add_option("--frames", options.frames,
                 "render a sequence of N frames, numbered name_0000.png ... (default 1; with "
                 "--camera-path, up to the path's end)")
      ->each([&options](const std::string&) { options.frames_given = true; });
  cmd.add_option("--step", options.step_s,
                 "seconds of scene time between frames of a sequence (the clock and the wind)")
      ->each([&options](const std::string&) { options.step_given = true; });
  cmd.add_option("--start-frame", options.start_frame,
                 "number of a sequence's first frame, [0, 10000000]; frame K is K steps (or K / "
                 "--fps seconds) into the sequence, so a flight can be rendered in parts");
  cmd.add_option("--camera-path", options.camera_path,
                 "fly the camera along this path (TOML [[key]] tables, see docs/camera.md): frame "
                 "i at path time (--start-frame + i) / --fps, the scene's clock advancing alike; "
                 "rendered as an animation (temporal reprojection)")
      ->type_name("FILE");
  cmd.add_option("--fps", options.fps, "frames per second of a --camera-path flight, (0, 1000]")
      ->each([&options](const std::string&) { options.fps_given = true; })
      ->capture_default_str();
  cmd.add_flag("--still-frames", options.still_frames,
               "render every frame of a --camera-path flight as a still image (every pixel "
               "marched, slower) instead of as an animation");
  cmd.add_flag("--reference", options.reference,
               "path trace the scene (its [lab] grid when it has one; unbiased, progressive; --seed "
               "seeds the paths); "
               "an .exr output gets the mean (R, G, B) and its variance (variance.R, .G, .B)");
  cmd.add_option("--spp", options.spp, "--reference: samples per pixel, [1, 1000000]")
      ->capture_default_str();
  cmd.add_option("--time-limit", options.time_limit_s,
                 "--reference: stop after this many seconds (at the end of a pass; 0 = none); "
                 "samples still in flight a tenth of it later are left out")
      ->capture_default_str();
  cmd.add_option("--max-bounces", options.max_bounces,
                 "--reference: scatterings after the first, [0, 1024] (0 = single scattering); -1: "
                 "the lab's max_bounces, or all that matter on the planet")
      ->capture_default_str();
  cmd.add_option("--majorant-grid", options.majorant_grid,
                 "--reference: auto (the lab: its bricks where under a quarter of them are "
                 "stored; the planet: the noise clouds' grid), bricks (the lab's bricks always) or "
                 "none (one majorant for the lab's box, for each cloud layer's shell)")
      ->capture_default_str();
  add_device_flags(cmd, options.device, options.verbose, options.validation);
  add_progress_flags(cmd, options.progress, options.quiet);
}

void write_text_output(const std::string& path, const std::string& text) {
  if (path == kStandardOutput) {
    std::cout << text << std::flush;
    if (!std::cout) throw RuntimeError("cannot write to standard output");
    return;
  }
  write_file_atomically(path, text);
}

std::string sequence_frame_path(const std::string& path, int number, const std::string& parameter) {
  const auto refuse = [&](const std::string& what) {
    throw InputError(parameter + " '" + shorten_path_for_message(path) + "': " + what);
  };
  std::string out;
  bool numbered = false;
  for (size_t i = 0; i < path.size(); ++i) {
    if (path[i] != '%') {
      out += path[i];
      continue;
    }
    if (i + 1 < path.size() && path[i + 1] == '%') {  // %% is a percent sign
      out += '%';
      ++i;
      continue;
    }
    // %d or %0Nd: a zero-padded width of at most 2 digits.
    size_t j = i + 1;
    const bool zero = j < path.size() && path[j] == '0';
    if (zero) ++j;
    int width = 0;
    size_t digits = 0;
    for (; j < path.size() && std::isdigit(static_cast<unsigned char>(path[j])) && digits < 3;
         ++j, ++digits)
      width = 10 * width + (path[j] - '0');
    const bool ok = j < path.size() && path[j] == 'd' && digits <= 2 && zero == (digits > 0) &&
                    (!zero || width > 0);
    if (!ok)
      refuse(
          "only %d or a zero-padded %0Nd (N of 1 or 2 digits) can number the frames, and %% "
          "writes a percent sign");
    if (numbered) refuse("has more than one %d: one number names a frame");
    numbered = true;
    char text[64];
    std::snprintf(text, sizeof text, "%0*d", width, number);
    out += text;
    i = j;
  }
  if (numbered) return out;
  const fs::path p(path);
  char suffix[16];
  std::snprintf(suffix, sizeof suffix, "_%04d", number);
  return (p.parent_path() / (p.stem().string() + suffix + p.extension().string())).string();
}

std::string frame_path(const std::string& path, int index, int frames) {
  if (frames <= 1) return path;
  return sequence_frame_path(path, index);
}

namespace {

constexpr int kMaxFrames = 100000;
constexpr int kMaxStartFrame = 10000000;
constexpr double kMaxFps = 1000.0;

std::string number_text(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", value);
  return text;
}

// What `render` draws: one still, or a sequence of numbered frames along the clock or a path.
struct Sequence {
  bool numbered = false;  // files named by frame number (sequence_frame_path)
  int frames = 1;
  std::optional<CameraPath> path;

  int number(const RenderOptions& options, int i) const { return options.start_frame + i; }
  std::string output(const std::string& file, const RenderOptions& options, int i,
                     const std::string& parameter) const {
    return numbered ? sequence_frame_path(file, number(options, i), parameter) : file;
  }
  // The scene of frame i: the clock `number` steps on, or 1 / fps a frame along the path.
  Scene scene(const Scene& base, const RenderOptions& options, int i) const {
    Scene s = base;
    const int n = number(options, i);
    if (path) {
      const double t_s = double(n) / options.fps;
      s.camera = path->at(t_s);
      s.time_s = float(double(base.time_s) + t_s);
    } else {
      s.time_s = base.time_s + float(n) * options.step_s;
    }
    return s;
  }
};

// The flags that shape a sequence, each checked on its own.
void check_sequence_flags(const RenderOptions& options) {
  const bool flight = !options.camera_path.empty();
  if (options.frames_given && (options.frames < 1 || options.frames > kMaxFrames))
    throw InputError("--frames " + std::to_string(options.frames) + ": must be in [1, " +
                     std::to_string(kMaxFrames) + "]");
  if (!std::isfinite(options.step_s))
    throw InputError("--step " + number_text(options.step_s) +
                     ": must be a finite number of seconds");
  if (options.start_frame < 0 || options.start_frame > kMaxStartFrame)
    throw InputError("--start-frame " + std::to_string(options.start_frame) + ": must be in [0, " +
                     std::to_string(kMaxStartFrame) + "]");
  if (!(options.fps > 0.0 && options.fps <= kMaxFps))
    throw InputError("--fps " + number_text(options.fps) + ": must be in (0, 1000]");
  if (!flight && options.fps_given)
    throw InputError("--fps " + number_text(options.fps) +
                     ": needs --camera-path (a --frames sequence moves the clock by --step)");
  if (!flight && options.still_frames)
    throw InputError("--still-frames needs --camera-path (a --frames sequence renders stills)");
  if (flight && options.step_given)
    throw InputError("--step " + number_text(options.step_s) +
                     ": cannot be combined with --camera-path (the clock advances 1 / --fps a "
                     "frame)");
}

// --layers and --holdout: an EXR of stills.
void check_layer_flags(const RenderOptions& options) {
  if (options.holdout && !options.layers)
    throw InputError("--holdout needs --layers (it shapes the multi-layer EXR's image)");
  if (!options.layers) return;
  const std::string ext = fs::path(options.output).extension().string();
  if (ext != ".exr" && ext != ".EXR" && ext != ".Exr")
    throw InputError("--layers '" + shorten_path_for_message(options.output) +
                     "': needs an .exr output (-o name.exr)");
  if (!options.camera_path.empty() && !options.still_frames)
    throw InputError("--layers renders stills: add --still-frames to a --camera-path flight");
}

// A flight without --frames runs to the path's end: frames start ... floor(end x fps).
int flight_frames(const CameraPath& path, const RenderOptions& options) {
  const double last = std::floor(path.end_s() * options.fps + 1e-9);
  const double count = last - double(options.start_frame) + 1.0;
  if (count < 1.0)
    throw InputError("--start-frame " + std::to_string(options.start_frame) + ": at --fps " +
                     number_text(options.fps) + " it is " +
                     number_text(options.start_frame / options.fps) +
                     " s into the path, after its end (" + number_text(path.end_s()) +
                     " s); give --frames to render beyond the end");
  if (count > kMaxFrames)
    throw InputError("--camera-path " + shorten_path_for_message(options.camera_path) + ": " +
                     number_text(count) + " frames at --fps " + number_text(options.fps) +
                     " (more than " + std::to_string(kMaxFrames) + "); give --frames");
  return int(count);
}

// What a render reads, named as the user gave it: no output may replace one of them.
NamedPaths render_inputs(const Scene& scene, const RenderOptions& options) {
  NamedPaths inputs = scene_input_files(scene);
  if (options.scene.scene_file) inputs.emplace_back("--scene", *options.scene.scene_file);
  if (!options.camera_path.empty()) inputs.emplace_back("--camera-path", options.camera_path);
  return inputs;
}

// Everything about the sequence that can be checked before the first frame: the flags, the
// camera path, every frame's scene and every output's name.
Sequence plan_sequence(const Scene& scene, const RenderOptions& options) {
  check_sequence_flags(options);
  check_layer_flags(options);
  Sequence seq;
  seq.frames = options.frames;
  if (!options.camera_path.empty()) {
    seq.path = load_camera_path(options.camera_path, scene);
    if (!options.frames_given) seq.frames = flight_frames(*seq.path, options);
  }
  seq.numbered = seq.frames > 1 || seq.path || options.start_frame != 0;
  if (seq.path) {
    for (int i = 0; i < seq.frames; ++i) {
      try {
        validate_scene(seq.scene(scene, options, i));
      } catch (const InputError& e) {
        throw InputError("--camera-path " + shorten_path_for_message(options.camera_path) +
                         ": frame " + std::to_string(seq.number(options, i)) + " (t = " +
                         number_text(seq.number(options, i) / options.fps) + " s): " + e.what());
      }
    }
  } else if (seq.numbered) {
    // The clock moves linearly: its ends bound the frames between.
    try {
      validate_scene(seq.scene(scene, options, seq.frames - 1));
    } catch (const InputError& e) {
      throw InputError("--frames " + std::to_string(seq.frames) + " --step " +
                       number_text(options.step_s) + ": the last frame's " + e.what());
    }
  }
  const bool stats_to_stdout = options.stats_json == kStandardOutput;
  const NamedPaths inputs = render_inputs(scene, options);
  for (int i = 0; i < seq.frames; ++i) {
    const std::string image = seq.output(options.output, options, i, "--output");
    check_output_path(image, "--output");
    std::vector<std::pair<std::string, std::string>> outputs = {{"--output", image}};
    if (!options.stats_json.empty()) {
      const std::string stats = stats_to_stdout
                                    ? options.stats_json
                                    : seq.output(options.stats_json, options, i, "--stats-json");
      check_output_file(stats, "--stats-json", true);
      outputs.emplace_back("--stats-json", stats);
    }
    if (i == 0) check_distinct_outputs(outputs);
    check_outputs_not_inputs(outputs, inputs);
  }
  return seq;
}

}  // namespace

namespace {

// `nephele render --reference`: the path-traced image (of the lab, or of the planet's scene),
// with progress.
int run_reference(const Scene& scene, const RenderOptions& options) {
  if (options.frames_given || !options.camera_path.empty())
    throw InputError("--reference renders one image (not with --frames or --camera-path)");
  if (options.spp < 1 || options.spp > 1000000)
    throw InputError("--spp " + std::to_string(options.spp) + ": must be in [1, 1000000]");
  if (!(options.time_limit_s >= 0.0 && std::isfinite(options.time_limit_s)))
    throw InputError("--time-limit " + number_text(options.time_limit_s) +
                     ": must be a finite number of seconds, at least 0 (0 = none)");
  if (options.max_bounces < -1 || options.max_bounces > kMaxReferenceBounces)
    throw InputError("--max-bounces " + std::to_string(options.max_bounces) + ": must be in [0, " +
                     std::to_string(kMaxReferenceBounces) + "] or -1 (auto)");
  const std::map<std::string, MajorantGrid> grids{
      {"auto", MajorantGrid::kAuto}, {"bricks", MajorantGrid::kBricks}, {"none", MajorantGrid::kNone}};
  const auto grid = grids.find(options.majorant_grid);
  if (grid == grids.end())
    throw InputError("--majorant-grid " + options.majorant_grid + ": must be auto, bricks or none");
  check_output_path(options.output, "--output");
  check_outputs_not_inputs({{"--output", options.output}}, render_inputs(scene, options));
  Renderer renderer({options.device, options.validation, options.verbose, {}});
  std::unique_ptr<Progress> bar;
  // The scene's seed (--seed) seeds the paths: the same seed, scene and --spp, the same image.
  ReferenceOptions reference{options.spp, options.time_limit_s, scene.noise_seed, {}, grid->second,
                             options.max_bounces};
  if (progress_wanted(options.progress, options.quiet, options.verbose))
    reference.progress = [&](std::string_view stage, int done, int total) {
      if (!bar) bar = std::make_unique<Progress>(std::string(stage), total, true);
      bar->step(done);
    };
  const ReferenceImage image = renderer.render_reference(scene, reference);
  bar.reset();
  const bool exr = std::filesystem::path(options.output).extension() == ".exr" ||
                   std::filesystem::path(options.output).extension() == ".EXR";
  const ExrPixels pixels = options.exr_float ? ExrPixels::kFloat : ExrPixels::kHalf;
  // 32-bit floats whatever --exr-float says: a variance passes half's 65504 at a few hundred
  // cd/m^2 of noise, and a reference is for measuring.
  if (exr)
    write_exr_layers({{"", &image.mean, 4, {}}, {"variance", &image.variance, 3, {}}},
                     options.output, ExrPixels::kFloat);
  else
    write_image(image.mean, options.output, still_exposure(scene.output, image.mean), pixels,
                scene.output.tonemap);
  if (!options.quiet)
    std::fprintf(stderr, "nephele: reference %dx%d, %d samples per pixel in %.1f s on %s\n",
                 image.mean.width, image.mean.height, image.spp, image.seconds,
                 renderer.device_name().c_str());
  if (image.majorant_violations > 0)
    std::fprintf(stderr, "nephele: warning: %lld tentative collisions found the extinction above "
                 "its majorant: the image is biased\n", image.majorant_violations);
  if (image.cut_loops > 0)
    std::fprintf(stderr,
                 "nephele: warning: %lld tracking walks were cut at 2^24 tentative collisions: "
                 "the image is biased\n",
                 image.cut_loops);
  if (image.abandoned > 0 && !options.quiet)
    std::fprintf(stderr,
                 "nephele: the time limit left out %lld samples still in flight a tenth of it "
                 "later (of %lld taken)\n",
                 image.abandoned, (long long)(image.spp) * image.mean.width * image.mean.height);
  if (options.validation && renderer.validation_messages() > 0) {
    std::fprintf(stderr, "nephele: %d Vulkan validation messages\n", renderer.validation_messages());
    return 1;
  }
  std::cout << options.output << std::endl;
  return 0;
}

}  // namespace

int run_render(const RenderOptions& options) {
  // Everything the user typed is checked before any work, so a bad flag writes nothing.
  const Scene scene = resolve_scene(options.scene);
  if (options.reference && (options.layers || options.holdout))
    throw InputError("--layers and --holdout are the fast renderer's; --reference writes its "
                     "own layers (the mean and its variance)");
  if (options.reference) return run_reference(scene, options);
  const Sequence seq = plan_sequence(scene, options);
  if (options.verbose) {
    std::cerr << "# resolved scene\n" << scene_to_toml(scene);
    for (const std::string& line : weather::describe_metar(scene))
      std::cerr << "# " << line << "\n";
    for (const std::string& line : weather::describe_grib(scene)) std::cerr << "# " << line << "\n";
  }

  const bool stats_to_stdout = options.stats_json == kStandardOutput;
  const ExrPixels exr = options.exr_float ? ExrPixels::kFloat : ExrPixels::kHalf;
  // A flight is an animation: the first frame a still, the others reprojected from it.
  const bool animation = seq.path && !options.still_frames;
  // A single still shows the renderer's own progress: the noise textures, then the clouds
  // marched in bands (about a minute at 1920x1080 on a CPU).
  const bool still_progress =
      !seq.numbered && progress_wanted(options.progress, options.quiet, options.verbose);
  std::unique_ptr<Progress> stage_progress;
  RendererOptions renderer_options{options.device, options.validation, options.verbose, {}};
  if (still_progress)
    renderer_options.progress = [&](std::string_view stage, int done, int total) {
      if (done == 0) stage_progress = std::make_unique<Progress>(std::string(stage), total, true);
      if (stage_progress) stage_progress->step(done);
      if (done == total) stage_progress.reset();  // finishes its line
    };
  Renderer renderer(renderer_options);
  // Per frame for a sequence. (--verbose prints a line a frame instead, unless --progress.)
  Progress progress(
      "render", seq.frames,
      seq.numbered && progress_wanted(options.progress, options.quiet, options.verbose));
  // Auto exposure adapts from frame to frame over the scene time between them.
  std::optional<double> ev100;
  double previous_time_s = 0.0;
  for (int i = 0; i < seq.frames; ++i) {
    const Scene frame_scene = seq.scene(scene, options, i);
    std::optional<FilmLayers> layers;
    if (options.layers) layers = renderer.render_layers(frame_scene);
    const Frame frame = layers                 ? layers->frame
                        : animation && i > 0 ? renderer.render_next(frame_scene)
                                             : renderer.render(frame_scene);
    const double dt_s = std::abs(double(frame_scene.time_s) - previous_time_s);
    ev100 = frame_ev100(scene.output, frame.color, ev100 ? &*ev100 : nullptr, dt_s);
    previous_time_s = frame_scene.time_s;
    const float exposure = float(exposure_from_ev100(*ev100));
    const std::string path = seq.output(options.output, options, i, "--output");
    if (layers)
      write_film_exr(*layers, frame_scene, path, {exr, options.holdout, *ev100});
    else
      write_image(frame.color, path, exposure, exr, frame_scene.output.tonemap);
    if (!options.stats_json.empty())
      write_text_output(stats_to_stdout
                            ? options.stats_json
                            : seq.output(options.stats_json, options, i, "--stats-json"),
                        frame_stats_json(frame.stats, *ev100, path));
    progress.clear();
    if (options.verbose)
      std::fprintf(stderr, "nephele: %dx%d on %s: %.1f ms GPU, %.1f ms wall, EV100 %.2f%s\n",
                   frame.stats.width, frame.stats.height, frame.stats.device.c_str(),
                   frame.stats.frame_ms, frame.stats.wall_ms, *ev100,
                   scene.output.auto_exposure ? " (auto)" : "");
    if (options.validation && renderer.validation_messages() > 0) {
      std::fprintf(stderr, "nephele: %d Vulkan validation messages\n",
                   renderer.validation_messages());
      return 1;
    }
    if (!stats_to_stdout) std::cout << path << std::endl;
    progress.advance();
  }
  return 0;
}

}  // namespace nephele::cli

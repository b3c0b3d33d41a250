// nephele-view — interactive sky and cloud viewer (GLFW + Dear ImGui) on nephele's frame API.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <string>

#include "nephele/camera_path.h"
#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/output_file.h"
#include "scene_flags.h"
#include "script.h"
#include "viewer.h"

namespace {

void print_error(const std::string& kind, const std::string& message) {
  constexpr size_t kMaxChars = 1000;
  std::string text = message.size() > kMaxChars ? message.substr(0, kMaxChars - 3) + "..." : message;
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = ' ';
  std::fprintf(stderr, "nephele-view: %s: %s\n", kind.c_str(), text.c_str());
}

// "1280x800" -> width, height in [1, 16384].
void parse_size(const std::string& text, int& width, int& height) {
  if (!nephele::view::parse_window_size(text, width, height))
    throw nephele::InputError("--size " + nephele::shorten_for_message(text) +
                              ": expected WxH, each in [1, 16384], e.g. 1280x800");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{
      "nephele-view: interactive sky and volumetric clouds (right drag looks, WASD/QE fly, "
      "wheel or +/- speed, Z/C roll, space plays time, R records the camera path, P flies it, F1 "
      "hides the panel)"};
  app.set_version_flag("--version", "nephele-view 0.1.0");

  nephele::cli::SceneFlags scene_flags;
  nephele::cli::add_scene_flags(app, scene_flags);
  std::string size = "1280x800", script_path, camera_path;
  nephele::view::ViewerOptions options;
  app.add_option("--size", size, "window size WxH (default 1280x800)")->type_name("WxH");
  app.add_flag("--validation", options.validation,
               "Vulkan validation layer with synchronisation validation; any message makes the "
               "exit status 1");
  app.add_option("--device", options.device, "substring of the Vulkan device's name")
      ->type_name("NAME");
  app.add_option("--frames", options.frames, "render N frames, then write the screenshots and exit")
      ->type_name("N")
      ->check(CLI::Range(1L, 100'000'000L));
  app.add_option("--screenshot", options.screenshot,
                 "after the last frame, a still-quality render of the scene (.png or .exr), as "
                 "`nephele render` makes it")
      ->type_name("FILE");
  app.add_option("--window-screenshot", options.window_screenshot,
                 "the last frame's whole window, panel included (.png)")
      ->type_name("FILE");
  app.add_option("--script", script_path,
                 "timed commands, one a line: frame N set KEY VALUE | preset NAME | load FILE | "
                 "camera-path FILE | record-start | record-stop [FILE] | print-camera | "
                 "screenshot FILE | window-screenshot FILE | resize WxH | quit")
      ->type_name("FILE");
  app.add_option("--camera-path", camera_path,
                 "fly this camera path (TOML, as `nephele render --camera-path` reads) from the "
                 "first frame, in scene time; the clock runs")
      ->type_name("FILE");
  app.add_option("--target-ms", options.target_ms,
                 "frame time the dynamic resolution holds (default 33)")
      ->type_name("MS")
      ->check(CLI::Range(1.0, 10000.0));
  bool fixed_resolution = false;
  app.add_flag("--no-dynamic-resolution", fixed_resolution,
               "always render at the full output size");
  app.add_flag("--soak", options.soak,
               "measure RSS at frame 100 and at the end (with --frames); growth over 8 MiB "
               "makes the exit status 1");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    print_error("error", std::string(e.what()) + " (see nephele-view --help)");
    return 2;
  }

  nephele::install_temporary_file_cleanup();
  try {
    parse_size(size, options.window_width, options.window_height);
    options.scene = nephele::cli::resolve_scene(scene_flags);
    options.follow_window = !scene_flags.width && !scene_flags.height;
    options.dynamic_resolution = !fixed_resolution;
    if (!options.screenshot.empty()) nephele::check_output_path(options.screenshot, "--screenshot");
    if (!options.window_screenshot.empty()) {
      nephele::check_output_path(options.window_screenshot, "--window-screenshot");
      if (!options.window_screenshot.ends_with(".png") &&
          !options.window_screenshot.ends_with(".PNG"))
        throw nephele::InputError("--window-screenshot '" +
                                  nephele::shorten_path_for_message(options.window_screenshot) +
                                  "': unsupported image format (allowed: .png)");
    }
    if ((!options.screenshot.empty() || !options.window_screenshot.empty() || options.soak) &&
        options.frames < 0)
      throw nephele::InputError(
          "--screenshot, --window-screenshot and --soak need --frames N (how many frames "
          "before it)");
    if (!script_path.empty()) options.script = nephele::view::load_script(script_path);
    if (!camera_path.empty()) {
      try {
        options.camera_path = nephele::load_camera_path(camera_path, options.scene);
      } catch (const nephele::InputError& e) {
        throw nephele::InputError("--camera-path " + std::string(e.what()));
      }
      options.camera_path_name = camera_path;
    }
    return nephele::view::run_viewer(options);
  } catch (const nephele::InputError& e) {
    print_error("error", e.what());
    return 2;
  } catch (const std::exception& e) {
    print_error("failed", e.what());
    return 1;
  }
}

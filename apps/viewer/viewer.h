// nephele-view — the interactive viewer: a GLFW window, its own Vulkan device and swapchain,
// nephele's frame API (frame.h) rendering into it, and a Dear ImGui panel over the image.
#pragma once

#include <optional>
#include <string>

#include "nephele/camera_path.h"
#include "nephele/scene.h"
#include "script.h"

namespace nephele::view {

struct ViewerOptions {
  Scene scene;                   // resolved from --scene / --preset / the scene flags
  bool follow_window = true;     // output size = window size (false when --width/--height given)
  int window_width = 1280, window_height = 800;  // --size
  bool validation = false;       // --validation
  std::string device;            // --device
  long frames = -1;              // --frames N: quit after N frames (-1: run until closed)
  std::string screenshot;        // --screenshot FILE: after the last frame, a still render
  std::string window_screenshot;  // --window-screenshot FILE: the last frame's window
  std::optional<Script> script;  // --script FILE
  std::optional<CameraPath> camera_path;  // --camera-path FILE: flown from the first frame
  std::string camera_path_name;           // its file's name, for messages
  bool soak = false;             // --soak: RSS at frame 100 and at the end; growth fails
  double target_ms = 33.0;       // --target-ms: dynamic resolution's frame time
  bool dynamic_resolution = true;
};

// Runs until the window closes, --frames are done or the script quits. Returns the exit
// status: 0, or 1 when validation was on and reported anything, a screenshot could not be
// written or the soak found memory growing. Throws nephele::RuntimeError when there is no
// window or device.
int run_viewer(const ViewerOptions& options);

}  // namespace nephele::view

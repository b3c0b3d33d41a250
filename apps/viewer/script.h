// nephele-view — timed commands (--script FILE): one a line, run at a frame number.
//
//   # comment
//   frame 10 set clouds.coverage 0.9      scene key, TOML literal (as set_scene_value takes)
//   frame 20 preset overcast              load a built-in preset
//   frame 25 load scenes/storm.toml       load a scene file
//   frame 30 camera-path path.toml        fly a camera path (camera_path.h) in scene time
//   frame 32 record-start                 record the flown camera as a path (path_control.h)
//   frame 38 record-stop flight.toml      stop recording and write the path (the file optional)
//   frame 39 print-camera                 the scene's camera to standard output, as TOML
//   frame 40 screenshot out.png           still-quality render of the scene (.png or .exr)
//   frame 45 window-screenshot win.png    the window as shown, panel included (.png)
//   frame 48 resize 640x400               resize the window (the swapchain follows)
//   frame 50 quit
//
// Commands of one frame run in the order of their lines. A line that cannot be a command
// (unknown command, bad frame number, unknown scene key, unsupported image extension) is
// refused when the script is read: InputError "FILE:LINE: what". A value that is of the wrong
// type or out of range, or a path file that cannot be read or is malformed, is reported when the
// command runs ("FILE:LINE: " and the message), and the scene (and the flight) stays as it was.
#pragma once

#include <stdexcept>
#include <string>
#include <vector>

namespace nephele::view {

enum class ScriptAction {
  kSet,
  kPreset,
  kLoad,
  kCameraPath,
  kRecordStart,
  kRecordStop,
  kPrintCamera,
  kScreenshot,
  kWindowScreenshot,
  kResize,
  kQuit
};

struct ScriptCommand {
  int line = 0;           // 1-based line in the script
  long frame = 0;         // run before rendering this frame (0 = the first)
  ScriptAction action = ScriptAction::kQuit;
  std::string key;        // kSet: "clouds.coverage"
  std::string argument;   // kSet: the value's TOML text; others: the name or path ("" for none)
  int width = 0, height = 0;  // kResize
};

// "640x400" -> width and height in [1, 16384]; false when it is not one.
bool parse_window_size(std::string_view text, int& width, int& height);

struct Script {
  std::string source;                  // the file's name, for messages
  std::vector<ScriptCommand> commands;  // sorted by frame, then line
};

// Parses a script's text; `source` prefixes messages. Throws nephele::InputError on a bad line.
Script parse_script(const std::string& text, const std::string& source);
// Reads and parses a script file (at most 1 MiB).
Script load_script(const std::string& path);

}  // namespace nephele::view

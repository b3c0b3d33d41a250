// nephele-view — reading --script files.
#include "script.h"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/output_file.h"
#include "nephele/scene_io.h"

namespace nephele::view {
namespace {

constexpr std::uintmax_t kMaxScriptBytes = 1u << 20;
// Frames a script may name: about 3 days at 60 frames a second.
constexpr long kMaxFrame = 16'000'000;

std::string_view trim(std::string_view text) {
  const size_t begin = text.find_first_not_of(" \t\r");
  if (begin == std::string_view::npos) return {};
  const size_t end = text.find_last_not_of(" \t\r");
  return text.substr(begin, end - begin + 1);
}

// The first word of `text` and the rest, trimmed.
std::pair<std::string_view, std::string_view> split_word(std::string_view text) {
  text = trim(text);
  const size_t space = text.find_first_of(" \t");
  if (space == std::string_view::npos) return {text, {}};
  return {text.substr(0, space), trim(text.substr(space))};
}

struct ActionName {
  const char* name;
  ScriptAction action;
};
constexpr ActionName kActions[] = {
    {"set", ScriptAction::kSet},
    {"preset", ScriptAction::kPreset},
    {"load", ScriptAction::kLoad},
    {"camera-path", ScriptAction::kCameraPath},
    {"record-start", ScriptAction::kRecordStart},
    {"record-stop", ScriptAction::kRecordStop},
    {"print-camera", ScriptAction::kPrintCamera},
    {"screenshot", ScriptAction::kScreenshot},
    {"window-screenshot", ScriptAction::kWindowScreenshot},
    {"resize", ScriptAction::kResize},
    {"quit", ScriptAction::kQuit},
};

// 'text', shortened for a message.
std::string quoted(std::string_view text) {
  std::string out = "'";
  out += shorten_for_message(text);
  out += "'";
  return out;
}

std::string action_list() {
  std::string out;
  for (const ActionName& a : kActions) out += (out.empty() ? "" : ", ") + std::string(a.name);
  return out;
}

}  // namespace

bool parse_window_size(std::string_view text, int& width, int& height) {
  const size_t x = text.find_first_of("xX");
  if (x == std::string_view::npos) return false;
  const auto number = [](std::string_view digits, int& out) {
    const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), out);
    return !digits.empty() && r.ec == std::errc() && r.ptr == digits.data() + digits.size() &&
           out >= 1 && out <= 16384;
  };
  return number(text.substr(0, x), width) && number(text.substr(x + 1), height);
}

Script parse_script(const std::string& text, const std::string& source) {
  Script script;
  script.source = shorten_path_for_message(source);
  std::istringstream in(text);
  std::string raw;
  int line_number = 0;
  while (std::getline(in, raw)) {
    ++line_number;
    const auto bad = [&](const std::string& what) {
      return InputError(script.source + ":" + std::to_string(line_number) + ": " + what);
    };
    std::string_view line = trim(raw);
    if (line.empty() || line.front() == '#') continue;

    auto [word, rest] = split_word(line);
    if (word != "frame")
      throw bad(quoted(line) + ": expected 'frame N COMMAND ...'");
    auto [number, command_text] = split_word(rest);
    long frame = -1;
    const auto parsed = std::from_chars(number.data(), number.data() + number.size(), frame);
    if (number.empty() || parsed.ec != std::errc() || parsed.ptr != number.data() + number.size() ||
        frame < 0 || frame > kMaxFrame)
      throw bad("frame " + quoted(number) + ": expected an integer in [0, " +
           std::to_string(kMaxFrame) + "]");

    auto [name, argument] = split_word(command_text);
    const ActionName* action = std::find_if(std::begin(kActions), std::end(kActions),
                                            [&](const ActionName& a) { return name == a.name; });
    if (action == std::end(kActions))
      throw bad("unknown command " + quoted(name) + " (allowed: " + action_list() + ")");

    ScriptCommand command;
    command.line = line_number;
    command.frame = frame;
    command.action = action->action;
    switch (command.action) {
      case ScriptAction::kSet: {
        auto [key, value] = split_word(argument);
        if (key.empty() || value.empty())
          throw bad("set: expected 'set KEY VALUE', e.g. 'set clouds.coverage 0.9'");
        try {
          get_scene_value(Scene{}, key);  // the key exists
        } catch (const InputError& error) {
          throw bad(std::string("set: ") + error.what());
        }
        command.key = std::string(key);
        command.argument = std::string(value);
        break;
      }
      case ScriptAction::kQuit:
      case ScriptAction::kRecordStart:
      case ScriptAction::kPrintCamera:
        if (!argument.empty())
          throw bad(std::string(name) + ": takes nothing, got " + quoted(argument));
        break;
      case ScriptAction::kResize:
        if (!parse_window_size(argument, command.width, command.height))
          throw bad("resize " + quoted(argument) + ": expected WxH, each in [1, 16384]");
        break;
      case ScriptAction::kCameraPath:
        // The file is read when the command runs: an earlier record-stop may write it.
        if (argument.empty())
          throw bad("camera-path: expected a path file, e.g. 'camera-path flight.toml'");
        command.argument = std::string(argument);
        break;
      case ScriptAction::kRecordStop:
        if (!argument.empty()) {
          try {
            check_output_file(std::string(argument), "record-stop");
          } catch (const InputError& error) {
            throw bad(error.what());
          }
        }
        command.argument = std::string(argument);
        break;
      case ScriptAction::kScreenshot:
      case ScriptAction::kWindowScreenshot:
        if (argument.empty()) throw bad(std::string(name) + ": expected a file name");
        try {
          check_output_path(std::string(argument), std::string(name));
          if (command.action == ScriptAction::kWindowScreenshot &&
              !std::string(argument).ends_with(".png"))
            throw InputError("window-screenshot '" + shorten_path_for_message(argument) +
                             "': unsupported image format (allowed: .png)");
        } catch (const InputError& error) {
          throw bad(error.what());
        }
        command.argument = std::string(argument);
        break;
      case ScriptAction::kPreset:
      case ScriptAction::kLoad:
        if (argument.empty())
          throw bad(std::string(name) + ": expected a " +
               (command.action == ScriptAction::kPreset ? "preset name" : "scene file"));
        if (command.action == ScriptAction::kPreset) {
          const auto names = preset_names();
          if (std::find(names.begin(), names.end(), argument) == names.end()) {
            std::string list;
            for (const std::string& n : names) list += (list.empty() ? "" : ", ") + n;
            throw bad("preset " + quoted(argument) + ": unknown preset (available: " +
                 list + ")");
          }
        }
        command.argument = std::string(argument);
        break;
    }
    script.commands.push_back(std::move(command));
  }
  std::stable_sort(script.commands.begin(), script.commands.end(),
                   [](const ScriptCommand& a, const ScriptCommand& b) { return a.frame < b.frame; });
  return script;
}

Script load_script(const std::string& path) {
  const std::string cannot = shorten_path_for_message(path) + ": cannot read the script: ";
  std::error_code error;
  const auto status = std::filesystem::status(path, error);
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(cannot + "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(cannot + std::strerror(errno));
  std::string text(kMaxScriptBytes + 1, '\0');
  in.read(text.data(), std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  if (text.size() > kMaxScriptBytes) throw InputError(cannot + "larger than 1 MiB");
  return parse_script(text, path);
}

}  // namespace nephele::view

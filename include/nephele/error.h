// nephele — errors reported at the boundary (scene load, CLI, API call).
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>

namespace nephele {

// Invalid input: the message names the parameter, the value and what is allowed,
// e.g. "clouds.coverage = 1.5: must be in [0, 1]". The CLI prints it and exits 2.
class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Failure of the machine, not of the input (no Vulkan device, device lost, I/O).
class RuntimeError : public std::runtime_error {
 public:
  explicit RuntimeError(const std::string& message) : std::runtime_error(message) {}
};

// A value as an error message may echo it: control characters as '?', and at most
// kMaxEchoedChars characters (longer text keeps its start and ends in "..."), so that a
// message stays one short line whatever was typed or read.
constexpr size_t kMaxEchoedChars = 80;
std::string shorten_for_message(std::string_view text);

// A parser's description of an error, which may quote what it read: on one line (a newline
// as a space, other control characters as '?'), whatever its length.
std::string one_line_for_message(std::string_view text);

// A path as an error message may echo it: as shorten_for_message, but at most kMaxPathChars
// and a long path keeps its end (the file's name): ".../scenes/storm.toml".
constexpr size_t kMaxPathChars = 200;
std::string shorten_path_for_message(std::string_view path);

// A number as a message shows it: printf's %g (1e+05, 0.25, nan, inf).
std::string number_for_message(double value);

}  // namespace nephele

// nephele — output files: checked before any work, written whole or not at all, and only
// ever regular files.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace nephele {

// "-" names standard output where an output allows it (text, not images).
constexpr std::string_view kStandardOutput = "-";

// Throws InputError naming `parameter` unless `path` can be written: a name that fits the file
// system (its NAME_MAX and PATH_MAX), in a folder that exists and is writable, where nothing
// but a regular file (or a link to one), which will be replaced, is now; or "-" when
// `allow_stdout`. The message reads e.g. "--stats-json '/dev/null': is not a regular file
// ...". Writes nothing. (Images: check_output_path of image.h adds the format.)
void check_output_file(const std::string& path, const std::string& parameter,
                       bool allow_stdout = false);

// (parameter, path) pairs: "--output", "out.png"; "clouds.weather_map", "wm.png".
using NamedPaths = std::vector<std::pair<std::string, std::string>>;

// Throws InputError when two of the outputs are the same file: the same absolute, normalised
// path through existing links, or, for files that exist, the same device and inode (a hard
// link): "--stats-json 'a.exr': is the same file as --output". "-" (standard output) is never
// compared.
void check_distinct_outputs(const NamedPaths& outputs);

// Throws InputError when an output is the same file as an input, through any path, symbolic
// or hard link (the same device and inode): "--output 'wm.png': is the same file as the input
// clouds.weather_map ...". Writing it would replace what the work reads. Inputs that do not
// exist (yet) and "-" are skipped.
void check_outputs_not_inputs(const NamedPaths& outputs, const NamedPaths& inputs);

// Writes `bytes` to `path`: into a new temporary file beside it, then renamed over it, so a
// reader sees the old file or the whole new one, never a part. A link is followed: the file
// it points to is replaced. Throws RuntimeError naming the path on failure, with nothing left
// behind.
void write_file_atomically(const std::string& path, std::string_view bytes);

// Installs handlers for SIGINT, SIGTERM and SIGHUP that delete the temporary files of writes
// in progress and then end the process as the signal would have. For programs (the CLI); a
// host with handlers of its own can call remove_temporary_files() from them instead.
void install_temporary_file_cleanup();

// Deletes the temporary files of writes in progress. Async-signal-safe.
void remove_temporary_files() noexcept;

}  // namespace nephele

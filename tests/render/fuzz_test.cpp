// Seeded fuzz tests of everything `nephele render` reads: scene files (TOML), the scene flags and
// whole command lines. The contract, for every input:
//   - either it is rejected: an InputError in-process; for a `nephele render` process exit
//     status 2, exactly one line on stderr starting "nephele: error: " (at most
//     kMaxErrorLineChars characters) and nothing written;
//   - or it is accepted, and the image it renders has only finite values (no NaN, no inf in
//     the linear HDR image);
//   - never a crash, a hang, another exception type or another exit status.
//
// Every input comes from std::mt19937 seeded with kSeed, a stream number and the case's index,
// so each case regenerates alone. A failure names its case and prints the input: the command
// line, or how the TOML was made and the file it was saved to (under
// NEPHELE_TEST_OUTPUT_DIR/fuzz/<test>/).
//
// What could crash or hang the test binary runs in a child process: renders (a Renderer per
// child, validation layer on), whole files read from disk, the 50,000-level dotted key.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <poll.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <optional>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include "nephele/error.h"
#include "nephele/image.h"
#include "nephele/renderer.h"
#include "nephele/scene_io.h"
#include "render_command.h"
#include "scene/scene_fields.h"
#include "scene_flags.h"
#include "support/fuzz_support.h"

namespace fs = std::filesystem;
using nephele::Scene;
using nephele::test::demangled_type;
using nephele::test::describe_death;
using nephele::test::printable;
using nephele::test::reset_peak_memory;
using nephele::test::write_all;

namespace {

// --- budget and contract ----------------------------------------------------------------------

constexpr uint32_t kSeed = 20260611;
// Streams of cases, each seeded kSeed + stream + index.
constexpr uint32_t kSceneStream = 0, kCommandStream = 1000000, kProcessStream = 2000000,
                   kSampleStream = 3000000;

constexpr int kSceneFileCases = 4000;    // TOML texts through parse_scene_toml + validate_scene
constexpr int kCommandLineCases = 3000;  // command lines through CLI11 + resolve_scene
constexpr int kProcessCases = 12;        // generated command lines run as processes
constexpr int kCli11ProcessCases = 40;   // CLI11 errors judged on a process (rejected at once)
constexpr int kRandomRenderCases = 16;   // accepted scenes rendered, besides the edge scenes
constexpr int kRenderSize = 16;          // rendered images are 16x16
// The light volume costs about 5 s a render on lavapipe whatever the image size, and nearly
// every fuzzed scene rebuilds it, and the diffusion light's field with it as much again; it is
// left on in these many sampled renders and turned off (quality.light_volume_km = 0, --light-
// volume-km 0; the diffusion light then falls back to the two-stream light) in the others.
constexpr int kLightVolumeRenders = 2;
constexpr int kMaxRandomDottedDepth = 2000;  // a.b.c... in random cases; 50,000 has its own test
constexpr int kKnownDeepDottedDepth = 50000;
// As apps/cli/main.cpp caps a printed line (an unknown key's message lists the allowed keys).
constexpr size_t kMaxErrorLineChars = 1000;
constexpr int kProcessTimeoutS = 60;
constexpr int kRenderTimeoutS = 60;  // per render in a render child, its Renderer's start included
constexpr int kFileReadTimeoutS = 20;
constexpr rlim_t kProcessMemoryBytes = rlim_t(3) << 30;     // address space of a CLI process
constexpr size_t kProcessMemoryUse = size_t(1) << 30;       // resident memory a CLI run may use
constexpr size_t kFileReadMemoryBytes = size_t(512) << 20;  // extra for a child reading a file

const std::string kErrorPrefix = "nephele: error: ";

// --- small helpers ----------------------------------------------------------------------------

// Deterministic choices for one case.
class Rng {
 public:
  explicit Rng(uint32_t seed) : engine_(seed) {}
  size_t below(size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(engine_); }
  int between(int lo, int hi) { return std::uniform_int_distribution<int>(lo, hi)(engine_); }
  double unit() { return std::uniform_real_distribution<double>(0.0, 1.0)(engine_); }
  bool chance(double p) { return unit() < p; }
  template <typename T>
  const T& pick(const std::vector<T>& items) {
    return items[below(items.size())];
  }
  unsigned char byte() { return static_cast<unsigned char>(engine_() & 0xff); }
  std::mt19937& engine() { return engine_; }

 private:
  std::mt19937 engine_;
};

// One of several weighted actions.
struct Weighted {
  int weight;
  std::function<void()> action;
};
void do_one_of(Rng& rng, const std::vector<Weighted>& actions) {
  int total = 0;
  for (const Weighted& a : actions) total += a.weight;
  int roll = rng.between(0, total - 1);
  for (const Weighted& a : actions) {
    if (roll < a.weight) return a.action();
    roll -= a.weight;
  }
}

// Shell words that paste back into a shell as the same arguments.
std::string shell_quote(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& word : words) {
    bool plain = !word.empty();
    for (char c : word)
      plain = plain && (std::isalnum(static_cast<unsigned char>(c)) || std::strchr("-_=.,/+:@", c));
    std::string quoted = "'";
    for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
    out += (out.empty() ? "" : " ") + (plain ? word : quoted + "'");
  }
  return out;
}

std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> lines;
  std::string line;
  std::istringstream in(text);
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::string join_lines(const std::vector<std::string>& lines) {
  std::string text;
  for (const std::string& line : lines) text += line + "\n";
  return text;
}

void write_file(const fs::path& path, const std::string& bytes) {
  // Beside the target, then renamed: test processes running at once see whole files only.
  const fs::path tmp = path.string() + ".tmp" + std::to_string(getpid());
  std::ofstream(tmp, std::ios::binary) << bytes;
  fs::rename(tmp, path);
}

// The error line the CLI prints for `message`, and why it breaks the one-line rule ("" if not).
std::string error_line_problem(const std::string& message) {
  const std::string line = kErrorPrefix + message;
  if (message.empty()) return "error message is empty";
  if (line.find_first_of(std::string("\n\r\0", 3)) != std::string::npos)
    return "error message spans several lines";
  if (line.size() > kMaxErrorLineChars)
    return "error line is longer than " + std::to_string(kMaxErrorLineChars) + " characters";
  return "";
}

// The number of pixels with a NaN or infinite channel, and the first of them, described.
size_t count_non_finite(const nephele::Image& image, std::string& first) {
  size_t count = 0;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const glm::vec4& p = image.at(x, y);
      if (std::isfinite(p.r) && std::isfinite(p.g) && std::isfinite(p.b) && std::isfinite(p.a))
        continue;
      if (count++ == 0) {
        std::ostringstream out;
        out << "(" << x << ", " << y << ") = (" << p.r << ", " << p.g << ", " << p.b << ", " << p.a
            << ")";
        first = out.str();
      }
    }
  return count;
}

// --- failures, grouped by symptom -------------------------------------------------------------

class FailureLog {
 public:
  void add(const std::string& symptom, const std::string& label, const std::string& detail,
           const std::string& input) {
    failures_.push_back({symptom, label, detail, input});
  }
  size_t size() const { return failures_.size(); }

  // Each symptom with its number of inputs, the first few in full, the rest by label.
  std::string report() const { return nephele::test::failure_report(failures_, "input", 5); }

 private:
  std::vector<nephele::test::Failure> failures_;
};

// A folder of this test's own under NEPHELE_TEST_OUTPUT_DIR/fuzz, emptied first.
fs::path test_folder() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path dir = fs::path(NEPHELE_TEST_OUTPUT_DIR) / "fuzz" / info->name();
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// --- files the inputs point at ----------------------------------------------------------------

struct Fixtures {
  std::string weather_png, weather_exr, garbage_png;  // weather maps: good, good, not a PNG
  std::string scene, empty, big, binary;              // scene files: good, empty, > 1 MiB, noise
  std::string missing, directory;
  std::vector<std::string> weather_paths;  // for clouds.weather_map and --weather-map
  std::vector<std::string> scene_paths;    // for --scene: none of them reads forever
};

// Written once per process into NEPHELE_TEST_OUTPUT_DIR/fuzz/fixtures.
const Fixtures& fixtures() {
  static const Fixtures f = [] {
    const fs::path dir = fs::path(NEPHELE_TEST_OUTPUT_DIR) / "fuzz" / "fixtures";
    fs::create_directories(dir / "a-directory");
    Fixtures f;
    auto path = [&](const char* name) { return (dir / name).string(); };
    f.weather_png = path("weather.png");
    f.weather_exr = path("weather.exr");
    f.garbage_png = path("garbage.png");
    f.scene = path("scene.toml");
    f.empty = path("empty.toml");
    f.big = path("big.toml");
    f.binary = path("binary.toml");
    f.missing = path("missing.toml");
    f.directory = path("a-directory");

    nephele::Image map(8, 8);
    for (size_t i = 0; i < map.pixels.size(); ++i)
      map.pixels[i] = glm::vec4(float(i % 8) / 7.0f, float(i / 8) / 7.0f, 0.5f, 1.0f);
    for (const std::string& p : {f.weather_png, f.weather_exr}) {
      const std::string tmp = fs::path(p).stem().string() + ".tmp" + std::to_string(getpid()) +
                              fs::path(p).extension().string();
      nephele::write_image(map, (dir / tmp).string());
      fs::rename(dir / tmp, p);
    }
    write_file(f.garbage_png, "this is not a PNG\n");
    write_file(f.scene, "preset = \"default\"\n[clouds]\ncoverage = 0.6\n");
    write_file(f.empty, "");
    std::string big;
    while (big.size() <= (size_t(1) << 20))
      big += "# padding padding padding padding padding padding padding pad\n";
    write_file(f.big, big + "[clouds]\ncoverage = 0.3\n");
    Rng rng(kSeed);
    std::string noise;
    for (int i = 0; i < 4096; ++i) noise += char(rng.byte());
    write_file(f.binary, noise);

    f.weather_paths = {f.weather_png, f.weather_exr, f.garbage_png, "",  f.missing,
                       f.directory,   "/dev/zero",   "/dev/null",   ".", "relative/missing.png"};
    f.scene_paths = {f.scene,   f.empty,     f.big,       f.binary,
                     f.missing, f.directory, "/dev/null", f.scene + "/"};
    return f;
  }();
  return f;
}

// --- values -----------------------------------------------------------------------------------

// Numbers at and past every edge, as TOML: NaN and the infinities, signed zeros, just past 0
// and 1, the float range's ends (3.4028235e38 is FLT_MAX; 3.5e38 and 1e300 overflow a float),
// denormals and underflow, huge integers, TOML's other number forms.
// clang-format off
const std::vector<std::string> kTomlNumbers = {
    "nan",    "+nan",        "-nan",         "inf",   "+inf",       "-inf",
    "0",      "0.0",         "-0.0",         "-1",    "-1.5",       "0.5",
    "1",      "2",           "25",           "1e9",   "1e10",       "1e20",
    "1e30",   "-1e30",       "1e38",         "3e38",  "-3e38",      "3.4028235e38",
    "3.5e38", "1e300",       "-1e300",       "1e-30", "1e-38",      "1e-45",
    "-1e-45", "1e-46",       "5e-324",       "1.0000001", "0.99999994", "16777217",
    "9223372036854775807",   "-9223372036854775808", "0x7fffffff", "1_000.5", "1e+30"};
// clang-format on

// Integers at and past the edges of int, uint32 and the ranges of the integer keys.
// clang-format off
const std::vector<std::string> kTomlIntegers = {
    "0",           "-1",          "1",           "2",          "3",          "4",
    "5",           "16",          "64",          "256",        "257",        "1000",
    "1001",        "1024",        "1025",        "16384",      "16385",      "2147483647",
    "2147483648",  "-2147483648", "-2147483649", "4294967295", "4294967296", "9223372036854775807",
    "-9223372036854775808", "99999999999999999999", "0x10", "0o17", "0b11", "+7", "1.0", "1e3",
    "nan"};
// clang-format on

// Values of every TOML type, and broken ones: for most keys the wrong type.
// clang-format off
const std::vector<std::string> kTomlAnyValues = {
    "\"\"", "\"abc\"", "\"1.5\"", "\"nan\"", "'literal'", "\"\"\"multi\nline\"\"\"",
    "\"\\u00e9\\u4e91\"", "\"a\\tb\"", "true", "false", "[]", "[1]", "[1, 2]", "[1, 2, 3]",
    "[1, 2, 3, 4]", "[nan, 0, 1]", "[\"a\", 1]", "[[1, 2], [3, 4]]", "[1, 2.5, true]", "{}",
    "{ a = 1 }", "{ x = { y = 2 } }", "1979-05-27T07:32:00Z", "1979-05-27T07:32:00", "1979-05-27",
    "07:32:00", "", "=", "[", "{", "\"unterminated", "1 2", "0.5 # comment", "[1, 2,]",
    "[1,\n2]"};
// clang-format on

// Dates and times (without TOML quotes): impossible fields, no zone, huge and negative years,
// leap days, leap seconds, the largest offsets, empty.
// clang-format off
const std::vector<std::string> kDates = {
    "2026-13-45T99:99:99Z",      "",
    "99999-01-01T00:00:00Z",     "2026-06-21T18:30:00Z",
    "2026-06-21T18:30:00",       "2026-02-29T12:00:00Z",
    "2024-02-29T12:00:00Z",      "0000-01-01T00:00:00Z",
    "-001-01-01T00:00:00Z",      "9999-12-31T23:59:60Z",
    "2026-06-21T18:30:00+14:00", "2026-06-21T18:30:00+15:00",
    "2026-06-21T18:30:00-14:59", "2026-06-21T18:30:00.123456789Z",
    "2026-06-21 18:30:00Z",      "2026-06-21T18:30Z",
    "1e30",                      "nan",
    "2026-06-21T18:30:00Z\n",    "2026-06-21T18:30:00ZZ",
    "1600-01-01T00:00:00Z",      "2026-06-21T24:00:00Z"};
// clang-format on

// What `key = value` may hold, for the value mutations.
// clang-format off
enum class Kind {
  Float, Integer, Vec2, Vec3, Time, Path, MarchMode, SkyModel, ConditionsMode, VoxelMarch,
  VoxelShadow, Bool, Preset, Table
};
// clang-format on

// A random float of any magnitude a float holds, e.g. "-3.81472e-21".
std::string random_magnitude(Rng& rng) {
  const double value = (rng.chance(0.3) ? -1.0 : 1.0) * (1.0 + 9.0 * rng.unit()) *
                       std::pow(10.0, rng.between(-45, 38));
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// A number for a float key: mostly an edge, sometimes any magnitude or a value near the usual
// [-2, 2] (which the range checks mostly accept).
std::string toml_number(Rng& rng) {
  if (rng.chance(0.2)) return random_magnitude(rng);
  if (rng.chance(0.15)) {
    char text[32];
    std::snprintf(text, sizeof text, "%.4f", rng.unit() * 4.0 - 2.0);
    return text;
  }
  return rng.pick(kTomlNumbers);
}

// An array for a vector key: mostly the right length with some edge components, sometimes the
// wrong length or element types.
std::string toml_vector(Rng& rng, size_t size) {
  size_t n = size;
  if (rng.chance(0.15)) n = rng.pick(std::vector<size_t>{0, 1, size - 1, size + 1, 8});
  std::string text = "[";
  for (size_t i = 0; i < n; ++i) {
    text += i ? ", " : "";
    if (rng.chance(0.05))
      text += rng.pick(kTomlAnyValues);
    else
      text += rng.chance(0.5) ? rng.pick(std::vector<std::string>{"0", "1", "2", "0.25", "-1"})
                              : toml_number(rng);
  }
  return text + "]";
}

std::string quoted(const std::string& text) {
  return nephele::scene_detail::toml_quote(text);
}

// A value of the key's own type, mostly at or past the edges of what it allows.
std::string typed_value(Rng& rng, Kind kind) {
  switch (kind) {
    case Kind::Float:
      return toml_number(rng);
    case Kind::Integer:
      return rng.pick(kTomlIntegers);
    case Kind::Vec2:
      return toml_vector(rng, 2);
    case Kind::Vec3:
      return toml_vector(rng, 3);
    case Kind::Time:
      return rng.chance(0.15)
                 ? rng.pick(std::vector<std::string>{"2026-06-21T18:30:00Z", "1979-05-27T07:32:00"})
                 : quoted(rng.pick(kDates));
    case Kind::Path:
      return quoted(rng.pick(fixtures().weather_paths));
    case Kind::MarchMode:
      return quoted(
          rng.pick(std::vector<std::string>{"default", "baseline", "Default", "", "default "}));
    case Kind::SkyModel:
      return quoted(
          rng.pick(std::vector<std::string>{"hillaire", "preetham", "reference", "rayleigh", ""}));
    case Kind::ConditionsMode:
      return quoted(rng.pick(std::vector<std::string>{"off", "artist", "overlay", "on", "ARTIST"}));
    case Kind::VoxelMarch:
      return quoted(
          rng.pick(std::vector<std::string>{"plain", "three-phase", "three_phase", "Plain", ""}));
    case Kind::VoxelShadow:
      return quoted(
          rng.pick(std::vector<std::string>{"march", "sdf-cone", "sdf", "cone", "MARCH"}));
    case Kind::Bool:
      return rng.pick(std::vector<std::string>{"true", "false", "\"true\"", "1", "0"});
    case Kind::Preset: {
      std::vector<std::string> names = nephele::preset_names();
      names.insert(names.end(), {"nosuch", "", "../presets/default", "default.toml"});
      return rng.chance(0.1) ? rng.pick(std::vector<std::string>{"1", "[\"default\"]", "{}"})
                             : quoted(rng.pick(names));
    }
    case Kind::Table:
      return rng.pick(std::vector<std::string>{"{}", "{ hour = 1.0 }", "1", "\"night\""});
  }
  return "0";
}

// A value of any type, mostly the wrong one for the key.
std::string any_value(Rng& rng) {
  if (rng.chance(0.08)) {  // nested arrays, past toml++'s limit of 256 levels at times
    const int depth = rng.between(2, 600);
    return std::string(size_t(depth), '[') + "1" + std::string(size_t(depth), ']');
  }
  if (rng.chance(0.04)) {  // a long string
    return quoted(std::string(size_t(rng.between(100, 100000)), 'x'));
  }
  return rng.pick(kTomlAnyValues);
}

// --- the scene keys ---------------------------------------------------------------------------

using nephele::scene_detail::Field;
using nephele::scene_detail::scene_sections;
using nephele::scene_detail::Section;

Kind kind_of_field(const Field& field) {
  return std::visit(
      [&](auto access) {
        using T = std::remove_reference_t<decltype(access(std::declval<Scene&>()))>;
        if constexpr (std::is_same_v<T, float>)
          return Kind::Float;
        else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, uint32_t>)
          return Kind::Integer;
        else if constexpr (std::is_same_v<T, glm::vec2>)
          return Kind::Vec2;
        else if constexpr (std::is_same_v<T, glm::vec3>)
          return Kind::Vec3;
        else if constexpr (std::is_same_v<T, std::string>)
          return field.name == "time" ? Kind::Time : Kind::Path;
        else if constexpr (std::is_same_v<T, nephele::MarchMode>)
          return Kind::MarchMode;
        else if constexpr (std::is_same_v<T, nephele::SkyModel>)
          return Kind::SkyModel;
        else if constexpr (std::is_same_v<T, nephele::ConditionsMode>)
          return Kind::ConditionsMode;
        else if constexpr (std::is_same_v<T, nephele::VoxelMarch>)
          return Kind::VoxelMarch;
        else if constexpr (std::is_same_v<T, nephele::VoxelShadow>)
          return Kind::VoxelShadow;
        else
          return Kind::Bool;
      },
      field.access);
}

const Section* find_section(std::string_view name) {
  for (const Section& section : scene_sections())
    if (section.name == name) return &section;
  return nullptr;
}

// The kind of `key` in table `section` ("" for the top level); Float for keys the table lacks.
Kind kind_of(std::string_view section, std::string_view key) {
  const Section* s = find_section(section);
  if (!s) return Kind::Float;
  for (const Field& field : s->fields)
    if (field.name == key) return kind_of_field(field);
  if (key == "preset") return Kind::Preset;
  if (key == "altitude_m" || key == "elevation_deg" || key == "azimuth_deg") return Kind::Float;
  for (std::string_view extra : s->extra_keys)
    if (extra == key) return Kind::Table;  // conditions.good, conditions.good.night, ...
  return Kind::Float;
}

bool is_keyframe_table(std::string_view section) {
  return section.starts_with("conditions.good") || section.starts_with("conditions.bad");
}

// --- scene files: generation ------------------------------------------------------------------

struct SceneText {
  std::string text;
  std::string recipe;  // how it was made, for the report: "preset 'sunset' in full; ..."
};

// The texts mutations start from: every preset in full (scene_to_toml: every key written),
// every preset by name only, and the empty file (the defaults).
const std::vector<SceneText>& scene_bases() {
  static const std::vector<SceneText> bases = [] {
    std::vector<SceneText> list;
    for (const std::string& name : nephele::preset_names())
      list.push_back({nephele::scene_to_toml(nephele::load_preset(name)),
                      "scene_to_toml(load_preset(\"" + name + "\"))"});
    for (const std::string& name : nephele::preset_names())
      list.push_back({"preset = \"" + name + "\"\n", "preset = \"" + name + "\""});
    list.push_back({"", "the empty file"});
    return list;
  }();
  return bases;
}

// A scene file being mutated line by line, with a log of the steps.
class SceneDraft {
 public:
  SceneDraft(const SceneText& base) : lines_(split_lines(base.text)), recipe_(base.recipe) {}

  struct KeyLine {
    size_t index;
    std::string section, key;
  };

  // Every `key = value` line with its table.
  std::vector<KeyLine> key_lines() const {
    std::vector<KeyLine> keys;
    std::string section;
    for (size_t i = 0; i < lines_.size(); ++i) {
      const std::string& line = lines_[i];
      if (line.starts_with("[")) {
        size_t end = line.find(']');
        section = end == std::string::npos ? "" : line.substr(1, end - 1);
        continue;
      }
      const size_t eq = line.find(" = ");
      if (line.empty() || line[0] == '#' || eq == std::string::npos) continue;
      keys.push_back({i, section, line.substr(0, eq)});
    }
    return keys;
  }

  // Where a new key of `section` goes: after its header, which is added when missing.
  size_t insertion_point(const std::string& section) {
    if (section.empty()) return 0;
    for (size_t i = 0; i < lines_.size(); ++i)
      if (lines_[i] == "[" + section + "]") return i + 1;
    lines_.push_back("[" + section + "]");
    return lines_.size();
  }

  // Sets `key` of `section` to `value`, replacing its line or adding one.
  void set(const std::string& section, const std::string& key, const std::string& value) {
    for (const KeyLine& k : key_lines())
      if (k.section == section && k.key == key) {
        lines_[k.index] = key + " = " + value;
        return note(section, key + " = " + value);
      }
    lines_.insert(lines_.begin() + long(insertion_point(section)), key + " = " + value);
    note(section, key + " = " + value + " (added)");
  }

  void note(const std::string& section, const std::string& step) {
    recipe_ += "; " + (section.empty() ? "" : "[" + section + "] ") + step;
  }

  std::vector<std::string>& lines() { return lines_; }
  std::string text() const { return join_lines(lines_); }
  const std::string& recipe() const { return recipe_; }

 private:
  std::vector<std::string> lines_;
  std::string recipe_;
};

// A section of the scene and one of its keys, at random (the keyframe tables as often as the
// rest, though they hold most of the keys).
std::pair<std::string, std::string> random_key(Rng& rng) {
  const auto& sections = scene_sections();
  const Section* section = nullptr;
  bool keyframes = rng.chance(0.3);
  while (!section || is_keyframe_table(section->name) != keyframes ||
         (section->fields.empty() && section->extra_keys.empty()))
    section = &sections[rng.below(sections.size())];
  std::vector<std::string> keys;
  for (const Field& f : section->fields) keys.emplace_back(f.name);
  for (std::string_view extra : section->extra_keys) keys.emplace_back(extra);
  return {std::string(section->name), rng.pick(keys)};
}

// Replaces the value of a key line with one of its type (mostly) or of any type.
void mutate_value(Rng& rng, SceneDraft& draft) {
  std::vector<SceneDraft::KeyLine> keys = draft.key_lines();
  if (keys.empty()) {
    auto [section, key] = random_key(rng);
    return draft.set(section, key,
                     rng.chance(0.8) ? typed_value(rng, kind_of(section, key)) : any_value(rng));
  }
  // Half the time a key outside the keyframe tables, which hold most of the lines.
  std::vector<SceneDraft::KeyLine> plain;
  for (const auto& k : keys)
    if (!is_keyframe_table(k.section)) plain.push_back(k);
  const auto& k = rng.chance(0.5) && !plain.empty() ? rng.pick(plain) : rng.pick(keys);
  const std::string value =
      rng.chance(0.8) ? typed_value(rng, kind_of(k.section, k.key)) : any_value(rng);
  draft.lines()[k.index] = k.key + " = " + value;
  draft.note(k.section, k.key + " = " +
                            (value.size() > 80 ? value.substr(0, 40) + "... (" +
                                                     std::to_string(value.size()) + " chars)"
                                               : value));
}

// Adds a known key (perhaps one the file has already, or one the table does not take).
void add_known_key(Rng& rng, SceneDraft& draft) {
  auto [section, key] = random_key(rng);
  const std::string value =
      rng.chance(0.8) ? typed_value(rng, kind_of(section, key)) : any_value(rng);
  const size_t at = draft.insertion_point(section);
  draft.lines().insert(draft.lines().begin() + long(at), key + " = " + value);
  draft.note(section, key + " = " + value + " (inserted)");
}

// Adds an unknown key: a typo, odd spellings, a 500-character name.
void add_unknown_key(Rng& rng, SceneDraft& draft) {
  // clang-format off
  const std::vector<std::string> names = {
      "covrage", "x", "Coverage", "\"quoted key\"", "\"\"", "a-b", "_", "1234",
      std::string(500, 'k'), "clouds", "\"\\u00e9\"", "camera.position_m.x"};
  // clang-format on
  auto [section, unused] = random_key(rng);
  if (rng.chance(0.3)) section = "";
  const std::string key = rng.pick(names);
  const size_t at = draft.insertion_point(section);
  draft.lines().insert(draft.lines().begin() + long(at), key + " = " + toml_number(rng));
  draft.note(section, "unknown key " + (key.size() > 40 ? key.substr(0, 10) + "... (" +
                                                              std::to_string(key.size()) + " chars)"
                                                        : key));
}

// Adds a dotted key a.a.a... of up to kMaxRandomDottedDepth levels.
void add_dotted_key(Rng& rng, SceneDraft& draft) {
  const int depth = rng.between(2, kMaxRandomDottedDepth);
  std::string key = "a";
  for (int i = 1; i < depth; ++i) key += ".a";
  const std::string section = rng.chance(0.5) ? "" : random_key(rng).first;
  const size_t at = draft.insertion_point(section);
  draft.lines().insert(draft.lines().begin() + long(at), key + " = 1");
  draft.note(section, "dotted key a.a.a... of " + std::to_string(depth) + " levels = 1");
}

// Breaks the structure: a duplicated or deleted line, a renamed or malformed table header.
void mutate_structure(Rng& rng, SceneDraft& draft) {
  std::vector<std::string>& lines = draft.lines();
  if (lines.empty()) return add_unknown_key(rng, draft);
  const size_t i = rng.below(lines.size());
  if (rng.chance(0.35)) {
    lines.insert(lines.begin() + long(i), lines[i]);
    return draft.note("", "line " + std::to_string(i + 1) + " duplicated");
  }
  if (rng.chance(0.35)) {
    draft.note("", "line " + std::to_string(i + 1) + " deleted: " + lines[i].substr(0, 60));
    lines.erase(lines.begin() + long(i));
    return;
  }
  std::vector<size_t> headers;
  for (size_t j = 0; j < lines.size(); ++j)
    if (lines[j].starts_with("[")) headers.push_back(j);
  if (headers.empty()) return add_unknown_key(rng, draft);
  const size_t h = rng.pick(headers);
  const std::string name = lines[h].substr(1, lines[h].find(']') - 1);
  const std::string header = rng.pick(std::vector<std::string>{
      "[[" + name + "]]", "[" + name + ".extra]", "[" + std::string(random_key(rng).first) + "]",
      "[ " + name + " ]", "[" + name, "[]", "[conditions.good.night.deeper]", "[\"" + name + "\"]",
      "[" + name + "] junk"});
  draft.note("", "header " + lines[h] + " -> " + header);
  lines[h] = header;
}

// Turns the keyframes on: the conditions mode and an hour, so their values matter.
void conditions_on(Rng& rng, SceneDraft& draft) {
  draft.set("conditions", "mode", quoted(rng.chance(0.5) ? "artist" : "overlay"));
  draft.set("conditions", "hour",
            rng.chance(0.8) ? std::to_string(rng.between(0, 23)) + ".5" : toml_number(rng));
}

// Byte-level damage to the whole text: cut at a random byte, random bytes spliced in, nothing
// but random bytes, or a NUL, a byte-order mark, CRLF line ends or invalid UTF-8 put in.
void damage_bytes(Rng& rng, std::string& text, std::string& recipe) {
  auto offset = [&](size_t past_end) {
    return text.empty() ? 0 : rng.below(text.size() + past_end);
  };
  auto truncate = [&] {
    text.resize(offset(0));
    recipe += "; truncated to " + std::to_string(text.size()) + " bytes";
  };
  auto splice = [&] {
    const size_t at = offset(1);
    std::string bytes;
    for (int i = rng.between(1, 16); i > 0; --i) bytes += char(rng.byte());
    text.insert(at, bytes);
    recipe += "; " + std::to_string(bytes.size()) + " random bytes inserted at byte " +
              std::to_string(at);
  };
  auto replace = [&] {
    text.clear();
    for (int i = rng.between(0, 4000); i > 0; --i) text += char(rng.byte());
    recipe = "random bytes (" + std::to_string(text.size()) + ")";
  };
  auto odd_bytes = [&] {
    const size_t at = offset(1);
    const std::vector<std::string> odd = {std::string(1, '\0'), "\xEF\xBB\xBF", "\r\n",
                                          "\xC3\x28",           "\xFF\xFE",     "\xED\xA0\x80"};
    const std::string what = rng.pick(odd);
    text.insert(at, what);
    recipe += "; bytes " + printable(what) + " inserted at byte " + std::to_string(at);
  };
  do_one_of(rng, {{4, truncate}, {3, splice}, {2, replace}, {1, odd_bytes}});
}

// Scene file case `index`: a base text with 1 to 3 mutations, sometimes byte-level damage.
SceneText make_scene_text(uint32_t index) {
  Rng rng(kSeed + kSceneStream + index);
  const auto& bases = scene_bases();
  const size_t presets = nephele::preset_names().size();
  const double roll = rng.unit();
  const SceneText& base = roll < 0.7   ? bases[rng.below(presets)]            // in full
                          : roll < 0.9 ? bases[presets + rng.below(presets)]  // by name
                                       : bases.back();                        // empty
  SceneDraft draft(base);
  for (int steps = rng.between(1, 3); steps > 0; --steps)
    do_one_of(rng,
              {
                  {40, [&] { mutate_value(rng, draft); }},
                  {10, [&] { add_known_key(rng, draft); }},
                  {6, [&] { add_unknown_key(rng, draft); }},
                  {3, [&] { add_dotted_key(rng, draft); }},
                  {8, [&] { mutate_structure(rng, draft); }},
                  {6, [&] { draft.set("", "time", typed_value(rng, Kind::Time)); }},
                  {5, [&] { draft.set("clouds", "weather_map", typed_value(rng, Kind::Path)); }},
                  {3, [&] { draft.set("", "preset", typed_value(rng, Kind::Preset)); }},
                  {5, [&] { conditions_on(rng, draft); }},
              });
  SceneText result{draft.text(), draft.recipe()};
  if (rng.chance(0.12)) damage_bytes(rng, result.text, result.recipe);
  return result;
}

// --- checking inputs in-process ---------------------------------------------------------------

struct Outcome {
  enum Verdict { kRejected, kAccepted, kBroken } verdict = kBroken;
  std::string symptom;  // kBroken: what went wrong, for grouping
  std::string detail;   // the error message, or the particulars of what went wrong
  Scene scene;          // kAccepted: the scene
  // Rejected by CLI11 (a CLI::ParseError), whose message only the CLI prints (and tidies):
  // a message that breaks the one-line rule here is judged again on a real process.
  bool cli11 = false;
};

Outcome rejected(const std::string& message) {
  const std::string problem = error_line_problem(message);
  if (!problem.empty()) return {Outcome::kBroken, problem, kErrorPrefix + message, {}};
  return {Outcome::kRejected, "", message, {}};
}

// Runs `fn`, which yields a scene, and sorts what happens into the contract's outcomes.
Outcome check(const std::function<Scene()>& fn) {
  try {
    Outcome accepted{Outcome::kAccepted, "", "", fn()};
    return accepted;
  } catch (const nephele::InputError& e) {
    return rejected(e.what());
  } catch (const CLI::ParseError& e) {  // main prints these as "nephele: error: ..." too
    Outcome outcome = rejected(std::string(e.what()) + " (see nephele --help)");
    outcome.cli11 = true;
    return outcome;
  } catch (const std::exception& e) {
    return {Outcome::kBroken, "threw " + demangled_type(e), e.what(), {}};
  } catch (...) {
    return {Outcome::kBroken, "threw something that is not a std::exception", "", {}};
  }
}

Outcome check_scene_text(const std::string& text) {
  return check([&] {
    Scene scene = nephele::parse_scene_toml(text, "fuzz.toml");
    nephele::validate_scene(scene);
    return scene;
  });
}

struct SceneFileCase {
  uint32_t index;
  SceneText input;
  Outcome outcome;
};

// Every scene file case, generated and checked once per process.
const std::vector<SceneFileCase>& scene_file_cases() {
  static const std::vector<SceneFileCase> cases = [] {
    std::vector<SceneFileCase> list;
    for (uint32_t i = 0; i < kSceneFileCases; ++i) {
      SceneText input = make_scene_text(i);
      Outcome outcome = check_scene_text(input.text);
      list.push_back({i, std::move(input), std::move(outcome)});
    }
    return list;
  }();
  return cases;
}

// What reproduces a scene file case: its recipe and the file it is saved to.
std::string scene_input(const fs::path& dir, const std::string& name, const SceneText& input) {
  const fs::path file = dir / (name + ".toml");
  write_file(file, input.text);
  std::string text = "made as: " + input.recipe + "\nsaved as: " + file.string();
  if (input.text.size() <= 600) text += "\n" + input.text;
  return text;
}

// --- command lines: generation ----------------------------------------------------------------

struct Flag {
  std::string name;  // "--coverage"
  std::string type;  // its value as --help shows it: "C", "E,N,U", "FILE", "off|artist|overlay"
};

// The options of `nephele render` that fuzzing sets: all but those choosing where the output
// goes and how the run reports (the harness sets those), and --voxel-cloud: the renderer draws
// no voxel clouds yet, and an accepted one (a generated cloud) would make every sampled render
// generate a grid. Its specs are tested in scene_flags_test; the voxel_clouds keys of scene
// files are not in the field table these tests draw keys from either.
const std::vector<Flag>& render_flags() {
  static const std::vector<Flag> flags = [] {
    CLI::App app;
    nephele::cli::RenderOptions options;
    nephele::cli::add_render_flags(app, options);
    const std::set<std::string> harness = {"--help",    "--output",     "--stats-json", "--device",
                                           "--verbose", "--validation", "--voxel-cloud"};
    std::vector<Flag> list;
    for (const CLI::Option* option : app.get_options()) {
      if (option->get_lnames().empty()) continue;
      const std::string name = "--" + option->get_lnames().front();
      if (!harness.count(name)) list.push_back({name, option->get_type_name()});
    }
    return list;
  }();
  return flags;
}

// Numbers as typed on a command line: as kTomlNumbers, and what from_chars and CLI11 may trip
// on (spaces, a leading '+', "1.", hexadecimal, nothing, words, a lone '-').
// clang-format off
const std::vector<std::string> kFlagNumbers = {
    "nan",   "-nan",  "NaN",  "inf",   "-inf",         "infinity", "0",     "-0",     "0.0",
    "-1",    "-1.5",  "0.5",  "1",     "2",            "1e9",      "1e20",  "1e30",   "-1e30",
    "1e38",  "3e38",  "-3e38", "3.4028235e38", "3.5e38", "1e39",   "1e300", "1e400",  "1e-25",
    "1e-30", "1e-45", "1e-46", "1e-400", "5e-324",     "+1",       " 1",    "1 ",     "1.",
    ".5",    "0x10",  "1e",   "",      "abc",          "1,2",      "--",    "-",      "0.99999994",
    "1.0000001"};
// clang-format on

// Integers as typed: past int and uint32, and not quite integers.
// clang-format off
const std::vector<std::string> kFlagIntegers = {
    "0",          "-1",         "1",          "2",          "4",   "16",  "1024", "1025",
    "16385",      "2147483647", "2147483648", "-2147483649", "4294967295", "4294967296",
    "99999999999999999999", "1.5", "1e3", "+5", "-0", "0x10", " 5", "abc", ""};
// clang-format on

std::string flag_number(Rng& rng) {
  return rng.chance(0.15) ? random_magnitude(rng) : rng.pick(kFlagNumbers);
}

// "E,N,U": edge components, sometimes the wrong count or separators.
std::string flag_vector(Rng& rng, size_t size) {
  if (rng.chance(0.15))
    return rng.pick(std::vector<std::string>{"0,0,0", "1e-25,0,0", "1e30,0,2", "nan,0,1", ",,",
                                             "1;2;3", "1 2 3", "0,0", "1,2,3,4", ""});
  size_t n = rng.chance(0.1) ? rng.pick(std::vector<size_t>{1, size - 1, size + 1}) : size;
  std::string text;
  for (size_t i = 0; i < n; ++i)
    text +=
        (i ? "," : "") + (rng.chance(0.5) ? rng.pick(std::vector<std::string>{"0", "1", "2", "0.3"})
                                          : flag_number(rng));
  return text;
}

// A value for `flag`, by the type its help shows.
std::string flag_value(Rng& rng, const Flag& flag, bool for_process) {
  const std::string& t = flag.type;
  if (rng.chance(0.05))  // anything at all
    return rng.pick(std::vector<std::string>{"", "-", "--", "=", "\t", std::string(1000, '9'),
                                             "\xC3\xA9", "1\n2", "true"});
  if (t == "E,N,U") return flag_vector(rng, 3);
  if (t == "E,N") return flag_vector(rng, 2);
  if (flag.name == "--frames")  // a process renders what it accepts: few frames
    return for_process ? rng.pick(std::vector<std::string>{"0", "-1", "1", "2", "3", "100001",
                                                           "abc", "1.5"})
                       : rng.pick(kFlagIntegers);
  if (t == "N" || t == "INT" || t == "KM") return rng.pick(kFlagIntegers);
  if (t == "ISO8601") return rng.pick(kDates);
  if (t == "NAME") {
    std::vector<std::string> names = nephele::preset_names();
    names.insert(names.end(), {"nosuch", "", "Default", "../default", "default.toml"});
    return rng.pick(names);
  }
  if (t == "FILE")
    return rng.pick(flag.name == "--scene" ? fixtures().scene_paths : fixtures().weather_paths);
  if (t.find('|') != std::string::npos) {
    std::vector<std::string> choices = {"", "DEFAULT", "x", "1"};
    for (size_t start = 0, bar; start <= t.size(); start = bar + 1) {
      bar = t.find('|', start);
      if (bar == std::string::npos) bar = t.size();
      choices.push_back(t.substr(start, bar - start));
      choices.push_back(t.substr(start, bar - start));  // the valid ones twice as often
    }
    return rng.pick(choices);
  }
  return flag_number(rng);
}

// A `nephele render` command line (the words after `render`): --preset or --scene or neither,
// then 1 to 4 flags of the table with values of their type, now and then as --flag=value,
// repeated, unknown or missing its value. A command line for a process leaves --width and
// --height to the harness (it renders at 16x16).
std::vector<std::string> make_command_line(uint32_t seed, bool for_process) {
  Rng rng(seed);
  std::vector<std::string> args;
  const auto& flags = render_flags();
  auto find = [&](const std::string& name) {
    return *std::find_if(flags.begin(), flags.end(), [&](const Flag& f) { return f.name == name; });
  };
  const double base = rng.unit();
  if (base < 0.25)
    args = {"--preset", flag_value(rng, find("--preset"), for_process)};
  else if (base < 0.35)
    args = {"--scene", flag_value(rng, find("--scene"), for_process)};
  for (int n = rng.between(1, 4); n > 0; --n) {
    const Flag* flag = &rng.pick(flags);
    while (for_process && (flag->name == "--width" || flag->name == "--height"))
      flag = &rng.pick(flags);
    const std::string value = flag_value(rng, *flag, for_process);
    const std::vector<std::string> unknown = {"--coverag", "-x", "--", "extra", "--Coverage"};
    auto plain = [&] { args.insert(args.end(), {flag->name, value}); };
    auto joined = [&] { args.push_back(flag->name + "=" + value); };
    auto twice = [&] { args.insert(args.end(), {flag->name, value, flag->name, value}); };
    auto stray = [&] { args.insert(args.end(), {rng.pick(unknown), value}); };
    auto no_value = [&] { args.push_back(flag->name); };  // or the next flag taken for it
    do_one_of(rng, {{85, plain}, {5, joined}, {3, twice}, {4, stray}, {3, no_value}});
  }
  return args;
}

// Parses `args` as `nephele render ARGS` does (CLI11, the same flags) and resolves the scene.
Scene resolve_command_line(const std::vector<std::string>& args) {
  CLI::App app("nephele");
  nephele::cli::RenderOptions options;
  CLI::App* render = app.add_subcommand("render", "");
  nephele::cli::add_render_flags(*render, options);
  std::vector<const char*> argv = {"nephele", "render"};
  for (const std::string& arg : args) argv.push_back(arg.c_str());
  app.parse(int(argv.size()), argv.data());
  return nephele::cli::resolve_scene(options.scene);
}

struct CommandLineCase {
  uint32_t index;
  std::vector<std::string> args;
  Outcome outcome;
};

// Every in-process command line case, generated and checked once per process.
const std::vector<CommandLineCase>& command_line_cases() {
  static const std::vector<CommandLineCase> cases = [] {
    std::vector<CommandLineCase> list;
    for (uint32_t i = 0; i < kCommandLineCases; ++i) {
      std::vector<std::string> args = make_command_line(kSeed + kCommandStream + i, false);
      Outcome outcome = check([&] { return resolve_command_line(args); });
      list.push_back({i, std::move(args), std::move(outcome)});
    }
    return list;
  }();
  return cases;
}

std::string render_command(const std::vector<std::string>& args) {
  return "nephele render " + shell_quote(args);
}

// --- child processes --------------------------------------------------------------------------

// Lines from a pipe, each within a time limit.
class LineReader {
 public:
  explicit LineReader(int fd) : fd_(fd) {}
  ~LineReader() { close(fd_); }
  enum Status { kLine, kEnd, kTimeout };

  Status next(std::string& line, int timeout_s) {
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeout_s);
    for (;;) {
      const size_t newline = buffer_.find('\n');
      if (newline != std::string::npos) {
        line = buffer_.substr(0, newline);
        buffer_.erase(0, newline + 1);
        return kLine;
      }
      const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(
          deadline - std::chrono::steady_clock::now());
      if (left.count() <= 0) return kTimeout;
      pollfd p{fd_, POLLIN, 0};
      const int ready = poll(&p, 1, int(left.count()));
      if (ready < 0 && errno == EINTR) continue;
      if (ready == 0) return kTimeout;
      char chunk[4096];
      const ssize_t n = read(fd_, chunk, sizeof chunk);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) return kEnd;
      buffer_.append(chunk, size_t(n));
    }
  }

 private:
  int fd_;
  std::string buffer_;
};

// A line for the pipe: newlines made visible.
std::string one_line(std::string text) {
  for (char& c : text)
    if (c == '\n') c = '|';
  return text;
}

size_t address_space_in_use() {
  std::ifstream statm("/proc/self/statm");
  size_t pages = 0;
  statm >> pages;
  return pages * size_t(sysconf(_SC_PAGESIZE));
}

// This process's resident memory (VmRSS) and its peak (VmHWM), in bytes.
size_t resident_memory(const char* field = "VmRSS:") {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.starts_with(field)) return size_t(std::stoull(line.substr(std::strlen(field)))) * 1024;
  return 0;
}

// What a child process reports: "" when its input kept the contract, else the symptom.
struct ChildResult {
  std::string symptom, detail;
};

// Runs `fn` in a child process within `timeout_s` and `extra_memory` bytes of address space
// beyond what this process has. `fn` returns "" when the contract held, else
// "SYMPTOM\tDETAIL". A child whose memory grows by more than kChildMemoryGrowth (reading a
// file without bound: a stringbuf stops quietly at the limit) fails too, as does one that
// crashes or hangs.
constexpr size_t kChildMemoryGrowth = size_t(256) << 20;
ChildResult run_in_child(const std::function<std::string()>& fn, int timeout_s,
                         size_t extra_memory) {
  int fds[2];
  if (pipe(fds) != 0) return {"cannot create a pipe", ""};
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const rlim_t limit = address_space_in_use() + extra_memory;
    const rlimit memory{limit, limit};
    setrlimit(RLIMIT_AS, &memory);
    reset_peak_memory();
    const size_t before = resident_memory();
    std::string result;
    try {
      result = fn();
    } catch (const std::exception& e) {
      result = "threw " + demangled_type(e) + "\t" + e.what();
    }
    const size_t peak = resident_memory("VmHWM:");
    const size_t growth = peak > before ? peak - before : 0;
    if (result.empty() && growth > kChildMemoryGrowth)
      result = "used more than " + std::to_string(kChildMemoryGrowth >> 20) +
               " MiB of memory (reads without bound?)\t" + std::to_string(growth >> 20) +
               " MiB more at its peak, with a limit of " + std::to_string(extra_memory >> 20) +
               " MiB";
    write_all(fds[1], one_line(result) + "\n");
    _exit(0);
  }
  close(fds[1]);
  LineReader reader(fds[0]);
  std::string line;
  const LineReader::Status status = reader.next(line, timeout_s);
  if (status == LineReader::kTimeout) kill(pid, SIGKILL);
  int wait_status = 0;
  waitpid(pid, &wait_status, 0);
  if (status == LineReader::kTimeout)
    return {"hung: no result within " + std::to_string(timeout_s) + " s", ""};
  if (status == LineReader::kEnd) return {describe_death(wait_status), ""};
  const size_t tab = line.find('\t');
  if (tab == std::string::npos) return {line, ""};
  return {line.substr(0, tab), line.substr(tab + 1)};
}

// The child's report of an Outcome: "" when the contract held.
std::string child_report(const Outcome& outcome) {
  return outcome.verdict == Outcome::kBroken ? outcome.symptom + "\t" + outcome.detail : "";
}

// --- rendering in child processes -------------------------------------------------------------

struct RenderJob {
  std::string label;  // "scene file case #12", "edge clouds.ambient_strength = 3e38"
  std::string input;  // what reproduces it
  Scene scene;
  bool light_volume = false;  // keep the scene's light volume (else light_volume_km = 0)
};

// Renders a job at 16x16 and writes it as the CLI does, to `exr` (half floats), and reads it
// back: "ok", "rejected MESSAGE" (an InputError at render time, e.g. a weather map that is no
// image) or "fail SYMPTOM\tDETAIL".
std::string render_one(nephele::Renderer& renderer, const RenderJob& job, const std::string& exr) {
  Scene scene = job.scene;
  scene.output.width = scene.output.height = kRenderSize;
  if (!job.light_volume) scene.quality.light_volume_km = 0;
  const int messages_before = renderer.validation_messages();
  try {
    const nephele::Frame frame = renderer.render(scene);
    const int messages = renderer.validation_messages() - messages_before;
    if (messages > 0)
      return "fail Vulkan validation messages\t" + std::to_string(messages) + " (printed above)";
    if (frame.color.width != kRenderSize || frame.color.height != kRenderSize)
      return "fail image of the wrong size\t" + std::to_string(frame.color.width) + "x" +
             std::to_string(frame.color.height);
    std::string first;
    const size_t bad = count_non_finite(frame.color, first);
    if (bad > 0)
      return "fail non-finite pixels in the HDR image\t" + std::to_string(bad) + " of " +
             std::to_string(frame.color.pixels.size()) + " pixels, first " + first;
    nephele::write_image(frame.color, exr);
    const size_t bad_in_file = count_non_finite(nephele::read_image(exr), first);
    if (bad_in_file > 0)
      return "fail non-finite pixels in the image written as EXR (half floats)\t" +
             std::to_string(bad_in_file) + " of " + std::to_string(frame.color.pixels.size()) +
             " pixels, first " + first;
    return "ok";
  } catch (const nephele::InputError& e) {
    const std::string problem = error_line_problem(e.what());
    if (!problem.empty()) return "fail " + problem + "\t" + one_line(e.what());
    return "rejected " + one_line(e.what());
  } catch (const std::exception& e) {
    return "fail threw " + demangled_type(e) + "\t" + one_line(e.what());
  }
}

// A child's loop: one Renderer (validation layer on), then for each job from `first` on a
// line "start I" and a line "I RESULT". Images are written into `scratch`.
[[noreturn]] void render_worker(const std::vector<RenderJob>& jobs, size_t first, int fd,
                                const fs::path& scratch) {
  const std::string exr = (scratch / ("render_" + std::to_string(getpid()) + ".exr")).string();
  try {
    nephele::RendererOptions options;
    options.validation = true;
    nephele::Renderer renderer(options);
    for (size_t i = first; i < jobs.size(); ++i) {
      write_all(fd, "start " + std::to_string(i) + "\n");
      write_all(fd, std::to_string(i) + " " + render_one(renderer, jobs[i], exr) + "\n");
    }
  } catch (const std::exception& e) {
    write_all(fd, "fatal " + one_line(e.what()) + "\n");
  }
  _exit(0);  // no destructors, no atexit handlers: they belong to the parent
}

struct RenderResult {
  bool ok = false;
  std::string symptom, detail;  // when not ok
  bool rejected = false;        // an InputError at render time
};

// Renders the jobs in child processes, so that a crash or a hang costs one job, not the test
// binary: when a child dies or a job runs past kRenderTimeoutS, that job is marked so and a new
// child takes up the next.
std::vector<RenderResult> render_in_children(const std::vector<RenderJob>& jobs,
                                             const fs::path& scratch) {
  std::vector<RenderResult> results(jobs.size());
  size_t next = 0;
  while (next < jobs.size()) {
    int fds[2];
    if (pipe(fds) != 0) throw std::runtime_error("pipe failed");
    std::fflush(nullptr);
    const pid_t pid = fork();
    if (pid == 0) {
      close(fds[0]);
      render_worker(jobs, next, fds[1], scratch);
    }
    close(fds[1]);
    LineReader reader(fds[0]);
    std::optional<size_t> in_flight;
    std::string line;
    for (;;) {
      const LineReader::Status status = reader.next(line, kRenderTimeoutS);
      if (status == LineReader::kLine) {
        std::istringstream in(line);
        std::string head, word;
        in >> head;
        if (head == "start") {
          in_flight = std::stoul(line.substr(6));
          continue;
        }
        if (head == "fatal") {  // no Renderer: every job left fails alike
          for (; next < jobs.size(); ++next)
            results[next] = {false, "cannot create a Renderer", line.substr(6)};
          continue;
        }
        const size_t i = std::stoul(head);
        in >> word;
        std::string rest;
        std::getline(in, rest);
        if (!rest.empty() && rest[0] == ' ') rest.erase(0, 1);
        if (word == "ok") {
          results[i] = {true, "", ""};
        } else if (word == "rejected") {
          results[i] = {true, "", rest, true};
        } else {
          const size_t tab = rest.find('\t');
          results[i] = {false, rest.substr(0, tab),
                        tab == std::string::npos ? "" : rest.substr(tab + 1)};
        }
        next = i + 1;
        in_flight.reset();
        continue;
      }
      if (status == LineReader::kTimeout) kill(pid, SIGKILL);
      int wait_status = 0;
      waitpid(pid, &wait_status, 0);
      // The job it was on (or about to start) dies with it; none when it finished them all.
      if (const size_t i = in_flight.value_or(next); i < jobs.size()) {
        results[i] = {false,
                      status == LineReader::kTimeout
                          ? "hung: no result within " + std::to_string(kRenderTimeoutS) + " s"
                          : describe_death(wait_status),
                      in_flight ? "while rendering" : "while starting the Renderer"};
        next = i + 1;
      }
      break;
    }
  }
  return results;
}

// --- `nephele render` processes ---------------------------------------------------------------

struct ProcessRun {
  int status = 0;         // from waitpid
  size_t peak_bytes = 0;  // the largest resident memory of the process
  std::string out, err;
};

// Runs NEPHELE_CLI_PATH render ARGS under `timeout`, with kProcessMemoryBytes of address space,
// stdout and stderr captured in files in `capture`.
ProcessRun run_cli(const std::vector<std::string>& args, const fs::path& capture) {
  std::vector<std::string> words = {
      "timeout", "-k", "5", std::to_string(kProcessTimeoutS), NEPHELE_CLI_PATH, "render"};
  words.insert(words.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  argv.push_back(nullptr);
  const std::string out_path = (capture / "stdout").string(),
                    err_path = (capture / "stderr").string();
  const int out = open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  const int err = open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  std::fflush(nullptr);
  const pid_t pid = fork();
  if (pid == 0) {
#ifndef __SANITIZE_ADDRESS__  // ASan reserves terabytes of address space for its shadow
    const rlimit memory{kProcessMemoryBytes, kProcessMemoryBytes};
    setrlimit(RLIMIT_AS, &memory);
#endif
    dup2(out, 1);
    dup2(err, 2);
    execvp("timeout", argv.data());
    _exit(127);
  }
  close(out);
  close(err);
  ProcessRun run;
  rusage usage{};
  wait4(pid, &run.status, 0, &usage);  // `timeout` and, waited for by it, the CLI
  run.peak_bytes = size_t(usage.ru_maxrss) * 1024;
  auto slurp = [](const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  };
  run.out = slurp(out_path);
  run.err = slurp(err_path);
  return run;
}

// Runs `nephele render OPTIONS ARGS` in a fresh, empty output folder and checks the contract;
// returns "rejected", "accepted" or "failed". OPTIONS, before ARGS (which may hold a "--"):
// the validation layer, -o and --stats-json inside the folder, 16x16 and no light volume
// unless ARGS set them.
std::string check_cli(const std::string& label, const std::vector<std::string>& args,
                      const fs::path& dir, FailureLog& failures) {
  const fs::path out = dir / "out";
  fs::create_directories(out);
  std::vector<std::string> words = {"--validation", "-o", (out / "x.exr").string(), "--stats-json",
                                    (out / "x.json").string()};
  auto absent = [&](const char* flag) {
    return std::find(args.begin(), args.end(), flag) == args.end();
  };
  if (absent("--width") && absent("--height"))
    words.insert(words.end(), {"--width", "16", "--height", "16"});
  if (absent("--light-volume-km")) words.insert(words.end(), {"--light-volume-km", "0"});
  words.insert(words.end(), args.begin(), args.end());
  const ProcessRun run = run_cli(words, dir);
  const std::string input = render_command(words);
  std::vector<std::string> written;
  for (const auto& entry : fs::directory_iterator(out))
    written.push_back(entry.path().filename().string());
  std::sort(written.begin(), written.end());
  const std::string err_tail =
      printable(run.err.size() > 1500 ? "..." + run.err.substr(run.err.size() - 1500) : run.err);
  auto fail = [&](const std::string& symptom, const std::string& detail) {
    failures.add(symptom, label, detail, input);
    return std::string("failed");
  };

  if (run.peak_bytes > kProcessMemoryUse)
    fail("used more than " + std::to_string(kProcessMemoryUse >> 20) +
             " MiB of memory (reads without bound?)",
         std::to_string(run.peak_bytes >> 20) + " MiB at its peak; stderr: " + err_tail);
  if (WIFSIGNALED(run.status)) return fail(describe_death(run.status), "stderr: " + err_tail);
  const int code = WEXITSTATUS(run.status);
  if (code == 124 || code == 137)
    return fail("hung: killed after " + std::to_string(kProcessTimeoutS) + " s",
                "stderr: " + err_tail);
  if (code == 2) {
    std::vector<std::string> lines = split_lines(run.err);
    std::string why;
    if (lines.size() != 1)
      why = "stderr has " + std::to_string(lines.size()) + " lines, not 1";
    else if (!lines[0].starts_with(kErrorPrefix))
      why = "stderr does not start with '" + kErrorPrefix + "'";
    else if (lines[0].size() > kMaxErrorLineChars)
      why = "error line is longer than " + std::to_string(kMaxErrorLineChars) + " characters";
    std::string result = "rejected";
    if (!why.empty()) result = fail("rejected (exit 2), but " + why, "stderr: " + err_tail);
    if (!written.empty()) {
      std::string names;
      for (const std::string& name : written) names += " " + name;
      result =
          fail("rejected (exit 2), but wrote files", "wrote:" + names + "; stderr: " + err_tail);
    }
    return result;
  }
  if (code != 0) return fail("exit status " + std::to_string(code), "stderr: " + err_tail);
  size_t images = 0;
  std::string result = "accepted";
  for (const std::string& name : written) {
    if (!name.ends_with(".exr")) continue;
    ++images;
    try {
      const nephele::Image image = nephele::read_image((out / name).string());
      std::string first;
      const size_t bad = count_non_finite(image, first);
      if (bad > 0)
        result = fail("non-finite pixels in the HDR image",
                      name + ": " + std::to_string(bad) + " of " +
                          std::to_string(image.pixels.size()) + " pixels, first " + first);
    } catch (const std::exception& e) {
      result = fail("accepted, but its image cannot be read", name + ": " + e.what());
    }
  }
  if (images == 0) result = fail("exit 0 without an image", "stdout: " + printable(run.out));
  return result;
}

// --- edge scenes ------------------------------------------------------------------------------

// Scenes with one number at the edge of what validation accepts: for every number and vector key
// outside the keyframe tables, on the default preset, the largest accepted value (the top of
// its documented range, found by bisection) and 1e-45 (a vector gets the value in every
// component). (Negative ends found nothing more and would cost a third more renders.)
std::vector<RenderJob> edge_jobs() {
  std::vector<RenderJob> jobs;
  auto scene_text = [](const std::string& section, const std::string& key, size_t components,
                       double number) {
    char digits[32];
    std::snprintf(digits, sizeof digits, "%.9g", number);
    std::string value = digits;
    if (components > 1) {
      value = "[" + value;
      for (size_t i = 1; i < components; ++i) value += ", " + std::string(digits);
      value += "]";
    }
    // A classical model's parameter is rendered by its model (Nishita's on a small grid of few
    // metaballs: their light passes cost seconds at the default 96 voxels).
    std::string model, extra;
    for (const char* name : {"blinn", "gardner", "kajiya", "nishita"})
      if (section == "classic" && key.rfind(std::string(name) + "_", 0) == 0)
        model = "[clouds]\nmodel = \"" + std::string(name) + "\"\n";
    if (section == "classic" && key.rfind("nishita_", 0) == 0)
      extra = "nishita_voxels = 16\nnishita_metaballs = 16\n";
    return "preset = \"default\"\n" + model + (section.empty() ? "" : "[" + section + "]\n") +
           key + " = " + value + "\n" + extra;
  };
  auto try_value = [&](const std::string& section, const std::string& key, size_t components,
                       double number) {
    const std::string text = scene_text(section, key, components, number);
    Outcome outcome = check_scene_text(text);
    if (outcome.verdict != Outcome::kAccepted) return false;
    jobs.push_back({"edge " + text.substr(text.find('\n') + 1), "scene file:\n" + text,
                    outcome.scene});
    return true;
  };
  // The largest accepted value: from the first accepted of a few rising values, bisected in
  // log10 up to the first rejected one above it (3e38 when all are).
  auto largest_accepted = [&](const std::string& section, const std::string& key,
                              size_t components) -> std::optional<double> {
    auto accepted = [&](double v) {
      return check_scene_text(scene_text(section, key, components, v)).verdict ==
             Outcome::kAccepted;
    };
    if (accepted(3e38)) return 3e38;
    double lo = std::nan("");
    for (double v : {1e-45, 1e-6, 1.0, 1e3, 1e6})
      if (accepted(v)) lo = std::log10(v);
    if (std::isnan(lo)) return std::nullopt;
    double hi = std::log10(3e38);
    for (int i = 0; i < 48; ++i) {
      const double mid = 0.5 * (lo + hi);
      (accepted(std::pow(10.0, mid)) ? lo : hi) = mid;
    }
    return std::pow(10.0, lo);
  };
  for (const Section& section : scene_sections()) {
    if (is_keyframe_table(section.name)) continue;
    std::vector<std::pair<std::string, size_t>> keys;  // name, components
    for (const Field& field : section.fields) {
      const Kind kind = kind_of_field(field);
      if (kind == Kind::Float) keys.emplace_back(field.name, 1);
      if (kind == Kind::Vec2) keys.emplace_back(field.name, 2);
      if (kind == Kind::Vec3) keys.emplace_back(field.name, 3);
    }
    for (std::string_view extra : section.extra_keys)
      if (kind_of(section.name, extra) == Kind::Float) keys.emplace_back(extra, 1);
    for (const auto& [key, components] : keys) {
      const std::string s(section.name);
      if (const std::optional<double> top = largest_accepted(s, key, components))
        try_value(s, key, components, *top);
      try_value(s, key, components, 1e-45);
    }
  }
  return jobs;
}

// Command lines of the flags' edges that the known bugs showed, rendered in-process.
// clang-format off
const std::vector<std::vector<std::string>> kEdgeCommandLines = {
    {"--camera-pos", "1e30,0,2"}, {"--camera-altitude-m", "1e38"}, {"--sun-illuminance", "1e9"},
    {"--ambient", "1e9"},         {"--view-dir", "1e-25,0,0"},     {"--sun-dir", "1e-25,0,0"},
    {"--time", "2026-06-21T18:30:00Z", "--time-s", "3e38"}};
// clang-format on

}  // namespace

// --- the tests --------------------------------------------------------------------------------

// Thousands of scene files mutated from the presets and the table of scene keys, through
// parse_scene_toml and validate_scene: each is rejected with a one-line InputError or accepted.
TEST(FuzzTest, SceneFiles) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = test_folder();
  FailureLog failures;
  int accepted = 0, rejected = 0;
  for (const SceneFileCase& c : scene_file_cases()) {
    if (c.outcome.verdict == Outcome::kAccepted) ++accepted;
    if (c.outcome.verdict == Outcome::kRejected) ++rejected;
    if (c.outcome.verdict != Outcome::kBroken) continue;
    const std::string name = "scene_case_" + std::to_string(c.index);
    failures.add(c.outcome.symptom, "scene file case #" + std::to_string(c.index), c.outcome.detail,
                 scene_input(dir, name, c.input));
  }
  std::cout << "[ fuzz     ] " << kSceneFileCases << " scene files: " << rejected << " rejected, "
            << accepted << " accepted, " << failures.size() << " failed, in "
            << seconds_since(start) << " s\n";
  EXPECT_EQ(failures.size(), 0u) << failures.report();
}

// Scene files read from disk with load_scene_file: a directory, /dev/zero (endless), /dev/null,
// an empty file, one over 1 MiB, random bytes, a missing file, a path through a file. Each runs
// in a child with a time limit and a memory allowance, so that one that reads forever fails
// alone.
TEST(FuzzTest, SceneFilesOnDisk) {
  const Fixtures& f = fixtures();
  FailureLog failures;
  for (const std::string& path : {f.directory, std::string("/dev/zero"), std::string("/dev/null"),
                                  f.empty, f.big, f.binary, f.missing, f.scene + "/x", f.scene}) {
    const ChildResult result = run_in_child(
        [&] {
          return child_report(check([&] {
            Scene scene = nephele::load_scene_file(path);
            nephele::validate_scene(scene);
            return scene;
          }));
        },
        kFileReadTimeoutS, kFileReadMemoryBytes);
    if (!result.symptom.empty())
      failures.add(result.symptom, "load_scene_file(\"" + path + "\")", result.detail,
                   "nephele::load_scene_file(\"" + path + "\") then validate_scene");
  }
  EXPECT_EQ(failures.size(), 0u) << failures.report();
}

// A dotted key of 50,000 levels (a.a.a... = 1), kept out of the random cases because it
// overflowed the stack inside toml++: through parse_scene_toml in a child process, and through
// `nephele render --scene`.
TEST(FuzzTest, DeeplyNestedDottedKey) {
  const fs::path dir = test_folder();
  std::string key = "a";
  for (int i = 1; i < kKnownDeepDottedDepth; ++i) key += ".a";
  const std::string text = key + " = 1\n";
  const std::string file = (dir / "deep.toml").string();
  write_file(file, text);
  FailureLog failures;
  const ChildResult result = run_in_child([&] { return child_report(check_scene_text(text)); },
                                          kFileReadTimeoutS, kFileReadMemoryBytes);
  if (!result.symptom.empty())
    failures.add("parse_scene_toml: " + result.symptom, "in-process", result.detail,
                 "nephele::parse_scene_toml of " + file + " (a.a.a... of " +
                     std::to_string(kKnownDeepDottedDepth) + " levels = 1)");
  fs::create_directories(dir / "cli");
  check_cli("nephele render --scene deep.toml", {"--scene", file}, dir / "cli", failures);
  EXPECT_EQ(failures.size(), 0u) << failures.report();
}

// Thousands of `nephele render` command lines, parsed by CLI11 with the CLI's own flags and
// resolved by resolve_scene: each is rejected with one error line or gives a valid scene.
// (--frames and --step are parsed here but checked only by the processes below.)
TEST(FuzzTest, CommandLines) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = test_folder();
  FailureLog failures;
  int accepted = 0, rejected = 0, processes = 0;
  for (const CommandLineCase& c : command_line_cases()) {
    if (c.outcome.verdict == Outcome::kAccepted) ++accepted;
    if (c.outcome.verdict == Outcome::kRejected) ++rejected;
    if (c.outcome.verdict != Outcome::kBroken) continue;
    const std::string label = "command line #" + std::to_string(c.index);
    if (!c.outcome.cli11) {
      failures.add(c.outcome.symptom, label, c.outcome.detail, render_command(c.args));
    } else if (processes < kCli11ProcessCases) {  // CLI11 rejects it: cheap as a process
      const fs::path case_dir = dir / ("case_" + std::to_string(c.index));
      fs::create_directories(case_dir);
      ++processes;
      check_cli(label + " (CLI11's error, as a process)", c.args, case_dir, failures);
    }
  }
  std::cout << "[ fuzz     ] " << kCommandLineCases << " command lines: " << rejected
            << " rejected, " << accepted << " accepted, " << failures.size() << " failed ("
            << processes << " run as processes), in " << seconds_since(start) << " s\n";
  EXPECT_EQ(failures.size(), 0u) << failures.report();
}

// Command lines run as `nephele render` processes, each in a fresh, empty folder: generated ones
// and a few whole-file and sequence cases (--scene /dev/zero, a directory, a file over 1 MiB,
// --frames 3 --step 3e38, a camera 1e30 m away). Exit 2 with one error line and nothing
// written, or exit 0 with finite images; anything else fails.
TEST(FuzzTest, CommandLineProcesses) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = test_folder();
  const Fixtures& f = fixtures();
  std::vector<std::pair<std::string, std::vector<std::string>>> cases = {
      {"fixed: --scene /dev/zero", {"--scene", "/dev/zero"}},
      {"fixed: --scene DIRECTORY", {"--scene", f.directory}},
      {"fixed: --scene BIG_FILE", {"--scene", f.big}},
      {"fixed: --frames 3 --step 3e38", {"--frames", "3", "--step", "3e38"}},
      {"fixed: --camera-pos 1e30,0,2", {"--camera-pos", "1e30,0,2"}},
  };
  for (uint32_t i = 0; i < kProcessCases; ++i)
    cases.push_back({"process case #" + std::to_string(i),
                     make_command_line(kSeed + kProcessStream + i, true)});
  FailureLog failures;
  std::map<std::string, int> tally;
  for (size_t i = 0; i < cases.size(); ++i) {
    const fs::path case_dir = dir / ("case_" + std::to_string(i));
    fs::create_directories(case_dir);
    ++tally[check_cli(cases[i].first, cases[i].second, case_dir, failures)];
  }
  std::cout << "[ fuzz     ] " << cases.size() << " processes: " << tally["rejected"]
            << " rejected, " << tally["accepted"] << " accepted, " << failures.size()
            << " failed, in " << seconds_since(start) << " s\n";
  EXPECT_EQ(failures.size(), 0u) << failures.report();
}

// Accepted scenes rendered in-process at 16x16 with one Renderer (validation layer on) per child
// process: the edge scenes (one number at its largest, most negative and smallest accepted
// value), the known bugs' command lines, and a deterministic sample of the accepted scene files
// and command lines above. Every pixel of the HDR image must be finite.
TEST(FuzzTest, AcceptedScenesRenderFinitePixels) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = test_folder();
  std::vector<RenderJob> jobs = edge_jobs();
  for (const auto& args : kEdgeCommandLines) {
    Outcome outcome = check([&] { return resolve_command_line(args); });
    if (outcome.verdict == Outcome::kAccepted)
      jobs.push_back({"edge " + shell_quote(args), render_command(args), outcome.scene});
  }
  const size_t edges = jobs.size();

  // The sample: two thirds scene files, one third command lines, in a seeded order.
  std::vector<const SceneFileCase*> files;
  for (const SceneFileCase& c : scene_file_cases())
    if (c.outcome.verdict == Outcome::kAccepted) files.push_back(&c);
  std::vector<const CommandLineCase*> lines;
  for (const CommandLineCase& c : command_line_cases())
    if (c.outcome.verdict == Outcome::kAccepted) lines.push_back(&c);
  Rng rng(kSeed + kSampleStream);
  std::shuffle(files.begin(), files.end(), rng.engine());
  std::shuffle(lines.begin(), lines.end(), rng.engine());
  const size_t from_files = std::min(files.size(), size_t(kRandomRenderCases) * 2 / 3);
  for (size_t i = 0; i < from_files; ++i) {
    const SceneFileCase& c = *files[i];
    jobs.push_back({"scene file case #" + std::to_string(c.index),
                    scene_input(dir, "scene_case_" + std::to_string(c.index), c.input),
                    c.outcome.scene});
  }
  for (size_t i = 0; i < lines.size() && jobs.size() < edges + kRandomRenderCases; ++i)
    jobs.push_back({"command line #" + std::to_string(lines[i]->index),
                    render_command(lines[i]->args), lines[i]->outcome.scene});
  for (size_t i = edges; i < jobs.size() && i < edges + kLightVolumeRenders; ++i)
    jobs[i].light_volume = true;
  for (RenderJob& job : jobs)
    if (!job.light_volume) job.label += " (light volume off)";
  // Noise textures are rebuilt when the seed changes: render each seed's scenes together.
  std::stable_sort(jobs.begin(), jobs.end(), [](const RenderJob& a, const RenderJob& b) {
    return a.scene.noise_seed < b.scene.noise_seed;
  });

  const std::vector<RenderResult> results = render_in_children(jobs, dir);
  FailureLog failures;
  int rejected = 0;
  for (size_t i = 0; i < jobs.size(); ++i) {
    if (results[i].rejected) ++rejected;
    if (!results[i].ok)
      failures.add(results[i].symptom, jobs[i].label, results[i].detail, jobs[i].input);
  }
  std::cout << "[ fuzz     ] " << jobs.size() << " renders (" << edges
            << " edge scenes): " << rejected << " rejected while rendering, " << failures.size()
            << " failed, in " << seconds_since(start) << " s\n";
  EXPECT_EQ(failures.size(), 0u) << failures.report();
}

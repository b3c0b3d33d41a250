// nephele — reading scene files and presets (TOML, via toml++).
#include "nephele/scene_io.h"

#include <toml++/toml.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <climits>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <span>
#include <sstream>

#include "nephele/camera_path.h"
#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele_embedded.h"
#include "scene/scene_fields.h"
#include "weather/grib.h"
#include "weather/metar_weather.h"
#include "weather/weather_state.h"

namespace nephele_presets {  // defined by the generated embedded_presets.cpp
extern const EmbeddedFile kFiles[];
extern const size_t kFileCount;
}  // namespace nephele_presets

namespace nephele {
namespace scene_detail {

// (kMaxKeyParts: nested arrays and inline tables are bounded by toml++ itself, at 256.)
// The first line on which keys have more than kMaxKeyParts dotted parts, 0 when none. Keys
// never span lines in TOML. Dots in strings and comments are not key dots, nor is the first
// dot between two digits of a word (1.5, 18:30:00.5); a key of digits (1.2.3) counts the rest.
int line_of_too_deep_key(std::string_view text) {
  enum class State { kPlain, kBasic, kLiteral, kMultiBasic, kMultiLiteral, kComment };
  State state = State::kPlain;
  const auto at = [&](size_t i, std::string_view what) { return text.substr(i, what.size()) == what; };
  const auto digit = [&](size_t i) {
    return i < text.size() && std::isdigit(static_cast<unsigned char>(text[i]));
  };
  const auto word_char = [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '+' ||
           c == ':' || c == '.';
  };
  int line = 1, dots = 0;
  bool decimal_point_seen = false;  // in the current word
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (!word_char(c)) decimal_point_seen = false;
    if (c == '\n') {
      ++line;
      dots = 0;
      if (state == State::kBasic || state == State::kLiteral || state == State::kComment)
        state = State::kPlain;
      continue;
    }
    switch (state) {
      case State::kPlain:
        if (c == '#') {
          state = State::kComment;
        } else if (at(i, "\"\"\"")) {
          state = State::kMultiBasic;
          i += 2;
        } else if (at(i, "'''")) {
          state = State::kMultiLiteral;
          i += 2;
        } else if (c == '"') {
          state = State::kBasic;
        } else if (c == '\'') {
          state = State::kLiteral;
        } else if (c == '.') {
          const bool decimal = !decimal_point_seen && i > 0 && digit(i - 1) && digit(i + 1);
          decimal_point_seen = decimal_point_seen || decimal;
          if (!decimal && ++dots >= kMaxKeyParts) return line;
        }
        break;
      case State::kBasic:
      case State::kMultiBasic:
        if (c == '\\' && i + 1 < text.size() && text[i + 1] != '\n') {
          ++i;  // an escaped character, perhaps a quote
        } else if (state == State::kBasic ? c == '"' : at(i, "\"\"\"")) {
          i += state == State::kBasic ? 0 : 2;
          state = State::kPlain;
        }
        break;
      case State::kLiteral:
        if (c == '\'') state = State::kPlain;
        break;
      case State::kMultiLiteral:
        if (at(i, "'''")) {
          state = State::kPlain;
          i += 2;
        }
        break;
      case State::kComment:
        break;
    }
  }
  return 0;
}

}  // namespace scene_detail

namespace {

using scene_detail::Field;
using scene_detail::kMaxKeyParts;
using scene_detail::line_of_too_deep_key;
using scene_detail::Section;

// A preset may start from another preset; this bounds the chain (and breaks cycles).
constexpr int kMaxPresetDepth = 8;

// Scene files are small; anything larger is not one (and /dev/zero never ends).

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

// One-line rendering of a TOML value for error messages, e.g. "abc" or [1, 2].
std::string describe(const toml::node& node) {
  std::string text;
  if (const auto* s = node.as_string()) {
    text = scene_detail::toml_quote(s->get());
  } else if (const auto* i = node.as_integer()) {
    text = std::to_string(i->get());
  } else if (const auto* f = node.as_floating_point()) {
    text = scene_detail::format_double(f->get());
  } else if (const auto* b = node.as_boolean()) {
    text = b->get() ? "true" : "false";
  } else if (const auto* a = node.as_array()) {
    std::vector<std::string> items;
    for (const toml::node& item : *a) items.push_back(describe(item));
    text = "[" + join(items) + "]";
  } else if (node.is_table()) {
    text = "{...}";
  } else {  // dates and times
    std::ostringstream out;
    node.visit([&out](const auto& value) { out << value; });
    text = out.str();
  }
  constexpr size_t kMaxChars = 60;
  if (text.size() > kMaxChars) text = text.substr(0, kMaxChars - 3) + "...";
  return text;
}

const Field* find_field(const Section& section, std::string_view name) {
  for (const Field& field : section.fields)
    if (field.name == name) return &field;
  return nullptr;
}

bool is_extra_key(const Section& section, std::string_view name) {
  return std::find(section.extra_keys.begin(), section.extra_keys.end(), name) !=
         section.extra_keys.end();
}

// Keys allowed in a section, for "unknown key" messages; nested sections as [name].
std::string allowed_keys(const Section& section) {
  std::vector<std::string> names;
  for (const Field& field : section.fields) names.emplace_back(field.name);
  for (std::string_view extra : section.extra_keys) names.emplace_back(extra);
  if (section.name.empty())
    for (const Section& nested : scene_detail::scene_sections())
      if (!nested.name.empty() && nested.name.find('.') == std::string_view::npos)
        names.push_back(std::string("[").append(nested.name).append("]"));
  if (section.name.empty())
    for (std::string_view array : {scene_detail::kCloudLayersKey, scene_detail::kVoxelCloudsKey})
      names.push_back(std::string("[[").append(array).append("]]"));
  return join(names);
}

const EmbeddedFile* find_preset_file(const std::string& name) {
  return find_embedded(nephele_presets::kFiles, nephele_presets::kFileCount, name + ".toml");
}

Scene parse_preset(const EmbeddedFile& file, int depth);

// Applies one TOML document to a Scene; `depth` counts the presets being read around it.
class SceneReader {
 public:
  SceneReader(std::string source, std::string base_dir, int depth)
      : source_(shorten_path_for_message(source)),
        base_dir_(std::move(base_dir)),
        depth_(depth) {}

  Scene read(std::string_view text) const {
    if (int line = line_of_too_deep_key(text))
      throw InputError(source_ + ":" + std::to_string(line) + ": a key with more than " +
                       std::to_string(kMaxKeyParts) + " dotted parts (nephele's keys have at most 4)");
    toml::table root;
    try {
      root = toml::parse(text, source_);
    } catch (const toml::parse_error& error) {
      // toml++ quotes the offending bytes: control characters among them (a carriage return)
      // would break the message's one line.
      fail(error.source(), "malformed TOML: " + one_line_for_message(error.description()));
    }
    Scene scene;
    if (const toml::node* preset = root.get("preset")) scene = read_preset(*preset);
    const Section& top = scene_detail::scene_sections().front();
    std::vector<GeoPosition> geo_positions;
    for (const auto& [key, node] : root) {
      std::string name(key.str());
      if (name == "preset") continue;
      if (name == scene_detail::kVoxelCloudsKey) {
        read_voxel_clouds(node, scene, geo_positions);
        continue;
      }
      if (name == scene_detail::kCloudLayersKey) {
        read_array(node, name, scene_detail::cloud_layer_fields(), {}, scene.cloud_layers);
        continue;
      }
      if (const Field* field = find_field(top, name)) {
        assign(*field, name, node, scene);
        continue;
      }
      const Section* section = find_table(name);
      if (!section)
        fail(key.source(),
             "unknown key '" + shorten_for_message(name) + "' (allowed at the top level: " + allowed_keys(top) + ")");
      const toml::table* table = node.as_table();
      if (!table) fail_value(node, name, "expected a table [" + name + "]");
      read_table(*section, *table, scene);
    }
    apply_sun_source(root, scene);
    // A weather report last: its clouds, wind, haze and time take precedence over the keys.
    if (!scene.weather.metar.empty()) {
      try {
        weather::apply_metar(scene);
      } catch (const InputError& e) {
        const toml::node* node = root.at_path("weather.metar").node();
        fail(node ? node->source() : toml::source_region{}, e.what());
      }
    }
    // Then a forecast's cloud cover (its layers over the report's).
    if (!scene.weather.grib.empty()) {
      try {
        weather::apply_grib(scene);
      } catch (const InputError& e) {
        const toml::node* node = root.at_path("weather.grib").node();
        fail(node ? node->source() : toml::source_region{}, e.what());
      }
    }
    // Then the wind and the visibility as a report gives them, over it.
    try {
      weather::apply_weather_keys(scene);
    } catch (const InputError& e) {
      const std::string what = e.what();
      const toml::node* node = root.at_path(what.substr(0, what.find(' '))).node();
      fail(node ? node->source() : toml::source_region{}, what);
    }
    // After every table: the location and the planet's radius may come later in the file.
    for (const GeoPosition& geo : geo_positions)
      scene.voxel_clouds[geo.index].position_m =
          glm::vec3(enu_from_lat_lon(scene, geo.lat_deg, geo.lon_deg, geo.altitude_m));
    return scene;
  }

  // One value into one field (set_scene_value); with no source name the messages have no
  // "file:line:column: " prefix.
  void assign_value(const Field& field, const std::string& key, const toml::node& node,
                    Scene& scene) const {
    assign(field, key, node, scene);
  }

 private:
  // A voxel cloud placed by latitude, longitude and altitude, converted once the scene's
  // location is known.
  struct GeoPosition {
    size_t index;
    double lat_deg, lon_deg, altitude_m;
  };

  // [[voxel_clouds]]: the file's array replaces a preset's (as any key does).
  void read_voxel_clouds(const toml::node& node, Scene& scene,
                         std::vector<GeoPosition>& geo_positions) const {
    read_array(node, scene_detail::kVoxelCloudsKey, scene_detail::voxel_cloud_fields(),
               scene_detail::kVoxelCloudGeoKeys, scene.voxel_clouds);
    const toml::array& array = *node.as_array();
    for (size_t i = 0; i < array.size(); ++i) {
      VoxelCloudParams& cloud = scene.voxel_clouds[i];
      cloud.file = resolve_path(cloud.file);
      if (std::optional<GeoPosition> geo = read_voxel_cloud_geo(i, *array[i].as_table()))
        geo_positions.push_back(*geo);
    }
  }

  // An array of tables ([[voxel_clouds]], [[cloud_layers]]) into `items`, replacing a preset's
  // (as any key does); the keys in `own_keys` are left to the caller.
  template <typename T>
  void read_array(const toml::node& node, std::string_view key,
                  const std::vector<scene_detail::ArrayField<T>>& fields,
                  std::span<const std::string_view> own_keys, std::vector<T>& items) const {
    const std::string array_key(key);
    const toml::array* array = node.as_array();
    if (!array || !std::all_of(array->begin(), array->end(),
                               [](const toml::node& item) { return item.is_table(); }))
      fail_value(node, array_key, "expected an array of tables [[" + array_key + "]]");
    items.assign(array->size(), T{});
    for (size_t i = 0; i < array->size(); ++i) {
      const toml::table& table = *(*array)[i].as_table();
      const std::string prefix = array_key + "[" + std::to_string(i) + "]";
      for (const auto& [name_key, value] : table) {
        const std::string name(name_key.str());
        const std::string full_key = prefix + "." + name;
        if (std::find(own_keys.begin(), own_keys.end(), name) != own_keys.end()) continue;
        const auto field = std::find_if(fields.begin(), fields.end(),
                                        [&](const auto& f) { return f.name == name; });
        if (field == fields.end()) {
          std::vector<std::string> names;
          for (const auto& f : fields) names.emplace_back(f.name);
          for (std::string_view own : own_keys) names.emplace_back(own);
          fail(name_key.source(), "unknown key '" + shorten_for_message(full_key) +
                                      "' (allowed in [[" + array_key + "]]: " + join(names) + ")");
        }
        std::visit([&](auto access) { read_value(value, full_key, access(items[i])); },
                   field->access);
      }
    }
  }

  // lat_deg, lon_deg and altitude_m: all three or none, and not with position_m.
  std::optional<GeoPosition> read_voxel_cloud_geo(size_t i, const toml::table& table) const {
    const std::string prefix = scene_detail::voxel_cloud_key(i);
    const toml::node* first = nullptr;
    for (std::string_view name : scene_detail::kVoxelCloudGeoKeys)
      if (!first) first = table.get(name);
    if (!first) return std::nullopt;
    if (table.contains("position_m"))
      fail(first->source(), prefix +
                                ": position_m and lat_deg/lon_deg/altitude_m are both given; give "
                                "one form");
    for (std::string_view name : scene_detail::kVoxelCloudGeoKeys)
      if (!table.contains(name))
        fail(first->source(), prefix + "." + std::string(name) +
                                  " is missing (lat_deg, lon_deg and altitude_m go together)");
    const auto number = [&](std::string_view name, double min, double max) {
      const toml::node& node = *table.get(name);
      const std::string key = prefix + "." + std::string(name);
      const double value = read_number(node, key);
      if (!(value >= min && value <= max))
        fail_value(node, key,
                   "must be in [" + scene_detail::format_double(min) + ", " +
                       scene_detail::format_double(max) + "]");
      return value;
    };
    // The altitude's range is position_m's up range; the point's ENU up is a little lower away
    // from the origin, and validate_scene checks it.
    return GeoPosition{i, number("lat_deg", -90.0, 90.0), number("lon_deg", -180.0, 360.0),
                       number("altitude_m", -1.0e3, 1.0e5)};
  }

  // "file:line:column: message"; the position is left out when toml++ has none.
  [[noreturn]] void fail(const toml::source_region& where, const std::string& message) const {
    if (source_.empty()) throw InputError(message);
    std::string position;
    if (where.begin.line > 0)
      position = ":" + std::to_string(where.begin.line) + ":" + std::to_string(where.begin.column);
    throw InputError(source_ + position + ": " + message);
  }

  [[noreturn]] void fail_value(const toml::node& node, const std::string& key,
                               const std::string& what) const {
    fail(node.source(), key + " = " + describe(node) + ": " + what);
  }

  static const Section* find_table(std::string_view name) {
    for (const Section& section : scene_detail::scene_sections())
      if (!section.name.empty() && section.name == name) return &section;
    return nullptr;
  }

  void read_table(const Section& section, const toml::table& table, Scene& scene) const {
    for (const auto& [key, node] : table) {
      std::string name(key.str());
      std::string full_key = std::string(section.name) + "." + name;
      const Section* nested = find_table(full_key);  // e.g. [conditions.good.night]
      if (nested && node.as_table()) {
        read_table(*nested, *node.as_table(), scene);
        continue;
      }
      if (nested) fail_value(node, full_key, "expected a table [" + full_key + "]");
      if (is_extra_key(section, name)) continue;  // read below, after the plain fields
      const Field* field = find_field(section, name);
      if (!field)
        fail(key.source(), "unknown key '" + shorten_for_message(full_key) + "' (allowed in [" +
                               std::string(section.name) + "]: " + allowed_keys(section) + ")");
      assign(*field, full_key, node, scene);
    }
    if (section.name == "camera") read_camera_altitude(table, scene);
    if (section.name == "camera") read_fov_form(table, scene);
    if (section.name == "sun") read_sun_angles(table, scene);
    if (section.name == "sun") read_legacy_illuminance(table, scene);
    if (section.name == "output") read_legacy_exposure(table, scene);
    if (section.name == "clouds") read_legacy_lighting(table, scene);
  }

  // clouds.two_stream_light, the old switch: true is lighting = "two-stream", false "seed".
  void read_legacy_lighting(const toml::table& table, Scene& scene) const {
    const toml::node* old = table.get("two_stream_light");
    if (!old) return;
    if (table.contains("lighting"))
      fail(old->source(),
           "clouds.two_stream_light and clouds.lighting are both given; give lighting "
           "(two_stream_light = true is lighting = \"two-stream\", false is \"seed\")");
    const auto* value = old->as_boolean();
    if (!value)
      fail_value(*old, "clouds.two_stream_light",
                 "expected true or false (the old switch; clouds.lighting = \"two-stream\" or "
                 "\"seed\" replaces it)");
    scene.clouds.lighting = value->get() ? "two-stream" : "seed";
  }

  // The field of view's form: at most one of fov_deg, horizontal_fov_deg and focal_length_mm
  // in a table (the last two given when not 0), and the one given replaces the form of a preset
  // underneath.
  void read_fov_form(const toml::table& table, Scene& scene) const {
    const char* const forms[] = {"fov_deg", "horizontal_fov_deg", "focal_length_mm"};
    std::vector<const char*> given;
    for (const char* form : forms) {
      const toml::node* node = table.get(form);
      if (!node) continue;
      if (form != forms[0] && node->is_number() && read_number(*node, form) == 0.0) continue;
      given.push_back(form);
    }
    if (given.size() > 1)
      fail(table.get(given[1])->source(),
           std::string("camera.") + given[0] + " and camera." + given[1] +
               " are both given; give one of fov_deg, horizontal_fov_deg, focal_length_mm");
    if (given.empty()) return;
    CameraParams& c = scene.camera;
    if (given[0] != forms[1]) c.horizontal_fov_deg = 0.0f;
    if (given[0] != forms[2]) c.focal_length_mm = 0.0f;
  }

  // sun.illuminance, the old radiance scale (20 for the sun): X x 6400 lux, the same light.
  void read_legacy_illuminance(const toml::table& table, Scene& scene) const {
    const toml::node* old = table.get("illuminance");
    if (!old) return;
    if (table.contains("illuminance_lux"))
      fail(old->source(),
           "sun.illuminance and sun.illuminance_lux are both given; give illuminance_lux (the "
           "old illuminance is illuminance_lux / 6400)");
    const double value = read_number(*old, "sun.illuminance");
    if (!(value >= 0.0 && value <= 1.0e6))
      fail_value(*old, "sun.illuminance",
                 "must be in [0, 1e+06] (the old radiance scale, read as x 6400 lux; "
                 "sun.illuminance_lux replaces it)");
    scene.sun.illuminance_lux = float(value * double(kLegacyLuxPerUnit));
  }

  // output.exposure, the old linear exposure: the EV100 that exposes the image as it did, manual
  // unless the table turns auto_exposure on.
  void read_legacy_exposure(const toml::table& table, Scene& scene) const {
    const toml::node* old = table.get("exposure");
    if (!old) return;
    if (table.contains("ev100"))
      fail(old->source(),
           "output.exposure and output.ev100 are both given; give ev100 (the old exposure e is "
           "ev100 = log2(5333 / e))");
    const double value = read_number(*old, "output.exposure");
    const double ev100 = ev100_from_legacy_exposure(value);
    if (!(value >= 5.0e-6 && value <= 1.0e6))
      fail_value(*old, "output.exposure",
                 "must be in [5e-06, 1e+06] (the old linear exposure, read as output.ev100 = "
                 "log2(5333 / exposure) in [-7.55, 30])");
    scene.output.ev100 = float(ev100);
    if (!table.contains("auto_exposure")) scene.output.auto_exposure = false;
  }

  void assign(const Field& field, const std::string& key, const toml::node& node,
              Scene& scene) const {
    // Not an integer where one is expected: the key's own range, not its type's.
    if (scene_detail::value_shape(field.access) == scene_detail::ValueShape::kInteger &&
        !node.is_integer())
      fail_value(node, key, scene_detail::expected_integer(scene_detail::allowed_text(field)));
    std::visit([&](auto access) { read_value(node, key, access(scene)); }, field.access);
    if (key == "clouds.weather_map")
      scene.clouds.weather_map = resolve_path(scene.clouds.weather_map);
    if (key == "lab.grid") scene.lab.grid = resolve_path(scene.lab.grid);
    if (key == "weather.grib") scene.weather.grib = resolve_path(scene.weather.grib);
  }

  // A relative path in a file is relative to the file's folder.
  std::string resolve_path(const std::string& path) const {
    std::filesystem::path p(path);
    if (path.empty() || base_dir_.empty() || p.is_absolute()) return path;
    return (std::filesystem::path(base_dir_) / p).lexically_normal().string();
  }

  double read_number(const toml::node& node, const std::string& key) const {
    if (const auto* i = node.as_integer()) return static_cast<double>(i->get());
    if (const auto* f = node.as_floating_point()) return f->get();
    fail_value(node, key, "expected a number");
  }

  int64_t read_integer(const toml::node& node, const std::string& key, int64_t min,
                       int64_t max) const {
    const auto* i = node.as_integer();
    if (!i || i->get() < min || i->get() > max)
      fail_value(
          node, key,
          "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
    return i->get();
  }

  void read_value(const toml::node& node, const std::string& key, float& out) const {
    out = static_cast<float>(read_number(node, key));
  }
  void read_value(const toml::node& node, const std::string& key, int& out) const {
    out = static_cast<int>(read_integer(node, key, INT_MIN, INT_MAX));
  }
  void read_value(const toml::node& node, const std::string& key, uint32_t& out) const {
    out = static_cast<uint32_t>(read_integer(node, key, 0, UINT32_MAX));
  }
  void read_value(const toml::node& node, const std::string& key, glm::vec2& out) const {
    read_vector(node, key, 2, &out.x);
  }
  void read_value(const toml::node& node, const std::string& key, glm::vec3& out) const {
    read_vector(node, key, 3, &out.x);
  }
  void read_value(const toml::node& node, const std::string& key, std::string& out) const {
    if (key == "time" && node.is_date_time()) {  // time = 2026-06-21T18:30:00Z, unquoted
      std::ostringstream text;
      text << *node.as_date_time();
      out = text.str();
      return;
    }
    const auto* s = node.as_string();
    if (!s) fail_value(node, key, "expected a string");
    out = s->get();
  }
  void read_value(const toml::node& node, const std::string& key, bool& out) const {
    const auto* b = node.as_boolean();
    if (!b) fail_value(node, key, "expected true or false");
    out = b->get();
  }
  void read_value(const toml::node& node, const std::string& key, MarchMode& out) const {
    const auto* s = node.as_string();
    std::optional<MarchMode> mode = s ? parse_march_mode(s->get()) : std::nullopt;
    if (!mode) fail_value(node, key, "expected \"default\" or \"baseline\"");
    out = *mode;
  }
  void read_value(const toml::node& node, const std::string& key, ConditionsMode& out) const {
    const auto* s = node.as_string();
    std::optional<ConditionsMode> mode = s ? parse_conditions_mode(s->get()) : std::nullopt;
    if (!mode) fail_value(node, key, "expected \"off\", \"artist\" or \"overlay\"");
    out = *mode;
  }
  void read_value(const toml::node& node, const std::string& key, VoxelMarch& out) const {
    const auto* s = node.as_string();
    std::optional<VoxelMarch> mode = s ? parse_voxel_march(s->get()) : std::nullopt;
    if (!mode) fail_value(node, key, "expected \"plain\" or \"three-phase\"");
    out = *mode;
  }
  void read_value(const toml::node& node, const std::string& key, VoxelShadow& out) const {
    const auto* s = node.as_string();
    std::optional<VoxelShadow> mode = s ? parse_voxel_shadow(s->get()) : std::nullopt;
    if (!mode) fail_value(node, key, "expected \"march\" or \"sdf-cone\"");
    out = *mode;
  }
  void read_value(const toml::node& node, const std::string& key, CloudModel& out) const {
    const auto* s = node.as_string();
    std::optional<CloudModel> model = s ? parse_cloud_model(s->get()) : std::nullopt;
    if (!model) fail_value(node, key, "expected " + cloud_model_names(true));
    out = *model;
  }
  void read_value(const toml::node& node, const std::string& key, ToneMap& out) const {
    const auto* s = node.as_string();
    std::optional<ToneMap> op = s ? parse_tonemap(s->get()) : std::nullopt;
    if (!op) fail_value(node, key, "expected \"aces\", \"agx\", \"uncharted2\", \"reinhard\" or \"none\"");
    out = *op;
  }
  void read_value(const toml::node& node, const std::string& key, SkyModel& out) const {
    const auto* s = node.as_string();
    std::optional<SkyModel> model = s ? parse_sky_model(s->get()) : std::nullopt;
    if (!model) fail_value(node, key, "expected \"hillaire\", \"preetham\" or \"reference\"");
    out = *model;
  }

  // `out` points at `size` consecutive floats (glm vectors are laid out so).
  void read_vector(const toml::node& node, const std::string& key, size_t size, float* out) const {
    const toml::array* array = node.as_array();
    bool ok = array && array->size() == size &&
              std::all_of(array->begin(), array->end(),
                          [](const toml::node& item) { return item.is_number(); });
    if (!ok) fail_value(node, key, "expected an array of " + std::to_string(size) + " numbers");
    for (size_t i = 0; i < size; ++i) out[i] = static_cast<float>(read_number((*array)[i], key));
  }

  // A file that gives a time and no sun direction places the sun by the ephemeris; one that
  // gives a sun direction uses it (also over a time); sun.from_time, when given, decides.
  static void apply_sun_source(const toml::table& root, Scene& scene) {
    const toml::table* sun = root["sun"].as_table();
    if (sun && sun->contains("from_time")) return;
    if (sun && (sun->contains("direction") || sun->contains("elevation_deg") ||
                sun->contains("azimuth_deg")))
      scene.sun.from_time = false;
    else if (root.contains("time"))
      scene.sun.from_time = true;
  }

  // camera.altitude_m is another way to write position_m's up component.
  void read_camera_altitude(const toml::table& table, Scene& scene) const {
    const toml::node* altitude = table.get("altitude_m");
    if (!altitude) return;
    if (table.contains("position_m"))
      fail_value(*altitude, "camera.altitude_m",
                 "camera.position_m is given too; give one of them (altitude_m sets its up "
                 "component)");
    scene.camera.position_m.z = static_cast<float>(read_number(*altitude, "camera.altitude_m"));
  }

  // sun.elevation_deg / sun.azimuth_deg replace the direction; one alone keeps the other angle.
  void read_sun_angles(const toml::table& table, Scene& scene) const {
    const toml::node* elevation = table.get("elevation_deg");
    const toml::node* azimuth = table.get("azimuth_deg");
    if (!elevation && !azimuth) return;
    const toml::node& first = elevation ? *elevation : *azimuth;
    if (table.contains("direction"))
      fail(first.source(),
           "sun.direction and sun.elevation_deg/azimuth_deg are both given; give one form");
    SunAngles angles = sun_angles_from_direction(scene.sun.direction);
    if (elevation) {
      angles.elevation_deg = read_number(*elevation, "sun.elevation_deg");
      if (!(angles.elevation_deg >= -90.0 && angles.elevation_deg <= 90.0))
        fail_value(*elevation, "sun.elevation_deg", "must be in [-90, 90]");
    }
    if (azimuth) {
      angles.azimuth_deg = read_number(*azimuth, "sun.azimuth_deg");
      if (!std::isfinite(angles.azimuth_deg))
        fail_value(*azimuth, "sun.azimuth_deg", "must be finite");
    }
    scene.sun.direction = sun_direction_from_angles(angles.elevation_deg, angles.azimuth_deg);
  }

  Scene read_preset(const toml::node& node) const {
    const auto* name = node.as_string();
    const EmbeddedFile* file = name ? find_preset_file(name->get()) : nullptr;
    if (!file)
      fail_value(node, "preset", "unknown preset (available: " + join(preset_names()) + ")");
    if (depth_ >= kMaxPresetDepth)
      fail_value(node, "preset", "presets refer to each other too deeply (a cycle?)");
    return parse_preset(*file, depth_ + 1);
  }

  std::string source_;
  std::string base_dir_;
  int depth_;
};

Scene parse_preset(const EmbeddedFile& file, int depth) {
  std::string_view text(reinterpret_cast<const char*>(file.data), file.size);
  return SceneReader(std::string("presets/") + file.name, "", depth).read(text);
}

// sin of an angle in degrees, exact at multiples of 90 so that the cardinal directions
// come out exact: elevation 90 is (0, 0, 1), not (-4e-8, 0, 1).
double sin_deg(double degrees) {
  double reduced = std::fmod(degrees, 360.0);
  if (reduced < 0.0) reduced += 360.0;
  if (reduced == 0.0 || reduced == 180.0) return 0.0;
  if (reduced == 90.0) return 1.0;
  if (reduced == 270.0) return -1.0;
  return std::sin(reduced * std::numbers::pi / 180.0);
}

double cos_deg(double degrees) {
  return sin_deg(degrees + 90.0);
}

}  // namespace

Scene parse_scene_toml(std::string_view text, const std::string& source_name,
                       const std::string& base_dir) {
  return SceneReader(source_name, base_dir, 0).read(text);
}

void scene_detail::read_field_value(Scene& scene, const Field& field, const std::string& key,
                                    std::string_view text) {
  const auto not_a_value = [&](const std::string& why) {
    return InputError(key + " = " + shorten_for_message(text) + ": " + why);
  };
  // One literal on one line: "0.9\nclouds.density = 1" is two assignments, not a value.
  if (text.find_first_of("\n\r") != std::string_view::npos)
    throw not_a_value("expected one TOML value on one line");
  toml::table root;
  try {
    root = toml::parse("value = " + std::string(text));
  } catch (const toml::parse_error& error) {
    throw not_a_value("not a TOML value (" + one_line_for_message(error.description()) + ")");
  }
  const toml::node* node = root.get("value");
  if (!node || root.size() != 1) throw not_a_value("expected one TOML value");
  Scene changed = scene;  // unchanged when the value is refused
  SceneReader("", "", 0).assign_value(field, key, *node, changed);
  scene = std::move(changed);
}

std::vector<std::pair<std::string, std::string>> scene_input_files(const Scene& scene) {
  std::vector<std::pair<std::string, std::string>> files = {
      {"clouds.weather_map", scene.clouds.weather_map},
      {"terrain.file", scene.terrain.file},
      {"terrain.albedo_map", scene.terrain.albedo_map},
      {"lab.grid", scene.lab.grid},
      {"weather.grib", scene.weather.grib}};
  for (size_t i = 0; i < scene.voxel_clouds.size(); ++i)
    files.emplace_back("voxel_clouds[" + std::to_string(i) + "].file", scene.voxel_clouds[i].file);
  std::erase_if(files, [](const auto& f) { return f.second.empty(); });
  return files;
}

void apply_weather_sources(Scene& scene) {
  Scene next = scene;
  weather::apply_metar(next);
  if (!next.weather.grib.empty()) weather::apply_grib(next);
  weather::apply_weather_keys(next);
  scene = std::move(next);
}

Scene load_scene_file(const std::string& path) {
  const std::string text = scene_detail::read_small_text_file(
      path, "scene file", "it is larger than 1 MiB (scene files are a few KB)");
  std::string base_dir = std::filesystem::path(path).parent_path().string();
  return parse_scene_toml(text, path, base_dir);
}

Scene load_preset(const std::string& name) {
  const EmbeddedFile* file = find_preset_file(name);
  if (!file)
    throw InputError("preset '" + shorten_for_message(name) + "': unknown preset (available: " + join(preset_names()) +
                     ")");
  return parse_preset(*file, 0);
}

std::vector<std::string> preset_names() {
  std::vector<std::string> names;
  for (size_t i = 0; i < nephele_presets::kFileCount; ++i) {
    std::string_view name = nephele_presets::kFiles[i].name;
    if (name.ends_with(".toml")) names.emplace_back(name.substr(0, name.size() - 5));
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string preset_description(const std::string& name) {
  const EmbeddedFile* file = find_preset_file(name);
  if (!file) return "";
  // The comment lines the file starts with, as one text, to the end of its first sentence.
  std::istringstream in(std::string(reinterpret_cast<const char*>(file->data), file->size));
  std::string line, text;
  while (std::getline(in, line) && line.starts_with("#")) {
    const size_t start = line.find_first_not_of("# ");
    if (start != std::string::npos) text += (text.empty() ? "" : " ") + line.substr(start);
  }
  const size_t end = text.find(". ");
  return end == std::string::npos ? text : text.substr(0, end + 1);
}

glm::vec3 sun_direction_from_angles(double elevation_deg, double azimuth_deg) {
  double horizontal = cos_deg(elevation_deg);
  return glm::vec3(static_cast<float>(horizontal * sin_deg(azimuth_deg)),
                   static_cast<float>(horizontal * cos_deg(azimuth_deg)),
                   static_cast<float>(sin_deg(elevation_deg)));
}

SunAngles sun_angles_from_direction(const glm::vec3& direction) {
  double x = direction.x, y = direction.y, z = direction.z;
  double length = std::sqrt(x * x + y * y + z * z);
  if (!(length > 0.0) || !std::isfinite(length)) return {};
  SunAngles angles;
  angles.elevation_deg = std::asin(std::clamp(z / length, -1.0, 1.0)) * 180.0 / std::numbers::pi;
  if (x != 0.0 || y != 0.0) {
    angles.azimuth_deg = std::atan2(x, y) * 180.0 / std::numbers::pi;
    if (angles.azimuth_deg < 0.0) angles.azimuth_deg += 360.0;
  }
  return angles;
}

}  // namespace nephele

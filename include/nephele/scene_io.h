// nephele — scene files (TOML), built-in presets, validation.
//
// A scene file mirrors the structs of scene.h: top-level `time_s`, `noise_seed` and
// `preset = "name"` (start from that preset instead of the defaults), then the tables
// [camera], [sun], [atmosphere], [clouds], [quality], [output] whose keys are the struct
// fields. Extra keys: camera.altitude_m (sets position_m's up component) and
// sun.elevation_deg / sun.azimuth_deg (replace sun.direction). Voxel clouds are an array of
// tables, [[voxel_clouds]], one per cloud (a file's array replaces a preset's), whose keys are
// VoxelCloudParams' fields; lat_deg, lon_deg and altitude_m (all three) may replace position_m
// (converted by enu_from_lat_lon with the file's final location and planet radius); a relative
// file is relative to the scene file. Messages name them voxel_clouds[i].key (i from 0). Every
// error is an InputError whose one-line message names the parameter, the value and what is
// allowed.
#pragma once

#include <functional>
#include <glm/vec3.hpp>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nephele/scene.h"

namespace nephele {

// Parses TOML text and applies it on top of the defaults of scene.h (or of the preset it
// names). `source_name` prefixes error messages; a relative clouds.weather_map or voxel cloud
// file is resolved against `base_dir` when that is not empty. Checks syntax, keys and types, not
// ranges: call validate_scene on the final scene.
Scene parse_scene_toml(std::string_view text, const std::string& source_name,
                       const std::string& base_dir = "");

// Applies the scene's weather as reading a scene file does: the report in weather.metar, then
// the forecast in weather.grib, then the wind and visibility keys of [weather] (its layers,
// wind, haze and time over the scene's). Throws InputError naming the key; the scene is
// unchanged then. For a host or a panel that has just set one of them.
void apply_weather_sources(Scene& scene);

// Reads and parses a scene file; relative paths inside are relative to the file's folder.
Scene load_scene_file(const std::string& path);

// Built-in presets (presets/*.toml, embedded at build time), by name without ".toml".
Scene load_preset(const std::string& name);
std::vector<std::string> preset_names();  // sorted
// A preset's first sentence of description (the comment its file starts with); "" for none.
std::string preset_description(const std::string& name);

// How validate_scene names a parameter. Given a scene key ("clouds.coverage"), returns the
// name to print instead, or "" to print the key itself. A name starting with "--" is printed
// as a command-line flag with the value as typed there (`--view-dir 0,0,0: ...`); any other
// name as an assignment (`clouds.coverage = 1.5: ...`).
using ParamNamer = std::function<std::string(const std::string& key)>;

// Throws InputError for the first parameter out of its allowed range, e.g.
// "clouds.coverage = 1.5: must be in [0, 1]". Also checks that a weather map is readable.
void validate_scene(const Scene& scene, const ParamNamer& display_name = {});

// The files the scene reads, each with its key: {"clouds.weather_map", "wm.png"},
// {"voxel_clouds[0].file", ...}, {"terrain.file", ...}, {"terrain.albedo_map", ...},
// {"lab.grid", ...}; empty paths left out. (An output must not be one of them.)
std::vector<std::pair<std::string, std::string>> scene_input_files(const Scene& scene);

// The whole scene as TOML; parse_scene_toml(scene_to_toml(s), ...) gives back s exactly.
std::string scene_to_toml(const Scene& scene);

// --- one parameter at a time (a viewer's panel, a script, a host's own UI) -----------------
// Every key of scene_to_toml, by its dotted name: "clouds.coverage", "time",
// "conditions.good.night.hour". Values are TOML literal text, as a scene file writes them.

// What a parameter holds; the TOML literal it takes.
enum class SceneValueKind {
  kFloat,   // 0.9 (an integer literal is accepted too)
  kInt,     // 64
  kUint,    // 1, [0, 4294967295]
  kVec2,    // [8.0, 2.0]
  kVec3,    // [0.0, 1.0, 0.25]
  kString,  // "file.png"
  kEnum,    // "hillaire": one of SceneParameter::allowed, quoted
  kBool,    // true
};

struct SceneParameter {
  std::string key;                   // "clouds.coverage"
  SceneValueKind kind = SceneValueKind::kFloat;
  std::vector<std::string> allowed;  // kEnum only: the allowed values, unquoted
  std::string note;                  // units and range, as scene_to_toml's comment; may be empty
  // Declared with the field once; validate_scene, the CLI, the viewer and the scene reference
  // (docs/scene-reference.md) all use the same.
  std::string meaning;         // the note without the allowed values
  std::string allowed_values;  // "[0, 1]", "0 or [1, 1e+07]", "1, 2 or 4"; "" = any of the type
  std::string unit;            // from the key's suffix: "m", "deg", "m/s", ...; "" = none
  // Numbers: the range, NaN when there is none (either end open as flagged); `off`, when set,
  // is one more value allowed outside it (0 for "0 or [1, 1e+07]").
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
  bool min_open = false, max_open = false;
  std::optional<double> off;
  std::string default_value;  // TOML literal text of Scene{}'s value (no preset)
  // The command line's flag for it, declared with the field ("ground-fog-visibility-m" for
  // --ground-fog-visibility-m); empty: none, or one of the CLI's own.
  std::string flag;
};

// In scene_to_toml's order: time, time_s, noise_seed, then [location], [camera], [sun], ...
// Scene::voxel_clouds, an array, is not among them (its number of entries varies): edit the
// Scene's vector; scene_to_toml writes it.
const std::vector<SceneParameter>& scene_parameters();

// The parameter's value as TOML literal text ("0.45", "[8.0, 2.0]", "\"hillaire\"", "true");
// set_scene_value(scene, key, get_scene_value(scene, key)) changes nothing. Throws InputError
// for an unknown key.
std::string get_scene_value(const Scene& scene, std::string_view key);

// Sets one parameter from TOML literal text (`0.9`, `[1, 2, 3]`, `"file.png"`) with the scene
// file's type rules; nothing else of the scene changes (unlike a file, a time does not move
// the sun to the ephemeris: set sun.from_time too). Checks the type, not the range: call
// validate_scene on the result. Throws InputError naming the key for an unknown key, a value
// that is not one TOML literal or one of the wrong type (`clouds.coverage = "x": expected a
// number`); the scene is unchanged then.
void set_scene_value(Scene& scene, std::string_view key, std::string_view value);

// "default" / "baseline" (the inverse of to_string(MarchMode)); nullopt for anything else.
std::optional<MarchMode> parse_march_mode(std::string_view text);
// "hillaire" / "preetham" / "reference" (the inverse of to_string(SkyModel)).
std::optional<SkyModel> parse_sky_model(std::string_view text);
// "off" / "artist" / "overlay".
std::optional<ConditionsMode> parse_conditions_mode(std::string_view text);
// "nephele" / "blinn" (the inverse of to_string(CloudModel)).
std::optional<CloudModel> parse_cloud_model(std::string_view text);
// The models' names for a message: "nephele or blinn", quoted as TOML strings when `quoted`.
std::string cloud_model_names(bool quoted);
// "plain" / "three-phase".
std::optional<VoxelMarch> parse_voxel_march(std::string_view text);
// "march" / "sdf-cone".
std::optional<VoxelShadow> parse_voxel_shadow(std::string_view text);

// Sun direction (ENU, unit length) from its elevation above the horizon and its azimuth
// from north through east: (cos el sin az, cos el cos az, sin el).
glm::vec3 sun_direction_from_angles(double elevation_deg, double azimuth_deg);

struct SunAngles {
  double elevation_deg = 0.0;  // [-90, 90]
  double azimuth_deg = 0.0;    // [0, 360); 0 when the direction is vertical
};
// Inverse of sun_direction_from_angles; `direction` need not be normalised.
SunAngles sun_angles_from_direction(const glm::vec3& direction);

}  // namespace nephele

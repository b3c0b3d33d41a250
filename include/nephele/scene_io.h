// nephele — scene files (TOML), built-in presets, validation.
//
// A scene file mirrors the structs of scene.h: top-level `time_s`, `noise_seed` and
// `preset = "name"` (start from that preset instead of the defaults), then the tables
// [camera], [sun], [atmosphere], [clouds], [quality], [output] whose keys are the struct
// fields. Extra keys: camera.altitude_m (sets position_m's up component) and
// sun.elevation_deg / sun.azimuth_deg (replace sun.direction). Every error is an
// InputError whose one-line message names the parameter, the value and what is allowed.
#pragma once

#include <functional>
#include <glm/vec3.hpp>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "nephele/scene.h"

namespace nephele {

// Parses TOML text and applies it on top of the defaults of scene.h (or of the preset it
// names). `source_name` prefixes error messages; a relative clouds.weather_map is resolved
// against `base_dir` when that is not empty. Checks syntax, keys and types, not ranges:
// call validate_scene on the final scene.
Scene parse_scene_toml(std::string_view text, const std::string& source_name,
                       const std::string& base_dir = "");

// Reads and parses a scene file; relative paths inside are relative to the file's folder.
Scene load_scene_file(const std::string& path);

// Built-in presets (presets/*.toml, embedded at build time), by name without ".toml".
Scene load_preset(const std::string& name);
std::vector<std::string> preset_names();  // sorted

// How validate_scene names a parameter. Given a scene key ("clouds.coverage"), returns the
// name to print instead, or "" to print the key itself. A name starting with "--" is printed
// as a command-line flag with the value as typed there (`--view-dir 0,0,0: ...`); any other
// name as an assignment (`clouds.coverage = 1.5: ...`).
using ParamNamer = std::function<std::string(const std::string& key)>;

// Throws InputError for the first parameter out of its allowed range, e.g.
// "clouds.coverage = 1.5: must be in [0, 1]". Also checks that a weather map is readable.
void validate_scene(const Scene& scene, const ParamNamer& display_name = {});

// The whole scene as TOML; parse_scene_toml(scene_to_toml(s), ...) gives back s exactly.
std::string scene_to_toml(const Scene& scene);

// "default" / "baseline" (the inverse of to_string(MarchMode)); nullopt for anything else.
std::optional<MarchMode> parse_march_mode(std::string_view text);
// "hillaire" / "preetham" / "reference" (the inverse of to_string(SkyModel)).
std::optional<SkyModel> parse_sky_model(std::string_view text);
// "off" / "artist" / "overlay".
std::optional<ConditionsMode> parse_conditions_mode(std::string_view text);

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

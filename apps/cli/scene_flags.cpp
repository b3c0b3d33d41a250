// nephele CLI — scene flags: registration, parsing, application to a Scene.
#include "scene_flags.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cfloat>
#include <charconv>
#include <climits>
#include <cmath>
#include <cstdio>
#include <map>
#include <variant>
#include <vector>

#include "nephele/error.h"
#include "nephele/exposure.h"
#include "nephele/scene_io.h"
#include "scene/scene_fields.h"
#include "voxel/voxel_grid.h"
#include "weather/grib.h"
#include "weather/metar_weather.h"
#include "weather/weather_state.h"

namespace nephele::cli {
namespace {

// Where a flag's value goes in the Scene; monostate for the flags resolve_scene handles itself.
using Target = std::variant<std::monostate, float& (*)(Scene&), int& (*)(Scene&),
                            uint32_t& (*)(Scene&), glm::vec2& (*)(Scene&), glm::vec3& (*)(Scene&),
                            std::string& (*)(Scene&), MarchMode& (*)(Scene&),
                            bool& (*)(Scene&), SkyModel& (*)(Scene&),
                            ConditionsMode& (*)(Scene&), VoxelMarch& (*)(Scene&),
                            VoxelShadow& (*)(Scene&), CloudModel& (*)(Scene&),
                            ToneMap& (*)(Scene&)>;

struct FlagSpec {
  const char* flag;
  std::optional<std::string> SceneFlags::*member;
  const char* key;  // scene key the flag sets: validation messages on it name the flag
  Target target;
  const char* type_name;
  const char* help;
};

// TO(clouds.coverage) is the Target of Scene::clouds.coverage.
#define TO(path)            \
  +[](Scene & s) -> auto& { \
    return s.path;          \
  }

// In the order they are applied (and listed by --help).
const std::vector<FlagSpec>& flag_specs() {
  using F = SceneFlags;
  static const std::vector<FlagSpec> specs = {
      {"--scene",
       &F::scene_file,
       "",
       {},
       "FILE",
       "scene file (TOML); relative paths inside it are relative to its folder"},
      {"--preset", &F::preset, "", {}, "NAME", "built-in scene to start from (default: default)"},
      {"--width", &F::width, "output.width", TO(output.width), "N", "image width (pixels)"},
      {"--height", &F::height, "output.height", TO(output.height), "N", "image height (pixels)"},
      {"--camera-pos", &F::camera_pos, "camera.position_m", TO(camera.position_m), "E,N,U",
       "camera position (m): east, north, up"},
      {"--camera-altitude-m", &F::camera_altitude_m, "camera.altitude_m", TO(camera.position_m.z),
       "A", "camera height above the ground (m)"},
      {"--view-dir", &F::view_dir, "camera.view_dir", TO(camera.view_dir), "E,N,U",
       "looking direction: east, north, up"},
      {"--fov-deg", &F::fov_deg, "camera.fov_deg", TO(camera.fov_deg), "F",
       "vertical field of view (deg); one of --fov-deg, --hfov, --focal-length-mm"},
      {"--hfov", &F::hfov_deg, "camera.horizontal_fov_deg", TO(camera.horizontal_fov_deg), "F",
       "horizontal field of view (deg): the vertical follows the image's aspect"},
      {"--focal-length-mm", &F::focal_length_mm, "camera.focal_length_mm",
       TO(camera.focal_length_mm), "MM",
       "lens focal length (mm): horizontal fov 2 atan(sensor width / 2f)"},
      {"--sensor-width-mm", &F::sensor_width_mm, "camera.sensor_width_mm",
       TO(camera.sensor_width_mm), "MM", "sensor (film gate) width (mm), [1, 1000], default 36"},
      {"--roll-deg", &F::roll_deg, "camera.roll_deg", TO(camera.roll_deg), "DEG",
       "camera roll about the view direction (deg); positive turns the camera "
       "clockwise, so the horizon rises to the right"},
      {"--sun-dir", &F::sun_dir, "sun.direction", TO(sun.direction), "E,N,U",
       "direction towards the sun: east, north, up"},
      {"--sun-elevation-deg",
       &F::sun_elevation_deg,
       "",
       {},
       "E",
       "sun elevation above the horizon (deg), [-90, 90]"},
      {"--sun-azimuth-deg",
       &F::sun_azimuth_deg,
       "",
       {},
       "A",
       "sun azimuth from north through east (deg)"},
      {"--sun-illuminance-lux", &F::sun_illuminance_lux, "sun.illuminance_lux",
       TO(sun.illuminance_lux), "LUX",
       "sunlight at the top of the atmosphere (lux); 128000 the solar constant"},
      {"--sun-illuminance",
       &F::sun_illuminance,
       "",
       {},
       "X",
       "the old radiance scale (20 the sun): X x 6400 lux; use --sun-illuminance-lux"},
      {"--coverage", &F::coverage, "clouds.coverage", TO(clouds.coverage), "C", "cloud coverage"},
      {"--cloud-type", &F::cloud_type, "clouds.type", TO(clouds.type), "T",
       "cloud type: 0 stratus, 0.25 stratocumulus, 0.5 altocumulus, 0.75 cumulus, 1 "
       "cumulonimbus"},
      {"--precipitation", &F::precipitation, "clouds.precipitation", TO(clouds.precipitation), "P",
       "precipitation: grows cumulonimbus"},
      {"--density", &F::density, "clouds.density", TO(clouds.density), "D", "cloud density scale"},
      {"--cloud-bottom-m", &F::cloud_bottom_m, "clouds.bottom_altitude_m",
       TO(clouds.bottom_altitude_m), "M", "cloud layer bottom above the ground (m)"},
      {"--cloud-top-m", &F::cloud_top_m, "clouds.top_altitude_m", TO(clouds.top_altitude_m), "M",
       "cloud layer top above the ground (m)"},
      {"--extinction-per-m", &F::extinction_per_m, "clouds.extinction_per_m",
       TO(clouds.extinction_per_m), "X", "cloud extinction at density 1 (1/m)"},
      {"--attenuation", &F::attenuation, "clouds.attenuation", TO(clouds.attenuation), "X",
       "extinction multiplier along view rays"},
      {"--light-attenuation", &F::light_attenuation, "clouds.light_attenuation",
       TO(clouds.light_attenuation), "X", "extinction multiplier along light rays"},
      {"--albedo", &F::albedo, "clouds.albedo", TO(clouds.albedo), "X",
       "cloud single-scattering albedo"},
      {"--g-forward", &F::g_forward, "clouds.phase_g_forward", TO(clouds.phase_g_forward), "G",
       "forward phase lobe asymmetry"},
      {"--g-backward", &F::g_backward, "clouds.phase_g_backward", TO(clouds.phase_g_backward), "G",
       "backward phase lobe asymmetry"},
      {"--lobe-weight", &F::lobe_weight, "clouds.phase_lobe_weight", TO(clouds.phase_lobe_weight),
       "W", "weight of the forward lobe"},
      {"--powder", &F::powder, "clouds.powder_strength", TO(clouds.powder_strength), "X",
       "powder effect strength"},
      {"--ambient", &F::ambient, "clouds.ambient_strength", TO(clouds.ambient_strength), "X",
       "sky ambient light on clouds"},
      {"--two-stream-light",
       &F::two_stream_light,
       "",
       {},
       "true|false",
       "the old switch: true is --cloud-lighting two-stream, false seed; use --cloud-lighting"},
      {"--wind-mps", &F::wind_mps, "clouds.wind_mps", TO(clouds.wind_mps), "E,N",
       "wind velocity (m/s): east, north"},
      {"--wind-shear-mps", &F::wind_shear_mps, "clouds.wind_shear_mps", TO(clouds.wind_shear_mps),
       "E,N", "the wind's growth from the cloud layer's bottom to its top (m/s)"},
      {"--detail-drift-mps", &F::detail_drift_mps, "clouds.detail_drift_mps",
       TO(clouds.detail_drift_mps), "E,N,U",
       "the detail noise's motion over the clouds (m/s): east, north, up"},
      {"--flow-speed-mps", &F::flow_speed_mps, "clouds.flow_speed_mps", TO(clouds.flow_speed_mps),
       "V", "flow map swirls' speed (m/s); 0 = none"},
      {"--high-coverage", &F::high_coverage, "high_clouds.coverage", TO(high_clouds.coverage), "C",
       "second, high volumetric layer's coverage, [0, 1] (0: none)"},
      {"--high-cloud-type", &F::high_cloud_type, "high_clouds.type", TO(high_clouds.type), "T",
       "high layer's cloud type, [0, 1] (as --cloud-type)"},
      {"--high-bottom-m", &F::high_bottom_m, "high_clouds.bottom_altitude_m",
       TO(high_clouds.bottom_altitude_m), "M", "high layer's bottom above the ground (m)"},
      {"--high-top-m", &F::high_top_m, "high_clouds.top_altitude_m", TO(high_clouds.top_altitude_m),
       "M", "high layer's top above the ground (m)"},
      {"--high-wind-mps", &F::high_wind_mps, "high_clouds.wind_mps", TO(high_clouds.wind_mps),
       "E,N", "high layer's wind (m/s): east, north"},
      {"--weather-map", &F::weather_map, "clouds.weather_map", TO(clouds.weather_map), "FILE",
       "weather map PNG (RGBA) instead of the procedural one"},
      {"--cirrus-coverage", &F::cirrus_coverage, "cirrus.coverage", TO(cirrus.coverage), "C",
       "cirrus sheet coverage, [0, 1] (0: none)"},
      {"--cirrus-type", &F::cirrus_type, "cirrus.type", TO(cirrus.type), "T",
       "0 cirrus, 0.5 cirrostratus, 1 cirrocumulus"},
      {"--cirrus-altitude-m", &F::cirrus_altitude_m, "cirrus.altitude_m", TO(cirrus.altitude_m),
       "M", "cirrus sheet altitude above the ground (m), above the cloud layer"},
      {"--weather-evolution-s", &F::weather_evolution_s, "clouds.weather_evolution_s",
       TO(clouds.weather_evolution_s), "S",
       "the procedural weather's clusters form and dissipate over about S seconds of --time-s, "
       ">= 0 (0: static)"},
      {"--time", &F::time, "time", TO(time), "ISO8601",
       "date and time, e.g. 2026-06-21T18:30:00Z: places the sun (unless a --sun-* flag is "
       "given), the moon and the stars"},
      {"--lat-deg", &F::lat_deg, "location.lat_deg", TO(location.lat_deg), "DEG",
       "latitude of the scene, [-90, 90], north positive"},
      {"--lon-deg", &F::lon_deg, "location.lon_deg", TO(location.lon_deg), "DEG",
       "longitude of the scene, [-180, 360], east positive"},
      {"--time-s", &F::time_s, "time_s", TO(time_s), "T", "animation time (s) after --time"},
      {"--seed", &F::seed, "noise_seed", TO(noise_seed), "N", "noise seed, [0, 4294967295]"},
      {"--steps", &F::steps, "quality.primary_steps", TO(quality.primary_steps), "N",
       "march steps through the cloud layer"},
      {"--light-steps", &F::light_steps, "quality.light_steps", TO(quality.light_steps), "N",
       "light march steps towards the sun"},
      {"--march-stride", &F::march_stride, "quality.march_stride", TO(quality.march_stride), "N",
       "animations march one pixel of each NxN block per frame and reproject the rest: 1, 2 or 4"},
      {"--cloud-downsample", &F::cloud_downsample, "quality.cloud_downsample",
       TO(quality.cloud_downsample), "N", "clouds at 1/N of the image resolution per axis"},
      {"--light-volume-km", &F::light_volume_km, "quality.light_volume_km",
       TO(quality.light_volume_km), "KM",
       "light volume half extent (km); 0 = march every light ray"},
      {"--light-shafts", &F::light_shafts, "quality.light_shafts", TO(quality.light_shafts),
       "volumetric|screen|off",
       "light shafts: volumetric (the air's light shadowed by the clouds), screen (seed 002's "
       "screen-space god rays and radial blur) or off (default)"},
      {"--terrain", &F::terrain, "terrain.file", TO(terrain.file), "FILE|mountains",
       "a terrain under the clouds: a heightfield (.png 16-bit grey, .exr, .tif GeoTIFF placed "
       "by its coordinates, .obj mesh) or mountains (procedural)"},
      {"--terrain-extent-m", &F::terrain_extent_m, "terrain.extent_m", TO(terrain.extent_m), "W,H",
       "the terrain's size east-west, north-south (m; PNG, EXR, mountains)"},
      {"--terrain-center-m", &F::terrain_center_m, "terrain.center_m", TO(terrain.center_m), "E,N",
       "the terrain's centre (m; default the origin; not GeoTIFF)"},
      {"--terrain-height-m", &F::terrain_height_m, "terrain.height_m", TO(terrain.height_m), "H",
       "the height of the file's largest value (PNG, EXR) or of the highest peak (mountains), m"},
      {"--terrain-method", &F::terrain_method, "terrain.method", TO(terrain.method),
       "raycast|raster",
       "how the terrain is found: raycast (default; rays walk a pyramid of maxima) or raster "
       "(seed 002's mesh drawn with depth)"},
      {"--mode", &F::mode, "quality.mode", TO(quality.mode), "default|baseline",
       "march algorithm: default, or baseline (the seed's, as written)"},
      {"--cloud-model", &F::cloud_model, "clouds.model", TO(clouds.model),
       "nephele|blinn|gardner|gardner-quadrics|kajiya|nishita",
       "the model drawing the [clouds] layer: nephele (default) or a classical one of seed 004: "
       "blinn (Blinn 1982: a layer of small particles, single scattering), gardner (Gardner "
       "1985: textured ellipsoids, sky plane or cirrus), gardner-quadrics (his impressionistic "
       "scenes: convex objects of a quadric and planes, ray cast), kajiya (Kajiya and Von Herzen "
       "1984: a light "
       "array, then Romberg integration along each eye ray, on nephele's density) or nishita "
       "(Nishita and Nakamae 1996: metaball cumulus, second-order scattering and sky light); "
       "see [classic]"},
      {"--voxel-march", &F::voxel_march, "quality.voxel_march", TO(quality.voxel_march),
       "plain|three-phase",
       "how rays cross the voxel clouds: three-phase (default; SDF sphere tracing across their "
       "empty space) or plain (the noise clouds' march everywhere)"},
      {"--voxel-shadow", &F::voxel_shadow, "quality.voxel_shadow", TO(quality.voxel_shadow),
       "march|sdf-cone",
       "the voxel clouds' shadows: march (default; light march through the density) or "
       "sdf-cone (cone traced through the distance field, soft)"},
      {"--sky", &F::sky, "atmosphere.model", TO(atmosphere.model), "hillaire|preetham|reference",
       "sky model: hillaire (default), preetham (seed 002's analytic sky), reference (brute "
       "force, slow)"},
      {"--turbidity", &F::turbidity, "atmosphere.turbidity", TO(atmosphere.turbidity), "T",
       "Preetham sky's turbidity"},
      {"--conditions", &F::conditions, "conditions.mode", TO(conditions.mode), "off|artist|overlay",
       "time-of-day keyframes (seed 003): artist = instead of the physical sky, overlay = their "
       "fog and stars on top of it"},
      {"--weather", &F::weather, "conditions.weather", TO(conditions.weather), "W",
       "keyframes' weather: 1 good, 0 bad"},
      {"--hour", &F::hour, "conditions.hour", TO(conditions.hour), "H",
       "keyframes' local solar time; default: from --time and --lon-deg"},
      {"--auto-exposure", &F::auto_exposure, "output.auto_exposure", TO(output.auto_exposure),
       "true|false",
       "expose each frame by a meter within --ev100-min..--ev100-max (true, the default) or at "
       "--ev100 (false)"},
      {"--tonemap", &F::tonemap, "output.tonemap", TO(output.tonemap),
       "aces|agx|uncharted2|reinhard|none",
       "the PNG's and the viewer's tone map: aces (default; Narkowicz's fit), agx (Sobotka), "
       "uncharted2 (Hable's filmic curve, the seed's), reinhard (x / (1 + x)) or none (clamped)"},
      {"--ev100", &F::ev100, "output.ev100", TO(output.ev100), "EV",
       "manual exposure at ISO 100, [-20, 30] (15 sunny day, 9 sunset, 4 civil twilight, -2.5 "
       "full moon); turns auto exposure off unless --auto-exposure true"},
      {"--ev100-min", &F::ev100_min, "output.ev100_min", TO(output.ev100_min), "EV",
       "auto exposure's lower limit"},
      {"--ev100-max", &F::ev100_max, "output.ev100_max", TO(output.ev100_max), "EV",
       "auto exposure's upper limit"},
      {"--exposure-compensation-ev", &F::exposure_compensation_ev,
       "output.exposure_compensation_ev", TO(output.exposure_compensation_ev), "EV",
       "auto exposure's compensation; + brightens"},
      {"--adaptation-ev-per-s", &F::adaptation_ev_per_s, "output.adaptation_ev_per_s",
       TO(output.adaptation_ev_per_s), "R",
       "auto exposure's adaptation between the frames of a sequence (EV per second of scene "
       "time); 0 = at once"},
      {"--exposure",
       &F::exposure,
       "",
       {},
       "X",
       "the old linear exposure: --ev100 log2(5333 / X), manual; use --ev100"},
  };
  return specs;
}

#undef TO

[[noreturn]] void fail(const std::string& flag, const std::string& text, const std::string& what) {
  throw InputError(flag + " " + shorten_for_message(text) + ": " + what);
}

// The whole of `text` as a number ("1.5", "-2", "1e-3", "nan"); a leading '+' is allowed.
std::optional<double> to_number(std::string_view text) {
  while (!text.empty() && text.front() == ' ') text.remove_prefix(1);
  while (!text.empty() && text.back() == ' ') text.remove_suffix(1);
  if (text.starts_with('+')) text.remove_prefix(1);
  double value = 0.0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || text.empty()) return {};
  return value;
}

float to_float(const std::string& flag, const std::string& text, std::string_view part) {
  std::optional<double> value = to_number(part);
  if (!value) fail(flag, text, "expected a number");
  if (std::isfinite(*value) && std::fabs(*value) > FLT_MAX) fail(flag, text, "is out of range");
  return static_cast<float>(*value);
}

// Digits, with an optional sign.
bool is_integer_text(std::string_view text) {
  if (text.starts_with('+') || text.starts_with('-')) text.remove_prefix(1);
  return !text.empty() &&
         std::all_of(text.begin(), text.end(), [](char c) { return c >= '0' && c <= '9'; });
}

int64_t to_integer(const std::string& flag, const std::string& text, int64_t min, int64_t max) {
  std::string_view digits = text;
  if (digits.starts_with('+')) digits.remove_prefix(1);
  int64_t value = 0;
  auto [end, error] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (error != std::errc() || end != digits.data() + digits.size() || value < min || value > max)
    fail(flag, text,
         "expected an integer in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  return value;
}

// The comma-separated parts of `text` ("a,,b" is three; "" is one, empty), viewing `text`.
std::vector<std::string_view> split_commas(std::string_view text) {
  std::vector<std::string_view> parts;
  for (size_t comma; (comma = text.find(',')) != std::string_view::npos;) {
    parts.push_back(text.substr(0, comma));
    text.remove_prefix(comma + 1);
  }
  parts.push_back(text);
  return parts;
}

// "E,N,U" into `size` floats.
void to_vector(const std::string& flag, const std::string& text, int size, float* out) {
  static const char* const kComponents[] = {"", "", "E,N", "E,N,U"};
  const std::vector<std::string_view> parts = split_commas(text);
  bool ok = parts.size() == static_cast<size_t>(size);
  for (size_t i = 0; ok && i < parts.size(); ++i) ok = to_number(parts[i]).has_value();
  if (!ok)
    fail(flag, text,
         "expected " + std::to_string(size) + " comma-separated numbers " + kComponents[size]);
  for (int i = 0; i < size; ++i) out[i] = to_float(flag, text, parts[i]);
}

void parse_into(const std::string& flag, const std::string& text, float& out) {
  out = to_float(flag, text, text);
}
void parse_into(const std::string& flag, const std::string& text, int& out) {
  out = static_cast<int>(to_integer(flag, text, INT_MIN, INT_MAX));
}
void parse_into(const std::string& flag, const std::string& text, uint32_t& out) {
  out = static_cast<uint32_t>(to_integer(flag, text, 0, UINT32_MAX));
}
void parse_into(const std::string& flag, const std::string& text, glm::vec2& out) {
  to_vector(flag, text, 2, &out.x);
}
void parse_into(const std::string& flag, const std::string& text, glm::vec3& out) {
  to_vector(flag, text, 3, &out.x);
}
void parse_into(const std::string&, const std::string& text, std::string& out) {
  out = text;
}
void parse_into(const std::string& flag, const std::string& text, bool& out) {
  if (text != "true" && text != "false") fail(flag, text, "expected true or false");
  out = text == "true";
}
void parse_into(const std::string& flag, const std::string& text, MarchMode& out) {
  std::optional<MarchMode> mode = parse_march_mode(text);
  if (!mode) fail(flag, text, "expected default or baseline");
  out = *mode;
}
void parse_into(const std::string& flag, const std::string& text, ConditionsMode& out) {
  std::optional<ConditionsMode> mode = parse_conditions_mode(text);
  if (!mode) fail(flag, text, "expected off, artist or overlay");
  out = *mode;
}
void parse_into(const std::string& flag, const std::string& text, ToneMap& out) {
  std::optional<ToneMap> op = parse_tonemap(text);
  if (!op) fail(flag, text, "expected aces, agx, uncharted2, reinhard or none");
  out = *op;
}
void parse_into(const std::string& flag, const std::string& text, SkyModel& out) {
  std::optional<SkyModel> model = parse_sky_model(text);
  if (!model) fail(flag, text, "expected hillaire, preetham or reference");
  out = *model;
}

void parse_into(const std::string& flag, const std::string& text, VoxelMarch& out) {
  std::optional<VoxelMarch> mode = parse_voxel_march(text);
  if (!mode) fail(flag, text, "expected plain or three-phase");
  out = *mode;
}
void parse_into(const std::string& flag, const std::string& text, CloudModel& out) {
  std::optional<CloudModel> model = parse_cloud_model(text);
  if (!model) fail(flag, text, "expected " + cloud_model_names(false));
  out = *model;
}
void parse_into(const std::string& flag, const std::string& text, VoxelShadow& out) {
  std::optional<VoxelShadow> mode = parse_voxel_shadow(text);
  if (!mode) fail(flag, text, "expected march or sdf-cone");
  out = *mode;
}

constexpr const char* kVoxelCloudFlag = "--voxel-cloud";
constexpr const char* kVoxelCloudForms =
    "expected FILE@E,N,U or preset:NAME[:SEED]@E,N,U, NAME one of cumulus, cumulus-congestus, "
    "cumulonimbus, cumulus-mesh (e.g. preset:cumulus:7@0,4000,1200)";
constexpr std::string_view kPresetPrefix = "preset:";
constexpr const char* kCloudLayerFlag = "--cloud-layer";

// The generated clouds (src/voxel's parse_cloud_preset; validate_scene checks them too, but a
// wrong name is a malformed spec, told with the accepted forms).
bool is_voxel_cloud_preset_name(std::string_view name) {
  for (std::string_view preset : voxel::kCloudPresetNames)
    if (name == preset) return true;
  return false;
}

void check_conflicts(const SceneFlags& flags) {
  if (flags.scene_file && flags.preset)
    throw InputError(
        "--scene and --preset cannot be combined (a scene file can start from a preset with "
        "preset = \"NAME\")");
  if (flags.camera_pos && flags.camera_altitude_m)
    throw InputError(
        "--camera-pos and --camera-altitude-m cannot be combined (the altitude is the position's "
        "up component)");
  if (flags.sun_dir && (flags.sun_elevation_deg || flags.sun_azimuth_deg))
    throw InputError(
        "--sun-dir cannot be combined with --sun-elevation-deg or --sun-azimuth-deg (both set the "
        "sun direction)");
  if (flags.sun_illuminance && flags.sun_illuminance_lux)
    throw InputError(
        "--sun-illuminance cannot be combined with --sun-illuminance-lux (the old scale is "
        "lux / 6400)");
  if (flags.two_stream_light)
    for (const auto& [key, value] : flags.table_values)
      if (key == "clouds.lighting")
        throw InputError(
            "--two-stream-light cannot be combined with --cloud-lighting (true is two-stream, "
            "false seed)");
  if (flags.exposure && flags.ev100)
    throw InputError("--exposure cannot be combined with --ev100 (the old exposure X is EV100 "
                     "log2(5333 / X))");
  const int fov_forms = int(flags.fov_deg.has_value()) + int(flags.hfov_deg.has_value()) +
                        int(flags.focal_length_mm.has_value());
  if (fov_forms > 1)
    throw InputError(
        "--fov-deg, --hfov and --focal-length-mm each set the field of view; give one of them");
}

// --sun-illuminance and --exposure, the old scales, and --two-stream-light, the old lighting
// switch, read as scene files read their keys.
void apply_legacy_light(const SceneFlags& flags, Scene& scene) {
  if (flags.sun_illuminance) {
    const std::string& text = *flags.sun_illuminance;
    const float value = to_float("--sun-illuminance", text, text);
    if (!(value >= 0.0f && value <= 1.0e6f))
      fail("--sun-illuminance", text,
           "must be in [0, 1e+06] (the old radiance scale, read as x 6400 lux; "
           "--sun-illuminance-lux replaces it)");
    scene.sun.illuminance_lux = value * kLegacyLuxPerUnit;
  }
  if (flags.exposure) {
    const std::string& text = *flags.exposure;
    const float value = to_float("--exposure", text, text);
    if (!(value >= 5.0e-6f && value <= 1.0e6f))
      fail("--exposure", text,
           "must be in [5e-06, 1e+06] (the old linear exposure, read as --ev100 log2(5333 / X) "
           "in [-7.55, 30])");
    scene.output.ev100 = float(ev100_from_legacy_exposure(value));
  }
  if (flags.two_stream_light) {
    bool two_stream = false;
    parse_into("--two-stream-light", *flags.two_stream_light, two_stream);
    scene.clouds.lighting = two_stream ? "two-stream" : "seed";
  }
  // A manual exposure turns the meter off unless --auto-exposure says otherwise.
  if ((flags.exposure || flags.ev100) && !flags.auto_exposure) scene.output.auto_exposure = false;
}

// One of --fov-deg, --hfov, --focal-length-mm replaces the scene's field of view, whatever
// form the scene gave it in.
void apply_fov_form(const SceneFlags& flags, Scene& scene) {
  CameraParams& c = scene.camera;
  if (flags.fov_deg) c.horizontal_fov_deg = c.focal_length_mm = 0.0f;
  if (flags.hfov_deg) c.focal_length_mm = 0.0f;
  if (flags.focal_length_mm) c.horizontal_fov_deg = 0.0f;
}

std::string join(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& item : items) out += (out.empty() ? "" : ", ") + item;
  return out;
}

Scene load_base(const SceneFlags& flags) {
  if (flags.scene_file) return load_scene_file(*flags.scene_file);
  std::string name = flags.preset.value_or("default");
  std::vector<std::string> names = preset_names();
  if (std::find(names.begin(), names.end(), name) == names.end())
    throw InputError("--preset '" + shorten_for_message(name) + "': unknown preset (available: " +
                     join(names) + ")");
  return load_preset(name);
}

// --sun-elevation-deg / --sun-azimuth-deg: the angle not given keeps its current value.
void apply_sun_angles(const SceneFlags& flags, Scene& scene) {
  if (!flags.sun_elevation_deg && !flags.sun_azimuth_deg) return;
  SunAngles angles = sun_angles_from_direction(scene.sun.direction);
  if (flags.sun_elevation_deg) {
    const std::string& text = *flags.sun_elevation_deg;
    angles.elevation_deg = to_float("--sun-elevation-deg", text, text);
    if (!(angles.elevation_deg >= -90.0 && angles.elevation_deg <= 90.0))
      fail("--sun-elevation-deg", text, "must be in [-90, 90]");
  }
  if (flags.sun_azimuth_deg) {
    const std::string& text = *flags.sun_azimuth_deg;
    angles.azimuth_deg = to_float("--sun-azimuth-deg", text, text);
    if (!std::isfinite(angles.azimuth_deg)) fail("--sun-azimuth-deg", text, "must be finite");
  }
  scene.sun.direction = sun_direction_from_angles(angles.elevation_deg, angles.azimuth_deg);
}

// Validation names a parameter by its flag when a flag set it, otherwise by its scene key
// prefixed with where the scene came from. The voxel clouds from index `first_flag_cloud` on
// came from --voxel-cloud.
ParamNamer make_namer(const SceneFlags& flags, size_t first_flag_cloud, size_t first_flag_layer) {
  std::map<std::string, std::string> flag_of_key;
  for (const FlagSpec& spec : flag_specs())
    if (*spec.key && (flags.*spec.member).has_value()) flag_of_key[spec.key] = spec.flag;
  for (const auto& [key, value] : flags.table_values)
    flag_of_key[key] = "--" + find_scene_parameter(key)->flag;
  std::string origin =
      flags.scene_file ? *flags.scene_file : "preset '" + flags.preset.value_or("default") + "'";
  return [flag_of_key, origin, first_flag_cloud,
          first_flag_layer](const std::string& key) -> std::string {
    auto found = flag_of_key.find(key);
    if (found != flag_of_key.end()) return found->second;
    size_t index = 0;  // voxel_clouds[index].name, cloud_layers[index].name
    if (std::sscanf(key.c_str(), "voxel_clouds[%zu]", &index) == 1 && index >= first_flag_cloud)
      return kVoxelCloudFlag;
    if (std::sscanf(key.c_str(), "cloud_layers[%zu]", &index) == 1 && index >= first_flag_layer)
      return std::string(kCloudLayerFlag) + " #" + std::to_string(index - first_flag_layer + 1) +
             " " + key.substr(key.find(']') + 2);
    return origin + ": " + key;
  };
}

}  // namespace

VoxelCloudParams parse_voxel_cloud_spec(const std::string& spec) {
  const auto bad = [&](const std::string& why) {
    fail(kVoxelCloudFlag, spec, why + "; " + kVoxelCloudForms);
  };
  // The last '@': a file's name may hold one.
  const size_t at = spec.rfind('@');
  if (at == std::string::npos) bad("no @E,N,U position");
  const std::string source = spec.substr(0, at), position = spec.substr(at + 1);
  VoxelCloudParams cloud;
  const std::vector<std::string_view> parts = split_commas(position);
  if (parts.size() != 3) bad("the position is not 3 comma-separated numbers");
  for (int i = 0; i < 3; ++i) {
    const std::optional<double> value = to_number(parts[size_t(i)]);
    if (!value || (std::isfinite(*value) && std::fabs(*value) > FLT_MAX))
      bad("the position's '" + std::string(parts[size_t(i)]) + "' is not a number");
    cloud.position_m[i] = static_cast<float>(*value);
  }
  if (source.starts_with(kPresetPrefix)) {
    const std::string rest = source.substr(kPresetPrefix.size());
    const size_t colon = rest.find(':');
    cloud.preset = rest.substr(0, colon);
    if (!is_voxel_cloud_preset_name(cloud.preset))
      bad("unknown preset '" + cloud.preset + "'");
    if (colon != std::string::npos) {
      const std::string seed = rest.substr(colon + 1);
      uint32_t value = 0;
      auto [end, error] = std::from_chars(seed.data(), seed.data() + seed.size(), value);
      if (seed.empty() || error != std::errc() || end != seed.data() + seed.size())
        bad("the seed '" + seed + "' is not an integer in [0, 4294967295]");
      cloud.seed = value;
    }
  } else {
    if (source.empty()) bad("no file before the @");
    cloud.file = source;  // as given: relative to the working folder, like --weather-map
  }
  return cloud;
}

CloudLayerParams parse_cloud_layer_spec(const std::string& spec) {
  const auto bad = [&](const std::string& why) {
    fail(kCloudLayerFlag, spec,
         why +
             "; expected GENUS,BASE_M,TOP_M,OKTAS, GENUS one of stratus, stratocumulus, "
             "altocumulus, cumulus, cumulonimbus (e.g. altocumulus,2500,3200,5)");
  };
  const std::vector<std::string_view> parts = split_commas(spec);
  if (parts.size() != 4) bad(std::to_string(parts.size()) + " comma-separated parts");
  CloudLayerParams layer;
  layer.genus = parts[0];
  float* numbers[] = {&layer.base_m, &layer.top_m, &layer.oktas};
  for (size_t i = 0; i < 3; ++i) {
    const std::optional<double> value = to_number(parts[i + 1]);
    if (!value || !std::isfinite(*value) || std::fabs(*value) > FLT_MAX)
      bad("'" + std::string(parts[i + 1]) + "' is not a number");
    *numbers[i] = static_cast<float>(*value);
  }
  return layer;
}

const SceneParameter* find_scene_parameter(std::string_view key) {
  for (const SceneParameter& p : scene_parameters())
    if (p.key == key) return &p;
  return nullptr;
}

std::vector<std::pair<std::string, std::string>> scene_flag_keys() {
  std::vector<std::pair<std::string, std::string>> pairs;
  for (const FlagSpec& spec : flag_specs())
    if (*spec.key) pairs.emplace_back(spec.flag, spec.key);
  for (const SceneParameter& p : scene_parameters())
    if (!p.flag.empty()) pairs.emplace_back("--" + p.flag, p.key);
  return pairs;
}

void add_scene_flags(CLI::App& cmd, SceneFlags& flags) {
  for (const FlagSpec& spec : flag_specs()) {
    auto member = spec.member;
    std::string help = spec.help;
    if (spec.member == &SceneFlags::preset) help += "; one of: " + join(preset_names());
    // What is allowed is declared once, with the scene field the flag sets.
    if (const SceneParameter* p = find_scene_parameter(spec.key); p && !p->allowed_values.empty())
      help += "; allowed: " + p->allowed_values;
    cmd.add_option_function<std::string>(
           spec.flag, [&flags, member](const std::string& value) { flags.*member = value; }, help)
        ->type_name(spec.type_name)
        ->group("Scene");
  }
  // The flags the scene's field table declares: the field's meaning, unit and range are its
  // help, set_scene_value reads the value.
  for (const SceneParameter& p : scene_parameters()) {
    if (p.flag.empty()) continue;
    std::string help = p.meaning;
    if (!p.unit.empty()) help += " (" + p.unit + ")";
    if (!p.allowed_values.empty()) help += "; allowed: " + p.allowed_values;
    std::string type = p.unit.empty() ? "X" : p.unit == "m" ? "M" : "V";
    cmd.add_option_function<std::string>(
           "--" + p.flag,
           [&flags, key = p.key, kind = p.kind](const std::string& value) {
             // A string's or a choice's flag takes the word as typed (--cloud-optics droplets),
             // or a quoted TOML string.
             const bool word = (kind == SceneValueKind::kString || kind == SceneValueKind::kEnum) &&
                               !value.empty() && value[0] != '"' && value[0] != '\'';
             flags.table_values.emplace_back(key, word ? "\"" + value + "\"" : value);
           },
           help)
        ->type_name(type)
        ->group("Scene");
  }
  // Repeatable: a vector option, one value an occurrence (no extra arguments after it).
  cmd.add_option_function<std::vector<std::string>>(
         kVoxelCloudFlag,
         [&flags](const std::vector<std::string>& values) {
           flags.voxel_clouds.insert(flags.voxel_clouds.end(), values.begin(), values.end());
         },
         "add a voxel cloud (repeatable): FILE@E,N,U (an OpenVDB .vdb or NanoVDB .nvdb file) or "
         "preset:NAME[:SEED]@E,N,U (a generated cumulus, cumulus-congestus or cumulonimbus, or cumulus-mesh: the shipped mesh baked), "
         "anchored at its base's centre (m: east, north, up); e.g. preset:cumulus:7@0,4000,1200")
      ->type_name("SPEC")
      ->allow_extra_args(false)
      ->group("Scene");
  cmd.add_option_function<std::vector<std::string>>(
         kCloudLayerFlag,
         [&flags](const std::vector<std::string>& values) {
           flags.cloud_layers.insert(flags.cloud_layers.end(), values.begin(), values.end());
         },
         "add a volumetric layer as a report gives it (repeatable, at most 4 with the scene's "
         "[[cloud_layers]]): GENUS,BASE_M,TOP_M,OKTAS, where its clouds' bases and tops are (m "
         "above the ground) and the sky it covers; e.g. altocumulus,2500,3200,5")
      ->type_name("SPEC")
      ->allow_extra_args(false)
      ->group("Scene");
}

Scene resolve_scene(const SceneFlags& flags) {
  check_conflicts(flags);
  Scene scene = load_base(flags);
  for (const FlagSpec& spec : flag_specs()) {
    const std::optional<std::string>& text = flags.*spec.member;
    if (!text) continue;
    std::visit(
        [&](auto target) {
          if constexpr (!std::is_same_v<decltype(target), std::monostate>) {
            using Value = std::decay_t<decltype(target(scene))>;
            // Not an integer: the values the key allows, not its type's range.
            if constexpr (std::is_same_v<Value, int> || std::is_same_v<Value, uint32_t>)
              if (const SceneParameter* p = find_scene_parameter(spec.key);
                  p && !p->allowed_values.empty() && !is_integer_text(*text))
                fail(spec.flag, *text, nephele::scene_detail::expected_integer(p->allowed_values));
            parse_into(spec.flag, *text, target(scene));
          }
        },
        spec.target);
  }
  for (const auto& [key, value] : flags.table_values) {
    try {
      set_scene_value(scene, key, value);
    } catch (const InputError& e) {  // names the key: name the flag
      fail("--" + find_scene_parameter(key)->flag, value, e.what());
    }
  }
  if (flags.terrain && *flags.terrain == "mountains") {  // the procedural range, not a file
    scene.terrain.file.clear();
    scene.terrain.preset = "mountains";
  } else if (flags.terrain) {
    scene.terrain.preset.clear();
  }
  apply_sun_angles(flags, scene);
  apply_legacy_light(flags, scene);
  apply_fov_form(flags, scene);
  // --metar last: the report's layers, wind, haze and time take precedence, on --time's date.
  for (const auto& [key, value] : flags.table_values)
    if (key == "weather.metar") {
      try {
        weather::apply_metar(scene);
      } catch (const InputError& e) {
        std::string what = e.what();
        if (what.starts_with("weather.metar: ")) what = what.substr(15);
        fail("--metar", scene.weather.metar, what);
      }
    }
  // Then --grib's forecast, over a report.
  for (const auto& [key, value] : flags.table_values)
    if (key == "weather.grib") {
      try {
        weather::apply_grib(scene);
      } catch (const InputError& e) {
        std::string what = e.what();
        if (const size_t at = what.find("': ");
            what.starts_with("weather.grib '") && at != std::string::npos)
          what.erase(0, at + 3);
        fail("--grib", scene.weather.grib, what);
      }
    }
  // Then --wind-from-deg, --wind-speed-kt or -mps and --visibility-m, over a report; the
  // message names the flags.
  try {
    weather::apply_weather_keys(scene);
  } catch (const InputError& e) {
    std::string what = e.what();
    for (const auto& [key, flag] :
         {std::pair<std::string, std::string>{"weather.wind_from_deg", "--wind-from-deg"},
          {"weather.wind_speed_kt", "--wind-speed-kt"},
          {"weather.wind_speed_mps", "--wind-speed-mps"},
          {"weather.visibility_m", "--visibility-m"}})
      for (size_t at; (at = what.find(key)) != std::string::npos;) {
        const bool assigned = what.compare(at + key.size(), 3, " = ") == 0;
        what.replace(at, key.size() + (assigned ? 3 : 0), assigned ? flag + " " : flag);
      }
    throw InputError(what);
  }
  // A sun flag places the sun; otherwise a --time does.
  if (flags.sun_dir || flags.sun_elevation_deg || flags.sun_azimuth_deg)
    scene.sun.from_time = false;
  else if (flags.time)
    scene.sun.from_time = true;
  if (flags.camera_pos && !(scene.camera.position_m.z >= 0.0f))
    fail("--camera-pos", *flags.camera_pos,
         "the up component must be >= 0 (the camera is below the ground)");
  const size_t first_flag_cloud = scene.voxel_clouds.size();
  if (first_flag_cloud + flags.voxel_clouds.size() > size_t(kMaxVoxelClouds))
    throw InputError(std::string(kVoxelCloudFlag) + ": " +
                     std::to_string(first_flag_cloud + flags.voxel_clouds.size()) +
                     " voxel clouds (" + std::to_string(first_flag_cloud) + " in the scene, " +
                     std::to_string(flags.voxel_clouds.size()) + " from " + kVoxelCloudFlag +
                     "): at most " + std::to_string(kMaxVoxelClouds) + " voxel clouds per scene");
  for (const std::string& spec : flags.voxel_clouds)
    scene.voxel_clouds.push_back(parse_voxel_cloud_spec(spec));
  const size_t first_flag_layer = scene.cloud_layers.size();
  for (const std::string& spec : flags.cloud_layers)
    scene.cloud_layers.push_back(parse_cloud_layer_spec(spec));
  validate_scene(scene, make_namer(flags, first_flag_cloud, first_flag_layer));
  return scene;
}

}  // namespace nephele::cli

// nephele — range checks on a resolved scene.
#include <stb/stb_image.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <type_traits>
#include <variant>

#include "image/input_images.h"
#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "nephele/sky.h"
#include "scene/scene_fields.h"
#include "terrain/heightfield.h"
#include "weather/weather_state.h"

namespace nephele {
namespace {

using scene_detail::ends_with_ignoring_case;
using scene_detail::format_float;

// The ranges in which a scene renders finite, meaningful pixels (scene.h documents each).
constexpr float kMaxCameraDistanceM = 1.0e9f;   // 2.6 times the Moon's distance
constexpr float kMinDirectionLength = 1.0e-6f;  // directions are normalised in float
constexpr float kMaxDirectionLength = 1.0e6f;
constexpr double kMaxParticleCells = 5.0e6;   // particle_clouds: the grid (a second to spawn)
// Voxel clouds' anchors (scene.h, VoxelCloudParams::position_m).
constexpr float kMaxVoxelCloudDistanceM = 1.0e7f;
constexpr float kMinVoxelCloudUpM = -1.0e3f;
constexpr float kMaxVoxelCloudUpM = 1.0e5f;
// What a weather map's channels mean (scene.h, CloudParams::weather_map), for messages.
constexpr const char* kWeatherMapNeeds =
    "a weather map needs 4 channels (RGBA: R coverage, G storm cells, B cloud type around "
    "clouds.type, A density)";

// Throws InputError naming a parameter the way the caller wants it named (scene key or flag).
class Checker {
 public:
  explicit Checker(const ParamNamer& namer) : namer_(namer) {}

  // Closed interval [min, max] unless an end is marked open.
  void in_range(const std::string& key, float value, float min, float max, bool min_open = false,
                bool max_open = false) const {
    bool ok = (min_open ? value > min : value >= min) && (max_open ? value < max : value <= max);
    if (!ok)
      fail(key, format_float(value),
           std::string("must be in ") + (min_open ? "(" : "[") + format_float(min) + ", " +
               format_float(max) + (max_open ? ")" : "]"));
  }

  void in_range(const std::string& key, int value, int min, int max) const {
    if (value < min || value > max)
      fail(key, std::to_string(value),
           "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "]");
  }

  // Every component in [min, max].
  template <typename Vector>
  void in_range(const std::string& key, const Vector& v, float min, float max) const {
    for (int i = 0; i < Vector::length(); ++i)
      if (!(v[i] >= min && v[i] <= max))
        fail(key, vector_text(key, v),
             "every component must be in [" + format_float(min) + ", " + format_float(max) + "]");
  }

  template <typename Vector>
  void finite(const std::string& key, const Vector& v) const {
    for (int i = 0; i < Vector::length(); ++i)
      if (!std::isfinite(v[i])) fail(key, vector_text(key, v), "must be finite");
  }

  // A direction is normalised in float on the CPU and the GPU: its length must be such that
  // its squared length neither underflows nor overflows.
  void direction(const std::string& key, const glm::vec3& v) const {
    const double length = std::sqrt(double(v.x) * v.x + double(v.y) * v.y + double(v.z) * v.z);
    if (!(length >= kMinDirectionLength && length <= kMaxDirectionLength))
      fail(key, vector_text(key, v),
           "must be a finite vector of length in [" + format_float(kMinDirectionLength) + ", " +
               format_float(kMaxDirectionLength) + "]");
  }

  // `value` must be below `other` (an altitude, named in the message).
  void below(const std::string& key, float value, const std::string& other_key,
             float other) const {
    if (!(value < other))
      fail(key, format_float(value),
           "must be below " + other_name(other_key) + " (" + format_float(other) + ")");
  }

  // `value` must be at or above `other` (an altitude, named in the message).
  void at_or_above(const std::string& key, float value, const std::string& other_key,
                   float other) const {
    if (!(value >= other))
      fail(key, format_float(value),
           "must be at or above " + other_name(other_key) + " (" + format_float(other) + ")");
  }

  // A regular file that opens (a pipe would block the open, a device be read without end).
  void readable_file(const std::string& key, const std::string& path) const {
    std::error_code error;
    const bool regular = std::filesystem::is_regular_file(path, error);
    if (!regular || !std::ifstream(path, std::ios::binary))
      fail(key, is_flag(key) ? path : scene_detail::toml_quote(path),
           regular || !std::filesystem::exists(path, error) ? "cannot read the file"
                                                            : "is not a regular file");
  }

  // A weather map (CloudParams::weather_map): a readable PNG with four channels or an EXR (read
  // as RGBA whatever it holds), within kMaxWeatherMapSide, told by its header without decoding.
  void weather_map(const std::string& key, const std::string& path) const {
    readable_file(key, path);
    const std::string value = is_flag(key) ? path : scene_detail::toml_quote(path);
    ImageHeader header;
    const std::string why = read_image_header(path, header, kMaxWeatherMapSide);
    // (The one message that says what is allowed already.)
    if (why == kNeitherPngNorExr) fail(key, value, why);
    if (!why.empty()) fail(key, value, why + "; " + weather_map_requirement());
    if (!header.exr && header.channels != 4) {
      static const char* const kLayouts[] = {"", "grey", "grey and alpha", "RGB"};
      const int channels = header.channels;
      fail(key, value,
           "has " + std::to_string(channels) + (channels == 1 ? " channel" : " channels") +
               (channels >= 1 && channels <= 3 ? std::string(" (") + kLayouts[channels] + ")"
                                               : std::string()) +
               "; " + kWeatherMapNeeds);
    }
  }

  bool is_flag(const std::string& key) const { return display(key).flag; }

  [[noreturn]] void fail(const std::string& key, const std::string& value,
                         const std::string& what) const {
    Display shown = display(key);
    throw InputError(shown.name + (shown.flag ? " " : " = ") + shorten_for_message(value) + ": " +
                     what);
  }

  // "(0, 1, 0.25)" for a scene key, "0,1,0.25" for a flag (as it would be typed).
  template <typename Vector>
  std::string vector_text(const std::string& key, const Vector& v) const {
    bool flag = is_flag(key);
    std::string text = flag ? "" : "(";
    for (int i = 0; i < Vector::length(); ++i)
      text += (i == 0 ? "" : (flag ? "," : ", ")) + format_float(v[i]);
    return flag ? text : text + ")";
  }

 private:
  struct Display {
    std::string name;
    bool flag = false;  // a command-line flag: "--x value" rather than "key = value"
  };

  Display display(const std::string& key) const {
    std::string name = namer_ ? namer_(key) : std::string();
    if (name.empty()) return {key, false};
    return {name, name.starts_with("--")};
  }

  // Another parameter named inside a message: its flag when a flag set it, else its key (the
  // message already says which file it is about).
  std::string other_name(const std::string& key) const {
    Display shown = display(key);
    return shown.flag ? shown.name : key;
  }

  const ParamNamer& namer_;
};

// One field's own rule as its table declares it (scene_fields.cpp): its range, with its "off"
// value, or its choices. The rules between fields follow below, by hand.
template <typename T>
void check_declared(const Checker& check, const std::string& key, const T& value,
                    const scene_detail::Range& range, const std::vector<std::string_view>& choices,
                    const std::string& allowed) {
  if constexpr (std::is_same_v<T, float>) {
    if (range.given && !(range.has_off && value == float(range.off)))
      check.in_range(key, value, float(range.min), float(range.max), range.min_open,
                     range.max_open);
  } else if constexpr (std::is_same_v<T, int> || std::is_same_v<T, uint32_t>) {
    const std::string text = std::to_string(value);
    if (!choices.empty() && std::find(choices.begin(), choices.end(), text) == choices.end())
      check.fail(key, text, "must be " + allowed);
    if (range.given && !(range.has_off && double(value) == range.off))
      check.in_range(key, int(value), int(range.min), int(range.max));
  } else if constexpr (std::is_same_v<T, glm::vec2> || std::is_same_v<T, glm::vec3>) {
    if (range.given) check.in_range(key, value, float(range.min), float(range.max));
  } else if constexpr (std::is_same_v<T, std::string>) {
    if (!choices.empty() && std::find(choices.begin(), choices.end(), value) == choices.end())
      check.fail(key, check.is_flag(key) ? value : scene_detail::toml_quote(value),
                 "must be " + allowed);
  }
}

// Every field of the scene's table against its declared rule.
void check_declared_fields(const Checker& check, const Scene& scene) {
  // The accessors hand out references into a Scene; this only reads through them.
  Scene& fields = const_cast<Scene&>(scene);
  for (const scene_detail::Section& section : scene_detail::scene_sections())
    for (const scene_detail::Field& field : section.fields) {
      if (!field.range.given && field.choices.empty()) continue;
      const std::string key = section.name.empty()
                                  ? std::string(field.name)
                                  : std::string(section.name) + "." + std::string(field.name);
      std::visit(
          [&](auto access) {
            check_declared(check, key, access(fields), field.range, field.choices,
                           scene_detail::allowed_text(field));
          },
          field.access);
    }
}

void check_camera(const Checker& check, const CameraParams& camera) {
  check.finite("camera.position_m", camera.position_m);
  const glm::vec3 p = camera.position_m;
  if (!(std::abs(p.x) <= kMaxCameraDistanceM && std::abs(p.y) <= kMaxCameraDistanceM))
    check.fail("camera.position_m", check.vector_text("camera.position_m", p),
               "east and north must be in [-" + format_float(kMaxCameraDistanceM) + ", " +
                   format_float(kMaxCameraDistanceM) + "] m");
  if (!(camera.position_m.z >= 0.0f))
    check.fail("camera.altitude_m", format_float(camera.position_m.z),
               "must be >= 0 (the camera is below the ground)");
  check.in_range("camera.altitude_m", camera.position_m.z, 0.0f, kMaxCameraDistanceM);
  check.direction("camera.view_dir", camera.view_dir);
  if (camera.horizontal_fov_deg != 0.0f && camera.focal_length_mm != 0.0f)
    check.fail("camera.focal_length_mm", format_float(camera.focal_length_mm),
               "camera.horizontal_fov_deg (" + format_float(camera.horizontal_fov_deg) +
                   ") is given too; give one of fov_deg, horizontal_fov_deg, focal_length_mm");
}

void check_sun(const Checker& check, const SunParams& sun) {
  check.direction("sun.direction", sun.direction);
}

void check_atmosphere(const Checker& check, const AtmosphereParams& atmosphere) {
  // Extinction is scattering plus absorption, so it cannot be smaller.
  if (!(atmosphere.mie_extinction_per_m >= atmosphere.mie_scattering_per_m))
    check.fail("atmosphere.mie_extinction_per_m", format_float(atmosphere.mie_extinction_per_m),
               "must be >= atmosphere.mie_scattering_per_m (" +
                   format_float(atmosphere.mie_scattering_per_m) + ")");
  if (atmosphere.model != SkyModel::Hillaire && atmosphere.model != SkyModel::Preetham &&
      atmosphere.model != SkyModel::Reference)
    check.fail("atmosphere.model", std::to_string(static_cast<int>(atmosphere.model)),
               "must be hillaire, preetham or reference");
}

// The top of the highest volumetric layer that is there, and its key.
struct LayerTop {
  const char* key;
  float altitude_m;
};
LayerTop highest_layer_top(const Scene& scene) {
  LayerTop top{"clouds.top_altitude_m", scene.clouds.top_altitude_m};
  if (scene.high_clouds.coverage > 0.0f)
    top = {"high_clouds.top_altitude_m", scene.high_clouds.top_altitude_m};
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (int i = 0; i < kMaxCloudLayers - 2; ++i)
      k.push_back(scene_detail::cloud_layer_key(size_t(i)) + ".top_m");
    return k;
  }();
  for (size_t i = 0; i < scene.cloud_layers.size() && i < keys.size(); ++i)
    if (scene.cloud_layers[i].oktas > 0.0f && scene.cloud_layers[i].top_m > top.altitude_m)
      top = {keys[i].c_str(), scene.cloud_layers[i].top_m};
  return top;
}

// [[cloud_layers]]: each table's declared rules, its base below its top, and the clouds of
// those that are there apart from each other and from the clouds of clouds and high_clouds
// (where their type and coverage put them in their shells; all of a storm's shell).
void check_cloud_layers(const Checker& check, const Scene& scene) {
  const std::vector<CloudLayerParams>& layers = scene.cloud_layers;
  if (layers.size() > size_t(kMaxCloudLayers - 2))
    check.fail(
        "cloud_layers", std::to_string(layers.size()) + " layers",
        "at most " + std::to_string(kMaxCloudLayers - 2) + " besides clouds and high_clouds");
  struct Span {
    std::string name;  // as the message says it
    glm::vec2 m;       // bottom, top above the ground
    std::string note = "";
  };
  // Where the clouds of clouds and high_clouds are in their shells (their genus and coverage
  // fill part of it); a storm's cells fill all of clouds'.
  std::vector<Span> taken;
  const CloudParams& c = scene.clouds;
  const glm::vec2 low_m(c.bottom_altitude_m, c.top_altitude_m);
  const char* where = ", where its type and coverage put them in its shell";
  if (c.precipitation > 0.0f)
    taken.push_back({"clouds' shell", low_m, ", which its storm cells fill"});
  else if (c.coverage > 0.0f)
    taken.push_back(
        {"clouds' clouds", weather::clouds_in_shell_m(c.type, c.coverage, low_m), where});
  const HighCloudParams& h = scene.high_clouds;
  if (h.coverage > 0.0f)
    taken.push_back(
        {"high_clouds' clouds",
         weather::clouds_in_shell_m(h.type, h.coverage, {h.bottom_altitude_m, h.top_altitude_m}),
         where});
  for (size_t i = 0; i < layers.size(); ++i) {
    const std::string prefix = scene_detail::cloud_layer_key(i);
    CloudLayerParams& fields = const_cast<CloudLayerParams&>(layers[i]);  // read only
    for (const scene_detail::CloudLayerField& field : scene_detail::cloud_layer_fields())
      std::visit(
          [&](auto access) {
            check_declared(check, prefix + "." + std::string(field.name), access(fields),
                           field.range, field.choices, scene_detail::allowed_text(field));
          },
          field.access);
    const CloudLayerParams& l = layers[i];
    check.below(prefix + ".base_m", l.base_m, prefix + ".top_m", l.top_m);
    if (!(l.oktas > 0.0f)) continue;
    for (const Span& other : taken)
      if (l.base_m < other.m.y && other.m.x < l.top_m)
        check.fail(prefix + ".base_m", format_float(l.base_m),
                   "its clouds (" + format_float(l.base_m) + "-" + format_float(l.top_m) +
                       " m) overlap " + other.name + " (" + format_float(std::round(other.m.x)) +
                       "-" + format_float(std::round(other.m.y)) + " m" + other.note +
                       "); layers that are there lie apart");
    taken.push_back({prefix + "'s clouds", {l.base_m, l.top_m}});
  }
}

void check_cirrus(const Checker& check, const CirrusParams& cirrus, const Scene& scene) {
  const LayerTop top = highest_layer_top(scene);
  if (cirrus.coverage > 0.0f)  // a sheet that is there sits above the volumetric layers
    check.below(top.key, top.altitude_m, "cirrus.altitude_m", cirrus.altitude_m);
}

void check_high_clouds(const Checker& check, const HighCloudParams& high,
                       const CloudParams& clouds) {
  check.below("high_clouds.bottom_altitude_m", high.bottom_altitude_m,
              "high_clouds.top_altitude_m", high.top_altitude_m);
  if (high.coverage > 0.0f)  // a layer that is there lies wholly above the low one
    check.at_or_above("high_clouds.bottom_altitude_m", high.bottom_altitude_m,
                      "clouds.top_altitude_m", clouds.top_altitude_m);
}

void check_clouds(const Checker& check, const CloudParams& clouds) {
  check.below("clouds.bottom_altitude_m", clouds.bottom_altitude_m, "clouds.top_altitude_m",
              clouds.top_altitude_m);
  if (!clouds.weather_map.empty()) check.weather_map("clouds.weather_map", clouds.weather_map);
  // With droplets the seed's optical keys mean nothing: one that was changed is refused,
  // naming what replaced it.
  if (clouds.optics == "droplets") {
    const CloudParams seed;
    const std::string why =
        "with clouds.optics = \"droplets\" the clouds' extinction, albedo and phase come from "
        "[droplets] (each genus' liquid water content and droplet radius); set clouds.optics = "
        "\"seed\" to use this key";
    struct Key {
      const char* name;
      float value, seed_default;
    };
    const Key keys[] = {
        {"clouds.extinction_per_m", clouds.extinction_per_m, seed.extinction_per_m},
        {"clouds.albedo", clouds.albedo, seed.albedo},
        {"clouds.phase_g_forward", clouds.phase_g_forward, seed.phase_g_forward},
        {"clouds.phase_g_backward", clouds.phase_g_backward, seed.phase_g_backward},
        {"clouds.phase_lobe_weight", clouds.phase_lobe_weight, seed.phase_lobe_weight}};
    for (const Key& k : keys)
      if (k.value != k.seed_default) check.fail(k.name, format_float(k.value), why);
  }
}

// Virga ends below the base it falls from.
void check_precipitation(const Checker& check, const Scene& scene) {
  if (scene.precipitation.rate_mm_per_h > 0.0f)
    check.below("precipitation.bottom_m", scene.precipitation.bottom_m, "clouds.bottom_altitude_m",
                scene.clouds.bottom_altitude_m);
}

// The cloud layer must lie inside the atmosphere the sky is integrated over.
void check_layers(const Checker& check, const Scene& scene) {
  float atmosphere_top_m = scene.atmosphere.atmosphere_height_km * 1000.0f;
  const LayerTop top = highest_layer_top(scene);
  if (!(top.altitude_m < atmosphere_top_m))
    check.fail(top.key, format_float(top.altitude_m),
               "must be below the top of the atmosphere (atmosphere.atmosphere_height_km = " +
                   format_float(scene.atmosphere.atmosphere_height_km) + ", i.e. " +
                   format_float(atmosphere_top_m) + " m)");
}

void check_quality(const Checker& check, const QualityParams& quality) {
  if (quality.mode != MarchMode::Default && quality.mode != MarchMode::Baseline)
    check.fail("quality.mode", std::to_string(static_cast<int>(quality.mode)),
               "must be default or baseline");
  if (quality.voxel_march != VoxelMarch::Plain && quality.voxel_march != VoxelMarch::ThreePhase)
    check.fail("quality.voxel_march", std::to_string(static_cast<int>(quality.voxel_march)),
               "must be plain or three-phase");
  if (quality.voxel_shadow != VoxelShadow::LightMarch &&
      quality.voxel_shadow != VoxelShadow::SdfCone)
    check.fail("quality.voxel_shadow", std::to_string(static_cast<int>(quality.voxel_shadow)),
               "must be march or sdf-cone");
}

// The classical models (seed 004): checked whichever model draws, so a scene file stays valid
// when its model changes.
void check_classic(const Checker& check, const CloudParams& clouds, const ClassicCloudParams& c) {
  if (parse_cloud_model(to_string(clouds.model)) != clouds.model)
    check.fail("clouds.model", std::to_string(static_cast<int>(clouds.model)),
               "must be " + cloud_model_names(false));
  const std::string& phase = c.blinn_phase;
  if (phase == "hg")
    check.in_range("classic.blinn_phase_x", c.blinn_phase_x, -1.0f, 1.0f, true, true);
  else
    check.in_range("classic.blinn_phase_x", c.blinn_phase_x, -1.0f, 1.0f);
  check.in_range("classic.nishita_clouds", c.nishita_clouds, 1, std::min(64, std::max(c.nishita_metaballs, 1)));
}

// The particle clouds' grid: bounded so that spawning a field takes seconds, not hours.
void check_particle_clouds(const Checker& check, const ParticleCloudParams& p) {
  check.below("particle_clouds.bottom_altitude_m", p.bottom_altitude_m,
              "particle_clouds.top_altitude_m", p.top_altitude_m);
  if (p.coverage <= 0.0f) return;
  // The grid's cells over the field: pi R^2 x height / cell^3.
  const double cells = 3.14159265 * double(p.field_radius_m) * p.field_radius_m *
                       std::max(double(p.top_altitude_m - p.bottom_altitude_m), double(p.cell_m)) /
                       (double(p.cell_m) * p.cell_m * p.cell_m);
  if (cells > kMaxParticleCells)
    check.fail("particle_clouds.cell_m", format_float(p.cell_m),
               "the field would hold " + format_float(float(cells)) + " cells, at most " +
                   format_float(float(kMaxParticleCells)) +
                   " (raise cell_m or lower field_radius_m)");
}

void check_lab(const Checker& check, const LabParams& lab) {
  if (!lab.grid.empty()) check.readable_file("lab.grid", lab.grid);
}

// A string value as messages show it: quoted for a scene key, as typed for a flag.
std::string string_text(const Checker& check, const std::string& key, const std::string& value) {
  return check.is_flag(key) ? value : scene_detail::toml_quote(value);
}

void check_terrain(const Checker& check, const TerrainParams& t) {
  const auto text = [&](const std::string& key, const std::string& value) {
    return check.is_flag(key) ? value : scene_detail::toml_quote(value);
  };
  if (!t.file.empty() && !t.preset.empty())
    check.fail("terrain.file", text("terrain.file", t.file),
               "terrain.preset = " + scene_detail::toml_quote(t.preset) +
                   " is given too; give at most one of file and preset");
  if (!t.preset.empty() && t.preset != "mountains")
    check.fail("terrain.preset", text("terrain.preset", t.preset), "must be mountains (or empty: none)");
  if (!t.file.empty()) {
    if (!terrain::has_heightfield_extension(t.file))
      check.fail("terrain.file", text("terrain.file", t.file), terrain::kHeightfieldExtensions);
    check.readable_file("terrain.file", t.file);
    if (const std::string why = terrain::heightfield_file_problem(t.file); !why.empty())
      check.fail("terrain.file", text("terrain.file", t.file), why);
  }
  if (!t.albedo_map.empty()) {
    if (!ends_with_ignoring_case(t.albedo_map, ".png") && !ends_with_ignoring_case(t.albedo_map, ".exr"))
      check.fail("terrain.albedo_map", text("terrain.albedo_map", t.albedo_map), "must name a .png (sRGB) or .exr (linear) image");
    check.readable_file("terrain.albedo_map", t.albedo_map);
    if (const std::string why = albedo_map_problem(t.albedo_map); !why.empty())
      check.fail("terrain.albedo_map", text("terrain.albedo_map", t.albedo_map),
                 why + "; an albedo map is a PNG or an EXR of at most " + std::to_string(kMaxAlbedoMapSide) +
                     " x " + std::to_string(kMaxAlbedoMapSide) + " pixels");
  }
  for (int i = 0; i < 2; ++i)
    if (!(t.extent_m[i] > 0.0f && t.extent_m[i] <= 1.0e6f))
      check.fail("terrain.extent_m", check.vector_text("terrain.extent_m", t.extent_m),
                 "each component must be in (0, 1e6] (east-west, north-south, m)");
}

void check_voxel_cloud(const Checker& check, const VoxelCloudParams& cloud, size_t index) {
  const std::string prefix = scene_detail::voxel_cloud_key(index);
  const std::string file_key = prefix + ".file", preset_key = prefix + ".preset";
  if (cloud.file.empty() && cloud.preset.empty())
    check.fail(preset_key, string_text(check, preset_key, cloud.preset),
               "a voxel cloud needs exactly one of file (.vdb or .nvdb) and preset (cumulus, "
               "cumulus-congestus, cumulonimbus or cumulus-mesh); neither is given");
  if (!cloud.file.empty() && !cloud.preset.empty())
    check.fail(file_key, string_text(check, file_key, cloud.file),
               "preset = " + scene_detail::toml_quote(cloud.preset) +
                   " is given too; give exactly one of file and preset");
  if (!cloud.preset.empty() && !scene_detail::is_voxel_cloud_preset(cloud.preset))
    check.fail(preset_key, string_text(check, preset_key, cloud.preset),
               "must be cumulus, cumulus-congestus, cumulonimbus or cumulus-mesh");
  if (!cloud.file.empty()) {
    // The importer reads the grids and reports what is wrong inside; here only what the
    // name and the file system tell.
    if (!ends_with_ignoring_case(cloud.file, ".vdb") &&
        !ends_with_ignoring_case(cloud.file, ".nvdb"))
      check.fail(file_key, string_text(check, file_key, cloud.file),
                 "must be an OpenVDB (.vdb) or NanoVDB (.nvdb) file");
    check.readable_file(file_key, cloud.file);
  }
  const std::string position_key = prefix + ".position_m";
  const glm::vec3 p = cloud.position_m;
  check.finite(position_key, p);
  if (!(std::abs(p.x) <= kMaxVoxelCloudDistanceM && std::abs(p.y) <= kMaxVoxelCloudDistanceM))
    check.fail(position_key, check.vector_text(position_key, p),
               "east and north must be in [-" + format_float(kMaxVoxelCloudDistanceM) + ", " +
                   format_float(kMaxVoxelCloudDistanceM) + "] m");
  if (!(p.z >= kMinVoxelCloudUpM && p.z <= kMaxVoxelCloudUpM))
    check.fail(position_key, check.vector_text(position_key, p),
               "up must be in [" + format_float(kMinVoxelCloudUpM) + ", " +
                   format_float(kMaxVoxelCloudUpM) + "] m");
  VoxelCloudParams& fields = const_cast<VoxelCloudParams&>(cloud);  // read only
  for (const scene_detail::VoxelField& field : scene_detail::voxel_cloud_fields())
    if (field.range.given)
      std::visit(
          [&](auto access) {
            check_declared(check, prefix + "." + std::string(field.name), access(fields),
                           field.range, {}, "");
          },
          field.access);
}

void check_voxel_clouds(const Checker& check, const std::vector<VoxelCloudParams>& clouds) {
  if (clouds.size() > size_t(kMaxVoxelClouds))
    check.fail("voxel_clouds", std::to_string(clouds.size()) + " clouds",
               "at most " + std::to_string(kMaxVoxelClouds) + " voxel clouds per scene");
  for (size_t i = 0; i < clouds.size(); ++i) check_voxel_cloud(check, clouds[i], i);
}

void check_output(const Checker& check, const OutputParams& output) {
  if (!(output.ev100_min <= output.ev100_max))
    check.fail("output.ev100_min", format_float(output.ev100_min),
               "must be <= output.ev100_max (" + format_float(output.ev100_max) + ")");
  if (parse_tonemap(to_string(output.tonemap)) != output.tonemap)
    check.fail("output.tonemap", std::to_string(static_cast<int>(output.tonemap)),
               "must be aces, agx, uncharted2, reinhard or none");
}

void check_conditions(const Checker& check, const Scene& scene) {
  const ConditionsParams& c = scene.conditions;
  if (c.mode != ConditionsMode::Off && c.mode != ConditionsMode::Artist &&
      c.mode != ConditionsMode::Overlay)
    check.fail("conditions.mode", std::to_string(static_cast<int>(c.mode)),
               "must be off, artist or overlay");
  if (c.mode != ConditionsMode::Off && c.hour == -1.0f && scene.time.empty())
    check.fail("conditions.hour", "-1",
               "the keyframes need a time of day: give an hour in [0, 24) or a time");
  for (const auto& [table, name] : {std::pair{&c.good, "conditions.good"}, {&c.bad, "conditions.bad"}})
    if (std::string problem = validate_table(*table, name); !problem.empty()) throw InputError(problem);
}

// The date, the place, and the sun placed by them.
void check_time(const Checker& check, const Scene& scene) {
  const std::string time_text =
      check.is_flag("time") ? scene.time : scene_detail::toml_quote(scene.time);
  if (!scene.time.empty() && !julian_day_from_iso8601(scene.time))
    check.fail("time", time_text,
               "must be an ISO 8601 date and time with a zone, like 2026-06-21T18:30:00Z");
  if (scene.sun.from_time && scene.time.empty())
    check.fail("time", time_text,
               "the sun is placed by the date (sun.from_time = true): give a date and time "
               "like 2026-06-21T18:30:00Z, or a sun direction");
}

}  // namespace

void validate_scene(const Scene& scene, const ParamNamer& display_name) {
  Checker check(display_name);
  check_declared_fields(check, scene);
  check_camera(check, scene.camera);
  check_sun(check, scene.sun);
  check_atmosphere(check, scene.atmosphere);
  check_clouds(check, scene.clouds);
  check_high_clouds(check, scene.high_clouds, scene.clouds);
  check_cloud_layers(check, scene);
  check_cirrus(check, scene.cirrus, scene);
  check_layers(check, scene);
  check_precipitation(check, scene);
  check_quality(check, scene.quality);
  check_output(check, scene.output);
  check_voxel_clouds(check, scene.voxel_clouds);
  check_lab(check, scene.lab);
  check_terrain(check, scene.terrain);
  check_particle_clouds(check, scene.particle_clouds);
  check_classic(check, scene.clouds, scene.classic);
  check_conditions(check, scene);
  check_time(check, scene);
}

}  // namespace nephele

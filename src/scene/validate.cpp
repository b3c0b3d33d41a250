// nephele — range checks on a resolved scene.
#include <stb/stb_image.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "nephele/sky.h"
#include "scene/scene_fields.h"
#include "image/input_images.h"
#include "terrain/heightfield.h"

namespace nephele {
namespace {

using scene_detail::ends_with_ignoring_case;
using scene_detail::format_float;

// The ranges in which a scene renders finite, meaningful pixels (scene.h documents each).
constexpr float kMaxCameraDistanceM = 1.0e9f;   // 2.6 times the Moon's distance
constexpr float kMaxAltitudeM = 1.0e6f;         // cloud layers and cirrus (and below the top)
constexpr float kMinDirectionLength = 1.0e-6f;  // directions are normalised in float
constexpr float kMaxDirectionLength = 1.0e6f;
constexpr float kMaxIlluminanceLux = 1.0e10f;    // sun.illuminance_lux (the old scale's 1e6 and more)
constexpr float kMinEv100 = -20.0f;              // output.ev100 and its auto limits
constexpr float kMaxEv100 = 30.0f;
constexpr double kMaxParticleCells = 5.0e6;   // particle_clouds: the grid (a second to spawn)
constexpr float kMaxFactor = 100.0f;             // extinction and light multipliers on clouds
constexpr float kMaxAirCoefficientPerM = 0.01f;  // 100 m of air has optical depth 1
constexpr float kMaxWindMps = 200.0f;
// Voxel clouds' anchors (scene.h, VoxelCloudParams::position_m).
constexpr float kMaxVoxelCloudDistanceM = 1.0e7f;
constexpr float kMinVoxelCloudUpM = -1.0e3f;
constexpr float kMaxVoxelCloudUpM = 1.0e5f;
// Animation time: winds of kMaxWindMps carry the clouds 2e8 m, where float keeps ~16 m steps.
constexpr float kMaxTimeS = 1.0e6f;
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

  // A wind velocity (m/s): every component in [-kMaxWindMps, kMaxWindMps].
  template <typename Vector>
  void wind(const std::string& key, const Vector& v) const {
    in_range(key, v, -kMaxWindMps, kMaxWindMps);
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
  check.in_range("camera.fov_deg", camera.fov_deg, 0.01f, 180.0f, false, true);
  if (camera.horizontal_fov_deg != 0.0f)
    check.in_range("camera.horizontal_fov_deg", camera.horizontal_fov_deg, 0.01f, 180.0f, false,
                   true);
  if (camera.focal_length_mm != 0.0f)
    check.in_range("camera.focal_length_mm", camera.focal_length_mm, 0.1f, 1.0e5f);
  check.in_range("camera.sensor_width_mm", camera.sensor_width_mm, 1.0f, 1000.0f);
  if (camera.horizontal_fov_deg != 0.0f && camera.focal_length_mm != 0.0f)
    check.fail("camera.focal_length_mm", format_float(camera.focal_length_mm),
               "camera.horizontal_fov_deg (" + format_float(camera.horizontal_fov_deg) +
                   ") is given too; give one of fov_deg, horizontal_fov_deg, focal_length_mm");
  check.in_range("camera.roll_deg", camera.roll_deg, -180.0f, 180.0f);
}

void check_sun(const Checker& check, const SunParams& sun) {
  check.direction("sun.direction", sun.direction);
  check.in_range("sun.illuminance_lux", sun.illuminance_lux, 0.0f, kMaxIlluminanceLux);
  check.in_range("sun.disk_angular_radius_deg", sun.disk_angular_radius_deg, 0.0f, 20.0f);
}

void check_atmosphere(const Checker& check, const AtmosphereParams& atmosphere) {
  check.in_range("atmosphere.planet_radius_km", atmosphere.planet_radius_km, 1000.0f, 10000.0f);
  check.in_range("atmosphere.atmosphere_height_km", atmosphere.atmosphere_height_km, 1.0f,
                 1000.0f);
  check.in_range("atmosphere.rayleigh_scattering_per_m", atmosphere.rayleigh_scattering_per_m,
                 0.0f, kMaxAirCoefficientPerM);
  check.in_range("atmosphere.rayleigh_scale_height_m", atmosphere.rayleigh_scale_height_m, 100.0f,
                 100000.0f);
  check.in_range("atmosphere.mie_scattering_per_m", atmosphere.mie_scattering_per_m, 0.0f,
                 kMaxAirCoefficientPerM);
  check.in_range("atmosphere.mie_extinction_per_m", atmosphere.mie_extinction_per_m, 0.0f,
                 kMaxAirCoefficientPerM);
  // Extinction is scattering plus absorption, so it cannot be smaller.
  if (!(atmosphere.mie_extinction_per_m >= atmosphere.mie_scattering_per_m))
    check.fail("atmosphere.mie_extinction_per_m", format_float(atmosphere.mie_extinction_per_m),
               "must be >= atmosphere.mie_scattering_per_m (" +
                   format_float(atmosphere.mie_scattering_per_m) + ")");
  check.in_range("atmosphere.mie_scale_height_m", atmosphere.mie_scale_height_m, 100.0f,
                 100000.0f);
  check.in_range("atmosphere.mie_g", atmosphere.mie_g, 0.0f, 0.999f);
  check.in_range("atmosphere.view_samples", atmosphere.view_samples, 1, 256);
  if (atmosphere.model != SkyModel::Hillaire && atmosphere.model != SkyModel::Preetham &&
      atmosphere.model != SkyModel::Reference)
    check.fail("atmosphere.model", std::to_string(static_cast<int>(atmosphere.model)),
               "must be hillaire, preetham or reference");
  check.in_range("atmosphere.ozone_absorption_per_m", atmosphere.ozone_absorption_per_m, 0.0f,
                 kMaxAirCoefficientPerM);
  check.in_range("atmosphere.ozone_peak_altitude_m", atmosphere.ozone_peak_altitude_m, 0.0f,
                 1.0e6f);
  check.in_range("atmosphere.ozone_half_width_m", atmosphere.ozone_half_width_m, 0.0f, 1.0e6f);
  check.in_range("atmosphere.ground_albedo", atmosphere.ground_albedo, 0.0f, 1.0f);
  check.in_range("atmosphere.turbidity", atmosphere.turbidity, 2.0f, 10.0f);
}

// The top of the highest volumetric layer that is there, and its key.
struct LayerTop {
  const char* key;
  float altitude_m;
};
LayerTop highest_layer_top(const Scene& scene) {
  if (scene.high_clouds.coverage > 0.0f)
    return {"high_clouds.top_altitude_m", scene.high_clouds.top_altitude_m};
  return {"clouds.top_altitude_m", scene.clouds.top_altitude_m};
}

void check_cirrus(const Checker& check, const CirrusParams& cirrus, const Scene& scene) {
  check.in_range("cirrus.altitude_m", cirrus.altitude_m, 0.0f, kMaxAltitudeM);
  const LayerTop top = highest_layer_top(scene);
  if (cirrus.coverage > 0.0f)  // a sheet that is there sits above the volumetric layers
    check.below(top.key, top.altitude_m, "cirrus.altitude_m", cirrus.altitude_m);
  check.in_range("cirrus.coverage", cirrus.coverage, 0.0f, 1.0f);
  check.in_range("cirrus.type", cirrus.type, 0.0f, 1.0f);
  check.in_range("cirrus.optical_depth", cirrus.optical_depth, 0.0f, 4.0f);
  check.wind("cirrus.wind_mps", cirrus.wind_mps);
}

void check_high_clouds(const Checker& check, const HighCloudParams& high,
                       const CloudParams& clouds) {
  check.in_range("high_clouds.coverage", high.coverage, 0.0f, 1.0f);
  check.in_range("high_clouds.type", high.type, 0.0f, 1.0f);
  check.in_range("high_clouds.density", high.density, 0.0f, 1.0f);
  check.wind("high_clouds.wind_mps", high.wind_mps);
  check.in_range("high_clouds.bottom_altitude_m", high.bottom_altitude_m, 0.0f, kMaxAltitudeM);
  check.in_range("high_clouds.top_altitude_m", high.top_altitude_m, 0.0f, kMaxAltitudeM);
  check.below("high_clouds.bottom_altitude_m", high.bottom_altitude_m,
              "high_clouds.top_altitude_m", high.top_altitude_m);
  if (high.coverage > 0.0f)  // a layer that is there lies wholly above the low one
    check.at_or_above("high_clouds.bottom_altitude_m", high.bottom_altitude_m,
                      "clouds.top_altitude_m", clouds.top_altitude_m);
}

void check_clouds(const Checker& check, const CloudParams& clouds) {
  check.in_range("clouds.bottom_altitude_m", clouds.bottom_altitude_m, 0.0f, kMaxAltitudeM);
  check.in_range("clouds.top_altitude_m", clouds.top_altitude_m, 0.0f, kMaxAltitudeM);
  check.below("clouds.bottom_altitude_m", clouds.bottom_altitude_m, "clouds.top_altitude_m",
              clouds.top_altitude_m);
  check.in_range("clouds.coverage", clouds.coverage, 0.0f, 1.0f);
  check.in_range("clouds.type", clouds.type, 0.0f, 1.0f);
  check.in_range("clouds.precipitation", clouds.precipitation, 0.0f, 1.0f);
  // 0 (a static map) or long enough that time / evolution stays finite.
  if (clouds.weather_evolution_s != 0.0f)
    check.in_range("clouds.weather_evolution_s", clouds.weather_evolution_s, 1.0f, 1.0e7f);
  check.in_range("clouds.density", clouds.density, 0.0f, 1.0f);
  check.in_range("clouds.extinction_per_m", clouds.extinction_per_m, 0.0f, kMaxFactor, true);
  check.in_range("clouds.attenuation", clouds.attenuation, 0.0f, kMaxFactor);
  check.in_range("clouds.light_attenuation", clouds.light_attenuation, 0.0f, kMaxFactor);
  check.in_range("clouds.albedo", clouds.albedo, 0.0f, 1.0f);
  check.in_range("clouds.phase_g_forward", clouds.phase_g_forward, 0.0f, 1.0f, false, true);
  check.in_range("clouds.phase_g_backward", clouds.phase_g_backward, -1.0f, 0.0f, true, false);
  check.in_range("clouds.phase_lobe_weight", clouds.phase_lobe_weight, 0.0f, 1.0f);
  check.in_range("clouds.powder_strength", clouds.powder_strength, 0.0f, 1.0f);
  check.in_range("clouds.ambient_strength", clouds.ambient_strength, 0.0f, kMaxFactor);
  check.wind("clouds.wind_mps", clouds.wind_mps);
  check.wind("clouds.wind_shear_mps", clouds.wind_shear_mps);
  check.in_range("clouds.wind_skew_s", clouds.wind_skew_s, 0.0f, 3600.0f);
  check.wind("clouds.detail_drift_mps", clouds.detail_drift_mps);
  check.in_range("clouds.curl_distortion_m", clouds.curl_distortion_m, 0.0f, 10000.0f);
  check.in_range("clouds.flow_speed_mps", clouds.flow_speed_mps, 0.0f, kMaxWindMps);
  check.in_range("clouds.flow_cycle_s", clouds.flow_cycle_s, 1.0f, 86400.0f);
  check.in_range("clouds.base_noise_period_m", clouds.base_noise_period_m, 10.0f, 1.0e6f);
  check.in_range("clouds.detail_noise_period_m", clouds.detail_noise_period_m, 1.0f, 1.0e5f);
  check.in_range("clouds.detail_erosion", clouds.detail_erosion, 0.0f, 1.0f);
  check.in_range("clouds.weather_period_m", clouds.weather_period_m, 1000.0f, 1.0e7f);
  if (!clouds.weather_map.empty()) check.weather_map("clouds.weather_map", clouds.weather_map);
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
  check.in_range("quality.primary_steps", quality.primary_steps, 1, 1024);
  check.in_range("quality.light_steps", quality.light_steps, 1, 64);
  if (quality.march_stride != 1 && quality.march_stride != 2 && quality.march_stride != 4)
    check.fail("quality.march_stride", std::to_string(quality.march_stride), "must be 1, 2 or 4");
  check.in_range("quality.cloud_downsample", quality.cloud_downsample, 1, 4);
  check.in_range("quality.light_volume_km", quality.light_volume_km, 0, 1000);
  if (quality.voxel_march != VoxelMarch::Plain && quality.voxel_march != VoxelMarch::ThreePhase)
    check.fail("quality.voxel_march", std::to_string(static_cast<int>(quality.voxel_march)),
               "must be plain or three-phase");
  if (quality.voxel_shadow != VoxelShadow::LightMarch &&
      quality.voxel_shadow != VoxelShadow::SdfCone)
    check.fail("quality.voxel_shadow", std::to_string(static_cast<int>(quality.voxel_shadow)),
               "must be march or sdf-cone");
  check.in_range("quality.sdf_light_tangent", quality.sdf_light_tangent, 0.001f, 10.0f);
  if (light_shafts_method(quality.light_shafts) < 0)
    check.fail("quality.light_shafts", scene_detail::toml_quote(quality.light_shafts),
               "must be \"volumetric\", \"screen\" or \"off\"");
  check.in_range("quality.screen_shaft_samples", quality.screen_shaft_samples, 1, 128);
  check.in_range("quality.screen_shaft_strength", quality.screen_shaft_strength, 0.0f, 10.0f);
  check.in_range("quality.screen_shaft_decay", quality.screen_shaft_decay, 0.0f, 1.0f);
}

// The classical models (seed 004): checked whichever model draws, so a scene file stays valid
// when its model changes.
void check_classic(const Checker& check, const CloudParams& clouds, const ClassicCloudParams& c) {
  if (parse_cloud_model(to_string(clouds.model)) != clouds.model)
    check.fail("clouds.model", std::to_string(static_cast<int>(clouds.model)),
               "must be " + cloud_model_names(false));
  const std::string& phase = c.blinn_phase;
  if (phase != "constant" && phase != "anisotropic" && phase != "lambert" && phase != "rayleigh" &&
      phase != "hg")
    check.fail("classic.blinn_phase", scene_detail::toml_quote(phase),
               "must be \"constant\", \"anisotropic\", \"lambert\", \"rayleigh\" or \"hg\"");
  if (phase == "hg")
    check.in_range("classic.blinn_phase_x", c.blinn_phase_x, -1.0f, 1.0f, true, true);
  else
    check.in_range("classic.blinn_phase_x", c.blinn_phase_x, -1.0f, 1.0f);
  check.in_range("classic.blinn_particle_radius_m", c.blinn_particle_radius_m, 0.0f, 1.0f, true);
  check.in_range("classic.blinn_particles_per_m3", c.blinn_particles_per_m3, 0.0f, 1.0e12f);
  check.in_range("classic.blinn_albedo", c.blinn_albedo, 0.0f, 1.0f);
  if (c.gardner_clouds != "cumulus" && c.gardner_clouds != "stratus" && c.gardner_clouds != "cirrus")
    check.fail("classic.gardner_clouds", scene_detail::toml_quote(c.gardner_clouds),
               "must be \"cumulus\", \"stratus\" or \"cirrus\"");
  check.in_range("classic.gardner_spacing_m", c.gardner_spacing_m, 100.0f, 1.0e5f);
  check.in_range("classic.gardner_period_m", c.gardner_period_m, 10.0f, 1.0e6f);
  check.in_range("classic.gardner_terms", c.gardner_terms, 1, 8);
  check.in_range("classic.gardner_t1", c.gardner_t1, 0.0f, 1.0f);
  check.in_range("classic.gardner_t2", c.gardner_t2, 0.0f, 1.0f);
  check.in_range("classic.gardner_range", c.gardner_range, 0.0f, 1.0f, true);
  check.in_range("classic.gardner_ambient", c.gardner_ambient, 0.0f, 1.0f);
  check.in_range("classic.gardner_texture", c.gardner_texture, 0.0f, 1.0f);
  check.in_range("classic.gardner_specular", c.gardner_specular, 0.0f, 1.0f);
  check.in_range("classic.kajiya_levels", c.kajiya_levels, 1, 10);
  check.in_range("classic.nishita_metaballs", c.nishita_metaballs, 1, 4096);
  check.in_range("classic.nishita_clouds", c.nishita_clouds, 1, std::min(64, std::max(c.nishita_metaballs, 1)));
  check.in_range("classic.nishita_extent_m", c.nishita_extent_m, 500.0f, 1.0e5f);
  check.in_range("classic.nishita_center_m", c.nishita_center_m, -1.0e6f, 1.0e6f);
  check.in_range("classic.nishita_sigma_t_per_m", c.nishita_sigma_t_per_m, 0.0f, 10.0f, true);
  check.in_range("classic.nishita_albedo", c.nishita_albedo, 0.0f, 1.0f);
  check.in_range("classic.nishita_voxels", c.nishita_voxels, 16, 192);
  check.in_range("classic.nishita_order", c.nishita_order, 1, 2);
}

// The particle clouds' grid: bounded so that spawning a field takes seconds, not hours.
void check_particle_clouds(const Checker& check, const ParticleCloudParams& p) {
  check.in_range("particle_clouds.coverage", p.coverage, 0.0f, 1.0f);
  check.in_range("particle_clouds.bottom_altitude_m", p.bottom_altitude_m, 0.0f, 1.0e5f);
  check.in_range("particle_clouds.top_altitude_m", p.top_altitude_m, 0.0f, 1.0e5f);
  check.below("particle_clouds.bottom_altitude_m", p.bottom_altitude_m,
              "particle_clouds.top_altitude_m", p.top_altitude_m);
  check.in_range("particle_clouds.field_radius_m", p.field_radius_m, 100.0f, 1.0e6f);
  check.in_range("particle_clouds.cloud_spacing_m", p.cloud_spacing_m, 100.0f, 1.0e5f);
  check.in_range("particle_clouds.cell_m", p.cell_m, 1.0f, 1.0e4f);
  check.in_range("particle_clouds.particle_radius_m", p.particle_radius_m, 1.0f, 1.0e4f);
  check.in_range("particle_clouds.noise_period_m", p.noise_period_m, 1.0f, 1.0e6f);
  if (p.evolution_s != 0.0f)
    check.in_range("particle_clouds.evolution_s", p.evolution_s, 1.0f, 1.0e7f);
  check.wind("particle_clouds.wind_mps", p.wind_mps);
  check.in_range("particle_clouds.opacity", p.opacity, 0.0f, 1.0f);
  check.in_range("particle_clouds.albedo", p.albedo, 0.0f, 1.0f);
  check.in_range("particle_clouds.phase_g", p.phase_g, -1.0f, 1.0f, true, true);
  check.in_range("particle_clouds.forward_solid_angle_sr", p.forward_solid_angle_sr, 0.0f,
                 4.0f * 3.14159265f);
  check.in_range("particle_clouds.diffuse_strength", p.diffuse_strength, 0.0f, 10.0f);
  if (p.light_buffer != 32 && p.light_buffer != 64)
    check.fail("particle_clouds.light_buffer", std::to_string(p.light_buffer), "must be 32 or 64");
  check.in_range("particle_clouds.layer_resolution", p.layer_resolution, 0.25f, 1.0f);
  if (p.impostors != "off" && p.impostors != "direct" && p.impostors != "tiles")
    check.fail("particle_clouds.impostors", scene_detail::toml_quote(p.impostors),
               "must be \"off\", \"direct\" or \"tiles\"");
  check.in_range("particle_clouds.impostor_distance_m", p.impostor_distance_m, 0.0f, 1.0e7f);
  check.in_range("particle_clouds.impostor_max_angle_deg", p.impostor_max_angle_deg, 0.0f, 90.0f, true);
  check.in_range("particle_clouds.impostor_distance_factor", p.impostor_distance_factor, 1.0f, 10.0f, true);
  check.in_range("particle_clouds.impostor_resolution", p.impostor_resolution, 0.1f, 4.0f);
  check.in_range("particle_clouds.impostor_updates_per_frame", p.impostor_updates_per_frame, 1, 1024);
  check.in_range("particle_clouds.impostor_fade_frames", p.impostor_fade_frames, 1, 1000);
  check.in_range("particle_clouds.atlas_size", p.atlas_size, 256, 8192);
  check.in_range("particle_clouds.atlas_granule", p.atlas_granule, 1, 256);
  check.in_range("particle_clouds.atlas_defragmentations_per_s", p.atlas_defragmentations_per_s, 0.0f, 1000.0f);
  if (p.atlas_tile != 16 && p.atlas_tile != 32)
    check.fail("particle_clouds.atlas_tile", std::to_string(p.atlas_tile), "must be 16 or 32");
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
  check.in_range("lab.sigma_t_per_m", lab.sigma_t_per_m, 0.0f, 1000.0f, true);
  check.in_range("lab.albedo", lab.albedo, 0.0f, 1.0f);
  check.in_range("lab.g", lab.g, -1.0f, 1.0f, true, true);
  check.in_range("lab.max_bounces", lab.max_bounces, 0, 100000);
  check.in_range("lab.sun_elevation_deg", lab.sun_elevation_deg, -90.0f, 90.0f);
  check.in_range("lab.sun_azimuth_deg", lab.sun_azimuth_deg, -360.0f, 360.0f);
  check.in_range("lab.sun_irradiance", lab.sun_irradiance, 0.0f, 1e6f);
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
  check.in_range("terrain.center_m", t.center_m, -1.0e6f, 1.0e6f);
  check.in_range("terrain.height_m", t.height_m, 0.0f, 1.0e4f);
  check.in_range("terrain.base_m", t.base_m, -1.0e4f, 1.0e4f);
  check.in_range("terrain.albedo", t.albedo, 0.0f, 1.0f);
  check.in_range("terrain.snow_altitude_m", t.snow_altitude_m, 0.0f, 1.0e4f);
  check.in_range("terrain.resolution", t.resolution, 16, 4096);
  if (t.method != "raycast" && t.method != "raster")
    check.fail("terrain.method", text("terrain.method", t.method), "must be raycast or raster");
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
  check.in_range(prefix + ".scale", cloud.scale, 0.0f, kMaxFactor, true);
  check.in_range(prefix + ".rotation_deg", cloud.rotation_deg, -360.0f, 360.0f);
  check.in_range(prefix + ".density", cloud.density, 0.0f, kMaxFactor);
  check.wind(prefix + ".wind_mps", cloud.wind_mps);
  check.in_range(prefix + ".resolution", cloud.resolution, 16, 256);
}

void check_voxel_clouds(const Checker& check, const std::vector<VoxelCloudParams>& clouds) {
  if (clouds.size() > size_t(kMaxVoxelClouds))
    check.fail("voxel_clouds", std::to_string(clouds.size()) + " clouds",
               "at most " + std::to_string(kMaxVoxelClouds) + " voxel clouds per scene");
  for (size_t i = 0; i < clouds.size(); ++i) check_voxel_cloud(check, clouds[i], i);
}

void check_output(const Checker& check, const OutputParams& output) {
  check.in_range("output.width", output.width, 1, 16384);
  check.in_range("output.height", output.height, 1, 16384);
  check.in_range("output.ev100", output.ev100, kMinEv100, kMaxEv100);
  check.in_range("output.ev100_min", output.ev100_min, kMinEv100, kMaxEv100);
  check.in_range("output.ev100_max", output.ev100_max, kMinEv100, kMaxEv100);
  if (!(output.ev100_min <= output.ev100_max))
    check.fail("output.ev100_min", format_float(output.ev100_min),
               "must be <= output.ev100_max (" + format_float(output.ev100_max) + ")");
  check.in_range("output.exposure_compensation_ev", output.exposure_compensation_ev, -10.0f, 10.0f);
  check.in_range("output.adaptation_ev_per_s", output.adaptation_ev_per_s, 0.0f, 1.0e6f);
  check.in_range("output.bloom_strength", output.bloom_strength, 0.0f, 1.0f);
  check.in_range("output.bloom_threshold_cd_m2", output.bloom_threshold_cd_m2, 0.0f, 1.0e12f);
  check.in_range("output.bloom_radius_deg", output.bloom_radius_deg, 0.01f, 30.0f);
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
  check.in_range("conditions.weather", c.weather, 0.0f, 1.0f);
  if (c.hour != -1.0f) check.in_range("conditions.hour", c.hour, 0.0f, 24.0f, false, true);
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
  check.in_range("location.lat_deg", scene.location.lat_deg, -90.0f, 90.0f);
  check.in_range("location.lon_deg", scene.location.lon_deg, -180.0f, 360.0f);
  check.in_range("location.altitude_m", scene.location.altitude_m, -500.0f, 9000.0f);
}

}  // namespace

void validate_scene(const Scene& scene, const ParamNamer& display_name) {
  Checker check(display_name);
  check_camera(check, scene.camera);
  check_sun(check, scene.sun);
  check_atmosphere(check, scene.atmosphere);
  check_clouds(check, scene.clouds);
  check_high_clouds(check, scene.high_clouds, scene.clouds);
  check_cirrus(check, scene.cirrus, scene);
  check_layers(check, scene);
  check_quality(check, scene.quality);
  check_output(check, scene.output);
  check_voxel_clouds(check, scene.voxel_clouds);
  check_lab(check, scene.lab);
  check_terrain(check, scene.terrain);
  check_particle_clouds(check, scene.particle_clouds);
  check_classic(check, scene.clouds, scene.classic);
  check_conditions(check, scene);
  check.in_range("time_s", scene.time_s, -kMaxTimeS, kMaxTimeS);
  check_time(check, scene);
}

}  // namespace nephele

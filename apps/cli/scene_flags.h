// nephele CLI — the command-line flags that choose and modify the scene.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "nephele/scene.h"
#include "nephele/scene_io.h"

namespace CLI {
class App;
}

namespace nephele::cli {

// Each flag as typed, unset when not given. resolve_scene parses them, so that a malformed
// value ("abc", "1,2") is an InputError naming the flag, like every other input error.
struct SceneFlags {
  std::optional<std::string> scene_file;  // --scene FILE
  std::optional<std::string> preset;      // --preset NAME; "default" when neither is given
  std::optional<std::string> width, height;
  std::optional<std::string> camera_altitude_m, camera_pos, view_dir, fov_deg, roll_deg;
  std::optional<std::string> hfov_deg, focal_length_mm, sensor_width_mm;
  std::optional<std::string> sun_dir, sun_elevation_deg, sun_azimuth_deg, sun_illuminance,
      sun_illuminance_lux;
  std::optional<std::string> coverage, cloud_type, precipitation, density, cloud_bottom_m, cloud_top_m, extinction_per_m;
  std::optional<std::string> attenuation, light_attenuation, albedo, g_forward, g_backward;
  std::optional<std::string> lobe_weight, powder, ambient, two_stream_light, wind_mps, weather_map,
      weather_evolution_s, cirrus_coverage, cirrus_type, cirrus_altitude_m;
  std::optional<std::string> wind_shear_mps, detail_drift_mps, flow_speed_mps, high_coverage,
      high_cloud_type, high_bottom_m, high_top_m, high_wind_mps;
  std::optional<std::string> time, lat_deg, lon_deg;
  std::optional<std::string> time_s, seed, steps, light_steps, march_stride, cloud_downsample,
      light_volume_km, mode, sky, turbidity, conditions, weather, hour, exposure, auto_exposure,
      voxel_march, voxel_shadow, cloud_model;
  std::optional<std::string> ev100, ev100_min, ev100_max, exposure_compensation_ev,
      adaptation_ev_per_s, tonemap, light_shafts;
  std::optional<std::string> terrain, terrain_extent_m, terrain_center_m, terrain_height_m, terrain_method;
  // --voxel-cloud SPEC, repeatable: FILE@E,N,U or preset:NAME[:SEED]@E,N,U, each appended to
  // the scene's voxel clouds in the order given.
  std::vector<std::string> voxel_clouds;
  std::vector<std::string> cloud_layers;  // --cloud-layer GENUS,BASE_M,TOP_M,OKTAS
  // The flags the scene's field table declares (SceneParameter::flag): (key, value) in the
  // order given.
  std::vector<std::pair<std::string, std::string>> table_values;
};

// One --voxel-cloud SPEC as a voxel cloud (the other fields at their defaults); throws an
// InputError naming --voxel-cloud, the value and the accepted forms.
VoxelCloudParams parse_voxel_cloud_spec(const std::string& spec);
// --cloud-layer's GENUS,BASE_M,TOP_M,OKTAS ("altocumulus,2500,3200,5") as a [[cloud_layers]]
// table; a malformed one is refused naming the flag (validate_scene checks the values).
CloudLayerParams parse_cloud_layer_spec(const std::string& spec);

// Every flag that sets one scene key, as (flag, key): ("--coverage", "clouds.coverage").
std::vector<std::pair<std::string, std::string>> scene_flag_keys();

// The scene parameter of a key (scene_parameters()), nullptr for none.
const SceneParameter* find_scene_parameter(std::string_view key);

// Registers --scene, --preset and the scene overrides on `cmd`, writing into `flags`.
void add_scene_flags(CLI::App& cmd, SceneFlags& flags);

// Loads --scene or --preset, applies every override, validates. Throws InputError with a
// message naming the flag when the value came from one ("--coverage 1.5: must be in [0, 1]").
Scene resolve_scene(const SceneFlags& flags);

}  // namespace nephele::cli

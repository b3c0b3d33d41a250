// nephele — the table of scene keys, MarchMode names, number formatting.
#include "scene/scene_fields.h"

#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <type_traits>
#include <utility>

#include "nephele/error.h"
#include "nephele/scene_io.h"
#include "voxel/voxel_grid.h"

namespace nephele {

const char* to_string(MarchMode mode) {
  switch (mode) {
    case MarchMode::Default:
      return "default";
    case MarchMode::Baseline:
      return "baseline";
  }
  return "unknown";
}

const char* to_string(SkyModel model) {
  switch (model) {
    case SkyModel::Hillaire:
      return "hillaire";
    case SkyModel::Preetham:
      return "preetham";
    case SkyModel::Reference:
      return "reference";
  }
  return "unknown";
}

const char* to_string(ToneMap op) {
  switch (op) {
    case ToneMap::Aces:
      return "aces";
    case ToneMap::Agx:
      return "agx";
    case ToneMap::Uncharted2:
      return "uncharted2";
    case ToneMap::Reinhard:
      return "reinhard";
    case ToneMap::None:
      return "none";
  }
  return "unknown";
}

int light_shafts_method(const std::string& name) {
  if (name == "off") return 0;
  if (name == "volumetric") return 1;
  if (name == "screen") return 2;
  return -1;
}

std::optional<ToneMap> parse_tonemap(std::string_view text) {
  for (ToneMap op : kToneMaps)
    if (text == to_string(op)) return op;
  return std::nullopt;
}

std::optional<SkyModel> parse_sky_model(std::string_view text) {
  for (SkyModel m : {SkyModel::Hillaire, SkyModel::Preetham, SkyModel::Reference})
    if (text == to_string(m)) return m;
  return std::nullopt;
}

const char* to_string(ConditionsMode mode) {
  switch (mode) {
    case ConditionsMode::Off:
      return "off";
    case ConditionsMode::Artist:
      return "artist";
    case ConditionsMode::Overlay:
      return "overlay";
  }
  return "unknown";
}

std::optional<ConditionsMode> parse_conditions_mode(std::string_view text) {
  for (ConditionsMode m : {ConditionsMode::Off, ConditionsMode::Artist, ConditionsMode::Overlay})
    if (text == to_string(m)) return m;
  return std::nullopt;
}

std::optional<MarchMode> parse_march_mode(std::string_view text) {
  if (text == "default") return MarchMode::Default;
  if (text == "baseline") return MarchMode::Baseline;
  return std::nullopt;
}

const char* to_string(CloudModel model) {
  switch (model) {
    case CloudModel::Nephele:
      return "nephele";
    case CloudModel::Blinn:
      return "blinn";
    case CloudModel::Gardner:
      return "gardner";
    case CloudModel::Kajiya:
      return "kajiya";
    case CloudModel::Nishita:
      return "nishita";
    case CloudModel::GardnerQuadrics:
      return "gardner-quadrics";
  }
  return "unknown";
}

std::optional<CloudModel> parse_cloud_model(std::string_view text) {
  for (CloudModel m : kCloudModels)
    if (text == to_string(m)) return m;
  return std::nullopt;
}

std::string cloud_model_names(bool quoted) {
  std::string names;
  const size_t n = std::size(kCloudModels);
  for (size_t i = 0; i < n; ++i) {
    names += i == 0 ? "" : (i + 1 == n ? " or " : ", ");
    if (quoted) names += '"';
    names += to_string(kCloudModels[i]);
    if (quoted) names += '"';
  }
  return names;
}

const char* to_string(VoxelMarch mode) {
  switch (mode) {
    case VoxelMarch::Plain:
      return "plain";
    case VoxelMarch::ThreePhase:
      return "three-phase";
  }
  return "unknown";
}

std::optional<VoxelMarch> parse_voxel_march(std::string_view text) {
  for (VoxelMarch m : {VoxelMarch::Plain, VoxelMarch::ThreePhase})
    if (text == to_string(m)) return m;
  return std::nullopt;
}

const char* to_string(VoxelShadow mode) {
  switch (mode) {
    case VoxelShadow::LightMarch:
      return "march";
    case VoxelShadow::SdfCone:
      return "sdf-cone";
  }
  return "unknown";
}

std::optional<VoxelShadow> parse_voxel_shadow(std::string_view text) {
  for (VoxelShadow m : {VoxelShadow::LightMarch, VoxelShadow::SdfCone})
    if (text == to_string(m)) return m;
  return std::nullopt;
}

namespace scene_detail {

// FIELD(camera, fov_deg, note[, range[, choices]]) is the key camera.fov_deg for
// Scene::camera.fov_deg; the unary + turns the capture-less lambda into the function pointer
// that FieldAccess holds.
#define FIELD(section, name, note, ...) \
  Field {                               \
#name, +[](Scene & s) -> auto& {    \
      return s.section.name;            \
    }                                   \
    , note __VA_OPT__(, ) __VA_ARGS__   \
  }
#define TOP_FIELD(name, note, ...)    \
  Field {                             \
#name, +[](Scene & s) -> auto& {  \
      return s.name;                  \
    }                                 \
    , note __VA_OPT__(, ) __VA_ARGS__ \
  }

// The keyframe tables: [conditions.good.night] ... [conditions.bad.late_evening], one section
// per keyframe, generated for table T (0 good, 1 bad) and key K.
template <int T, int K>
Keyframe& keyframe_of(Scene& s) {
  return (T == 0 ? s.conditions.good : s.conditions.bad).keys[K];
}

std::string_view keyframe_section_name(int table, int key) {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> n;
    for (const char* t : {"good", "bad"})
      for (int k = 0; k < kKeyframeCount; ++k)
        n.push_back(std::string("conditions.") + t + "." + keyframe_name(k));
    return n;
  }();
  return names[size_t(table * kKeyframeCount + key)];
}

#define KEY_FIELD(member, note)               \
  Field {                                     \
#member, +[](Scene & s) -> auto& {        \
      return keyframe_of<T, K>(s).set.member; \
    }                                         \
    , note                                    \
  }

template <int T, int K>
Section keyframe_section() {
  return {keyframe_section_name(T, K),
          {Field{"hour", +[](Scene & s) -> auto& {return keyframe_of<T, K>(s).hour;
}
, "local solar time, [0, 24), increasing through the table"
}  // namespace scene_detail
, KEY_FIELD(sky_zenith_rgb, "sky colour (HDR; a clear day's zenith is about 1)"),
    KEY_FIELD(sky_fog_rgb, "fog on the sky near the horizon"),
    KEY_FIELD(sky_fog_start_deg, "fully fogged at and below this elevation"),
    KEY_FIELD(sky_fog_end_deg, "no fog from this elevation up"),
    KEY_FIELD(disk_fog_rgb, "fog on the sun and moon discs"),
    KEY_FIELD(disk_fog_start_deg, "the discs fully fogged at and below this elevation"),
    KEY_FIELD(disk_fog_end_deg, "no fog on the discs from this elevation up"),
    KEY_FIELD(star_visibility, "[0, 1]"), KEY_FIELD(sun_light_rgb, "sunlight on clouds and ground"),
    KEY_FIELD(moon_light_rgb, "moonlight on clouds and ground"),
    KEY_FIELD(ambient_rgb, "sky light on clouds and ground"),
    KEY_FIELD(fog_rgb, "fog on clouds and ground"),
    KEY_FIELD(fog_near_m, "fog starts at this distance"),
    KEY_FIELD(fog_far_m, "fully fogged from this distance")
}  // namespace nephele
, {}
}
;
}
#undef KEY_FIELD

template <int T, int... K>
void append_keyframe_sections(std::vector<Section>& sections, std::integer_sequence<int, K...>) {
  (sections.push_back(keyframe_section<T, K>()), ...);
}

const std::vector<Section>& scene_sections() {
  static const std::vector<Section> sections = [] {
    std::vector<Section> list = {
        {"",
         {TOP_FIELD(time, "date and time, ISO 8601 (\"2026-06-21T18:30:00Z\"); \"\" = none"),
          TOP_FIELD(time_s, "animation time (s) after `time`; clouds move with the wind",
                    closed(-1e6, 1e6)),
          TOP_FIELD(noise_seed, "seeds the noise textures and the procedural weather map")},
         {"preset"}},
        {"location",
         {FIELD(location, lat_deg, "latitude, north positive", closed(-90, 90)),
          FIELD(location, lon_deg, "longitude, east positive", closed(-180, 360)),
          FIELD(location, altitude_m, "the ground's height above sea level", closed(-500, 9000))},
         {}},
        {"camera",
         {FIELD(camera, position_m,
                "east, north, up (m); east and north in [-1e9, 1e9], up in [0, 1e9]"),
          FIELD(camera, view_dir, "looking direction, ENU, length in [1e-6, 1e6]"),
          FIELD(camera, fov_deg,
                "vertical field of view; unless horizontal_fov_deg or focal_length_mm is given",
                right_open(0.01, 180)),
          FIELD(camera, horizontal_fov_deg,
                "horizontal field of view, the vertical from the aspect",
                or_off(0, right_open(0.01, 180))),
          FIELD(camera, focal_length_mm, "lens, horizontal fov 2 atan(sensor_width_mm / 2f)",
                or_off(0, closed(0.1, 1e5))),
          FIELD(camera, sensor_width_mm, "36 = full frame", closed(1, 1000)),
          FIELD(camera, roll_deg,
                "about view_dir; positive turns the camera clockwise (the horizon rises to the "
                "right)",
                closed(-180, 180))},
         {"altitude_m"}},
        {"sun",
         {FIELD(sun, from_time, "true: placed by the ephemeris for time and location"),
          FIELD(sun, direction, "towards the sun, ENU (when from_time is false)"),
          FIELD(sun, illuminance_lux,
                "sunlight at the top of the atmosphere (lux); 128000 the solar constant; radiances "
                "are then in cd/m^2",
                closed(0, 1e10)),
          FIELD(sun, disk_angular_radius_deg, "apparent radius of the sun disk", closed(0, 20))},
         {"elevation_deg", "azimuth_deg", "illuminance"}},
        {"atmosphere",
         {FIELD(atmosphere, model,
                "hillaire (LUTs, multiple scattering), preetham (analytic, seed 002) or reference "
                "(brute force, slow)"),
          FIELD(atmosphere, planet_radius_km, "the planet's radius (Earth 6360)",
                closed(1000, 10000)),
          FIELD(atmosphere, atmosphere_height_km, "top of the atmosphere above ground",
                closed(1, 1000)),
          FIELD(atmosphere, rayleigh_scattering_per_m, "sigma_s at sea level, rgb",
                closed(0, 0.01)),
          FIELD(atmosphere, rayleigh_scale_height_m,
                "the air molecules' density falls by e over this height", closed(100, 100000)),
          FIELD(atmosphere, mie_scattering_per_m, "sigma_s at sea level", closed(0, 0.01)),
          FIELD(atmosphere, mie_extinction_per_m, "sigma_t at sea level, >= mie_scattering_per_m",
                closed(0, 0.01)),
          FIELD(atmosphere, mie_scale_height_m, "the aerosols' density falls by e over this height",
                closed(100, 100000)),
          FIELD(atmosphere, mie_g, "Cornette-Shanks asymmetry", closed(0, 0.999)),
          FIELD(atmosphere, ozone_absorption_per_m, "sigma_a at the ozone layer's peak, rgb",
                closed(0, 0.01)),
          FIELD(atmosphere, ozone_peak_altitude_m, "the ozone layer's densest altitude",
                closed(0, 1e6)),
          FIELD(atmosphere, ozone_half_width_m,
                "density falls linearly to 0 this far from the peak", closed(0, 1e6)),
          FIELD(atmosphere, ground_albedo, "Lambertian ground", closed(0, 1)),
          FIELD(atmosphere, turbidity, "Preetham model's haze", closed(2, 10)),
          FIELD(atmosphere, view_samples, "samples along each sky-view LUT ray", closed(1, 256)),
          FIELD(atmosphere, angular_multiple_scattering,
                "true: multiple scattering with its angular dependence; false: Hillaire 2020's "
                "isotropic approximation")},
         {}},
        {"cirrus",
         {FIELD(cirrus, altitude_m, "above ground, above the volumetric layers when coverage > 0",
                closed(0, 1e6)),
          FIELD(cirrus, coverage, "share of the sky the sheet covers; 0 = none", closed(0, 1)),
          FIELD(cirrus, type, "0 cirrus, 0.5 cirrostratus, 1 cirrocumulus", closed(0, 1)),
          FIELD(cirrus, optical_depth, "vertical, where densest", closed(0, 4)),
          FIELD(cirrus, wind_mps, "east, north (m/s)", closed(-200, 200))},
         {}},
        {"ground_fog",
         {FIELD(ground_fog, visibility_m, "visibility inside the fog; 0 = no fog",
                or_off(0, closed(1, 1e5)), {}, "ground-fog-visibility-m"),
          FIELD(ground_fog, base_m, "bottom above the ground; 0 = down to the ground",
                closed(0, 1e5), {}, "ground-fog-base-m"),
          FIELD(ground_fog, top_m, "top above the ground; at or below base_m: no fog",
                closed(0, 1e5), {}, "ground-fog-top-m"),
          FIELD(ground_fog, softness_m,
                "the density fades to 0 over this height below the top; 0 = a hard top",
                closed(0, 1e5), {}, "ground-fog-softness-m")},
         {}},
        {"precipitation",
         {FIELD(precipitation, rate_mm_per_h,
                "liquid-water equivalent falling from the low layer; 0 = none", closed(0, 200), {},
                "precipitation-mm-per-h"),
          FIELD(precipitation, kind, "what falls", {}, {"rain", "drizzle", "snow", "sleet"},
                "precipitation-kind"),
          FIELD(precipitation, bottom_m,
                "the lowest height it reaches; 0 = the ground, above it virga", closed(0, 1e5)),
          FIELD(precipitation, shafts,
                "shafts under the precipitating clouds; false: an even curtain under the layer"),
          FIELD(precipitation, particles,
                "the particles near the camera drawn one by one: rain streaks, snowflakes"),
          FIELD(precipitation, shutter_s,
                "the camera's shutter time that draws the particles out into streaks; 0 = frozen",
                closed(0, 0.1))},
         {}},
        {"lightning",
         {FIELD(lightning, flashes_per_min, "a cumulonimbus cell's flashes a minute; 0 = none",
                closed(0, 30), {}, "lightning-per-min"),
          FIELD(lightning, ground_share, "the share of the flashes that strike the ground",
                closed(0, 1)),
          FIELD(lightning, seed, "where and when the flashes strike")},
         {}},
        {"clouds",
         {FIELD(clouds, model,
                "nephele (its noise clouds) or a classical model of seed 004 drawing the same "
                "layer (see [classic])"),
          FIELD(clouds, bottom_altitude_m, "above ground", closed(0, 1e6)),
          FIELD(clouds, top_altitude_m, "above ground, > bottom_altitude_m", closed(0, 1e6)),
          FIELD(clouds, coverage, "share of the sky the layer covers", closed(0, 1)),
          FIELD(clouds, type,
                "0 stratus, 0.25 stratocumulus, 0.5 altocumulus, 0.75 cumulus, 1 cumulonimbus",
                closed(0, 1)),
          FIELD(clouds, precipitation, "grows cumulonimbus", closed(0, 1)),
          FIELD(clouds, density,
                "scales the clouds' density (sigma_t = density x extinction_per_m)", closed(0, 1)),
          FIELD(clouds, extinction_per_m, "optics \"seed\": sigma_t at density 1",
                left_open(0, 100)),
          FIELD(clouds, attenuation, "sigma_t multiplier along view rays", closed(0, 100)),
          FIELD(clouds, light_attenuation, "sigma_t multiplier along light rays", closed(0, 100)),
          FIELD(clouds, albedo, "optics \"seed\": single-scattering albedo", closed(0, 1)),
          FIELD(clouds, phase_g_forward,
                "optics \"seed\": Henyey-Greenstein asymmetry of the forward lobe",
                right_open(0, 1)),
          FIELD(clouds, phase_g_backward,
                "optics \"seed\": Henyey-Greenstein asymmetry of the backward lobe",
                left_open(-1, 0)),
          FIELD(clouds, phase_lobe_weight, "optics \"seed\": weight of the forward lobe",
                closed(0, 1)),
          FIELD(clouds, powder_strength, "the powder term: dark edges facing the sun",
                closed(0, 1)),
          FIELD(clouds, ambient_strength, "sky light on the clouds, times the sky's",
                closed(0, 100)),
          FIELD(clouds, lighting,
                "how the clouds scatter sunlight: \"diffusion\" (single scattering and the "
                "multiple-scattered light solved on a grid around the camera, the diffusion "
                "equation with similarity scaling), \"two-stream\" (single scattering and the "
                "two-stream field along the sun's chord) or \"seed\" (Wrenninge's octaves, the "
                "powder term and a conservative diffuse term); the old "
                "two_stream_light = true / false reads as \"two-stream\" / \"seed\"",
                {}, {"seed", "two-stream", "diffusion"}, "cloud-lighting"),
          FIELD(clouds, optics,
                "what the clouds are made of: \"droplets\" (water droplets of [droplets]: "
                "sigma_t = 1.5 LWC / r_eff, their albedo and a fitted Mie phase function) or "
                "\"seed\" (sigma_t = density field x extinction_per_m, albedo, two "
                "Henyey-Greenstein lobes)",
                {}, {"seed", "droplets"}, "cloud-optics"),
          FIELD(clouds, wind_mps, "east, north (m/s), at the layer's bottom", closed(-200, 200)),
          FIELD(clouds, wind_shear_mps, "east, north (m/s): the wind's growth up to the top",
                closed(-200, 200)),
          FIELD(clouds, wind_skew_s, "tops lean downwind as if carried h x this longer (seed: 200)",
                closed(0, 3600)),
          FIELD(clouds, detail_drift_mps,
                "east, north, up (m/s): the detail noise's motion over the clouds",
                closed(-200, 200)),
          FIELD(clouds, curl_distortion_m, "curl noise displacement of the detail noise",
                closed(0, 10000)),
          FIELD(clouds, flow_speed_mps, "flow map swirls; 0 = none", closed(0, 200)),
          FIELD(clouds, flow_cycle_s, "the flow's two phases restart every this", closed(1, 86400)),
          FIELD(clouds, base_noise_period_m, "the base (Perlin-Worley) noise's tile on the ground",
                closed(10, 1e6)),
          FIELD(clouds, detail_noise_period_m, "the detail (Worley) noise's tile", closed(1, 1e5)),
          FIELD(clouds, detail_erosion, "how much the detail noise erodes the base shape's edges",
                closed(0, 1)),
          FIELD(clouds, weather_period_m,
                "the weather map's square tile on the ground (m), repeated", closed(1000, 1e7)),
          FIELD(clouds, weather_evolution_s,
                "the weather map's clusters form and dissipate over this time",
                or_off(0, closed(1, 1e7))),
          FIELD(clouds, weather_map,
                "RGBA PNG path (R coverage, G storm cells, B type around clouds.type, A density x "
                "2); row 0 north, columns west to east, centre at east 0, north 0 and moving with "
                "the wind; empty = procedural")},
         {"two_stream_light"}},
        {"droplets",
         {FIELD(droplets, stratus_water_g_m3,
                "clouds.optics = \"droplets\": stratus liquid water content in a cloud's core "
                "(where the density field is 0.1), scaled with the field",
                left_open(0, 10)),
          FIELD(droplets, stratus_radius_um,
                "stratus droplets' effective radius (the Mie fit's range: diameters 5-50 um)",
                closed(2.5, 25)),
          FIELD(droplets, stratocumulus_water_g_m3, "as stratus_water_g_m3", left_open(0, 10)),
          FIELD(droplets, stratocumulus_radius_um, "", closed(2.5, 25)),
          FIELD(droplets, altocumulus_water_g_m3, "", left_open(0, 10)),
          FIELD(droplets, altocumulus_radius_um, "", closed(2.5, 25)),
          FIELD(droplets, cumulus_water_g_m3, "also the voxel clouds' at density 1",
                left_open(0, 10)),
          FIELD(droplets, cumulus_radius_um, "also the voxel clouds'", closed(2.5, 25)),
          FIELD(droplets, cumulonimbus_water_g_m3, "", left_open(0, 10)),
          FIELD(droplets, cumulonimbus_radius_um, "", closed(2.5, 25))},
         {}},
        {"high_clouds",
         {FIELD(high_clouds, bottom_altitude_m,
                "above ground, >= clouds.top_altitude_m when coverage > 0", closed(0, 1e6)),
          FIELD(high_clouds, top_altitude_m, "above ground, > bottom_altitude_m", closed(0, 1e6)),
          FIELD(high_clouds, coverage, "0 = no high layer", closed(0, 1)),
          FIELD(high_clouds, type, "as clouds.type; 0.5 altocumulus", closed(0, 1)),
          FIELD(high_clouds, density, "as clouds.density", closed(0, 1)),
          FIELD(high_clouds, wind_mps, "east, north (m/s)", closed(-200, 200))},
         {}},
        {"quality",
         {FIELD(quality, mode, "\"default\" or \"baseline\""),
          FIELD(quality, primary_steps, "march steps along a view ray through a layer",
                closed(1, 1024)),
          FIELD(quality, light_steps, "march steps along a ray towards the sun", closed(1, 64)),
          FIELD(quality, march_stride, "1, 2 or 4: one pixel per stride^2 block marched per frame",
                {}, {"1", "2", "4"}),
          FIELD(quality, cloud_downsample, "cloud buffer = image / this per axis", closed(1, 4)),
          FIELD(quality, light_volume_km,
                "light volume half extent (km); 0 = march every light ray", closed(0, 1000)),
          FIELD(quality, voxel_march,
                "\"three-phase\" (SDF sphere tracing across the voxel clouds' empty space) or "
                "\"plain\" (the noise clouds' march everywhere)"),
          FIELD(quality, voxel_shadow,
                "\"march\" (light march through the voxel clouds) or \"sdf-cone\" (cone traced "
                "through their distance field)"),
          FIELD(quality, sdf_light_tangent, "the SDF cone's half-angle tangent", closed(0.001, 10)),
          FIELD(quality, light_shafts,
                "volumetric (the air's light shadowed by the clouds: beams below broken clouds), "
                "screen (seed 002's screen-space god rays and radial blur) or off",
                {}, {"volumetric", "screen", "off"}),
          FIELD(quality, screen_shaft_samples,
                "screen: samples towards the sun (and of the radial blur)", closed(1, 128)),
          FIELD(quality, screen_shaft_strength, "screen: the rays' strength", closed(0, 10)),
          FIELD(quality, screen_shaft_decay, "screen: each sample's weight over the one before",
                closed(0, 1))},
         {}},
        {"output",
         {FIELD(output, width, "pixels", closed(1, 16384)),
          FIELD(output, height, "pixels", closed(1, 16384)),
          FIELD(output, auto_exposure,
                "true: expose by a meter (log-average luminance) within ev100_min..ev100_max; "
                "false: at ev100"),
          FIELD(output, ev100,
                "manual exposure value at ISO 100: 15 sunny day, 12 overcast, 9 sunset, 4 civil "
                "twilight, -2.5 full moon",
                closed(-20, 30)),
          FIELD(output, ev100_min, "auto exposure's lower limit: darker nights stay dark",
                closed(-20, 30)),
          FIELD(output, ev100_max, "auto exposure's upper limit, >= ev100_min", closed(-20, 30)),
          FIELD(output, exposure_compensation_ev, "auto exposure: + brightens", closed(-10, 10)),
          FIELD(
              output, tonemap,
              "the display's tone map: aces (default), agx, uncharted2 (the seed's filmic curve), "
              "reinhard or none"),
          FIELD(output, bloom_strength,
                "the share of the light the lens spreads (bloom and glare); 0 = off; the image's "
                "total light is kept",
                closed(0, 1)),
          FIELD(output, bloom_threshold_cd_m2,
                "only light above this luminance is spread (cd/m^2); 0 = all of it",
                closed(0, 1e12)),
          FIELD(output, bloom_radius_deg, "the spread's Gaussian sigma (deg of view)",
                closed(0.01, 30)),
          FIELD(output, adaptation_ev_per_s,
                "auto exposure's adaptation in sequences and the viewer (EV/s); 0 = at once",
                closed(0, 1e6))},
         {"exposure"}},
        {"weather",
         {FIELD(weather, metar,
                "a METAR or SPECI report (\"EDDF 271150Z 24015KT 9999 FEW025 SCT040 12/06 "
                "Q1008\"): its clouds, wind, visibility, weather and time set the scene's when it "
                "is loaded; \"\" = none",
                {}, {}, "metar"),
          FIELD(
              weather, grib,
              "a GRIB2 (or GRIB1) forecast's path: its total, low, medium and high cloud cover "
              "(and cover on pressure levels) around location.lat_deg, lon_deg, valid nearest the "
              "scene's time, set the layers and where they cover, fixed to the ground; \"\" = none",
              {}, {}, "grib"),
          FIELD(weather, wind_from_deg,
                "the ground's wind blows from this direction (clockwise from north), with one of "
                "the speeds below: every layer's wind, 1.93 times it at 1 km; -1 = not given",
                or_off(-1, closed(0, 360)), {}, "wind-from-deg"),
          FIELD(weather, wind_speed_kt, "the ground's wind speed in knots; -1 = not given",
                or_off(-1, closed(0, 400)), {}, "wind-speed-kt"),
          FIELD(weather, wind_speed_mps, "the ground's wind speed in m/s; -1 = not given",
                or_off(-1, closed(0, 200)), {}, "wind-speed-mps"),
          FIELD(weather, visibility_m,
                "the meteorological visibility at the ground: sets the haze (what rain or snow "
                "leaves of it); 0 = not given",
                or_off(0, closed(400, 3e5)), {}, "visibility-m")},
         {}},
        {"conditions",
         {FIELD(conditions, mode,
                "off, artist (keyframes instead of the physical sky and lights) or overlay "
                "(keyframes' fog and star visibility on the physical sky)"),
          FIELD(conditions, weather, "1 good weather, 0 bad", closed(0, 1)),
          FIELD(conditions, hour, "local solar time; -1 = from time and location",
                or_off(-1, right_open(0, 24)))},
         {"good", "bad"}},
        {"particle_clouds",
         {FIELD(particle_clouds, coverage,
                "share of the grid's cells holding a particle (seed 003); 0 = no particle clouds",
                closed(0, 1)),
          FIELD(particle_clouds, bottom_altitude_m, "the clouds' base above ground",
                closed(0, 1e5)),
          FIELD(particle_clouds, top_altitude_m, "their highest tops, > bottom_altitude_m",
                closed(0, 1e5)),
          FIELD(particle_clouds, field_radius_m, "clouds within this distance of east 0, north 0",
                closed(100, 1e6)),
          FIELD(particle_clouds, cloud_spacing_m, "one cloud per square of this side",
                closed(100, 1e5)),
          FIELD(particle_clouds, cell_m, "the particles' grid (one particle per cell at most)",
                closed(1, 1e4)),
          FIELD(particle_clouds, particle_radius_m,
                "a particle's radius where the noise is largest", closed(1, 1e4)),
          FIELD(particle_clouds, noise_period_m, "the Perlin noise's lattice spacing",
                closed(1, 1e6)),
          FIELD(particle_clouds, evolution_s, "time's scale in 4D noise; coverage stays as set",
                or_off(0, closed(1, 1e7))),
          FIELD(particle_clouds, wind_mps, "east, north (m/s)", closed(-200, 200)),
          FIELD(particle_clouds, opacity, "a particle's opacity at its centre", closed(0, 1)),
          FIELD(particle_clouds, albedo, "single-scattering albedo", closed(0, 1)),
          FIELD(particle_clouds, phase_g, "Henyey-Greenstein asymmetry", open_range(-1, 1)),
          FIELD(particle_clouds, rayleigh_phase,
                "true: Harris and Lastra's Rayleigh phase (the seed's reference); false: "
                "Henyey-Greenstein with phase_g"),
          FIELD(particle_clouds, forward_solid_angle_sr,
                "Harris and Lastra's gamma: the solid angle about the light's direction whose "
                "scattered light goes on with it",
                closed(0, 4 * kPi)),
          FIELD(particle_clouds, diffuse_strength,
                "the multiply scattered light, an isotropic radiance albedo x I_k x sunlight / pi "
                "times this; 0 = Harris and Lastra's model alone",
                closed(0, 10)),
          FIELD(particle_clouds, light_buffer,
                "the CPU lighting's splat buffer, 32 or 64 texels a side", {}, {"32", "64"}),
          FIELD(particle_clouds, layer_resolution,
                "the particle layer's pixels per output pixel along each axis; drawn at this "
                "resolution and filtered up when composed",
                closed(0.25, 1)),
          FIELD(particle_clouds, seed, "seeds the noise and the particles' offsets"),
          FIELD(particle_clouds, impostors,
                "\"off\" (every particle every frame), \"direct\" (far clouds as impostors stored "
                "as rectangles) or \"tiles\" (stored as tiles)",
                {}, {"off", "direct", "tiles"}),
          FIELD(particle_clouds, impostor_distance_m, "clouds farther than this are impostors",
                closed(0, 1e7)),
          FIELD(particle_clouds, impostor_max_angle_deg,
                "an impostor is drawn again when the direction to it turns by more",
                left_open(0, 90)),
          FIELD(particle_clouds, impostor_distance_factor,
                "... or its distance changes by more than this factor", left_open(1, 10)),
          FIELD(particle_clouds, impostor_resolution, "impostor texels per particle-layer pixel",
                closed(0.1, 4)),
          FIELD(particle_clouds, impostor_updates_per_frame,
                "impostors drawn again at most each frame", closed(1, 1024)),
          FIELD(particle_clouds, impostor_fade_frames, "an update's cross-fade, in frames",
                closed(1, 1000)),
          FIELD(particle_clouds, atlas_size, "the impostor atlas's side (texels)",
                closed(256, 8192)),
          FIELD(particle_clouds, atlas_granule, "direct: sizes rounded up to this many texels",
                closed(1, 256)),
          FIELD(particle_clouds, atlas_defragment,
                "repack the atlas when an impostor does not fit"),
          FIELD(particle_clouds, atlas_defragmentations_per_s, "the defragmentations' rate limit",
                closed(0, 1000)),
          FIELD(particle_clouds, atlas_tile, "tiles: the tile side, 16 or 32 texels", {},
                {"16", "32"})},
         {}},
        {"classic",
         {FIELD(
              classic, seed_formulas,
              "true: the seed's printing of the formulas where it differs from the papers (Blinn's "
              "B and Tr, the Lambert phase's factor)"),
          FIELD(classic, blinn_phase,
                "Blinn's phase function: constant, anisotropic, lambert, rayleigh or hg", {},
                {"constant", "anisotropic", "lambert", "rayleigh", "hg"}),
          FIELD(classic, blinn_phase_x,
                "x of 1 + x cos alpha or g of hg, alpha = 0 back towards the light (forward "
                "scattering: < 0), [-1, 1] ((-1, 1) for hg)"),
          FIELD(classic, blinn_particle_radius_m, "r", left_open(0, 1)),
          FIELD(classic, blinn_particles_per_m3, "n; tau = n pi r^2 (top - bottom)",
                closed(0, 1e12)),
          FIELD(classic, blinn_albedo, "omega", closed(0, 1)),
          FIELD(classic, gardner_clouds,
                "Gardner's clouds: cumulus (textured ellipsoids), stratus (a textured sky plane) "
                "or cirrus (a thin streaked plane at cirrus.altitude_m)",
                {}, {"cumulus", "stratus", "cirrus"}),
          FIELD(classic, gardner_spacing_m,
                "the cumulus cells' side (m); one ellipsoid in a share clouds.coverage of them",
                closed(100, 1e5)),
          FIELD(classic, gardner_period_m, "his texture's longest wavelength (m)", closed(10, 1e6)),
          FIELD(classic, gardner_terms, "the texture's sines per axis, frequencies doubling",
                closed(1, 8)),
          FIELD(classic, gardner_t1, "T1, the texture's threshold at an ellipsoid's centre",
                closed(0, 1)),
          FIELD(classic, gardner_t2, "T2, the threshold at its edge", closed(0, 1)),
          FIELD(classic, gardner_range, "D, the texture's range from clear to opaque",
                left_open(0, 1)),
          FIELD(classic, gardner_ambient, "f, the ambient term", closed(0, 1)),
          FIELD(classic, gardner_texture, "t, the texture's share of the shading", closed(0, 1)),
          FIELD(classic, gardner_specular, "s, the specular share", closed(0, 1)),
          FIELD(classic, kajiya_levels,
                "Kajiya and Von Herzen's Romberg levels: 2^levels + 1 samples an eye ray",
                closed(1, 10)),
          FIELD(classic, kajiya_reference,
                "true: a brute-force march of the same single scattering instead (1024 samples, "
                "the light marched at each), to check their method against"),
          FIELD(classic, nishita_metaballs, "Nishita and Nakamae's metaballs in all",
                closed(1, 4096)),
          FIELD(classic, nishita_clouds, "the cumulus they make, at most nishita_metaballs",
                closed(1, 64)),
          FIELD(classic, nishita_extent_m, "the side of the square the clouds stand in (m)",
                closed(500, 1e5)),
          FIELD(classic, nishita_center_m, "its centre (east, north; m)", closed(-1e6, 1e6)),
          FIELD(classic, nishita_sigma_t_per_m, "sigma_t at a ball's centre of density 1 (1/m)",
                left_open(0, 10)),
          FIELD(classic, nishita_albedo, "single-scattering albedo", closed(0, 1)),
          FIELD(classic, nishita_voxels, "the voxel grid's cells along its longest side",
                closed(16, 192)),
          FIELD(classic, nishita_order,
                "scattering orders summed: 1 or 2 (the paper's second order)", closed(1, 2)),
          FIELD(classic, nishita_sky_light,
                "light the clouds by the sky and the ground as well as the sun")},
         {}},
        {"terrain",
         {FIELD(terrain, file,
                "a heightfield: .png (16-bit grey), .exr, .tif (GeoTIFF, placed by its "
                "coordinates) or .obj (metres, y up, -z north); empty = none"),
          FIELD(terrain, preset, "mountains: a procedural range; at most one of file and preset"),
          FIELD(terrain, extent_m,
                "east-west, north-south size (m; PNG, EXR, mountains), (0, 1e6] each"),
          FIELD(terrain, center_m, "its centre (east, north; m); a GeoTIFF places itself",
                closed(-1e6, 1e6)),
          FIELD(terrain, height_m,
                "PNG, EXR: the height of the largest value; mountains: the highest peak (m)",
                closed(0, 1e4)),
          FIELD(terrain, base_m, "PNG, EXR, mountains: the height of the value 0 (m)",
                closed(-1e4, 1e4)),
          FIELD(terrain, albedo, "Lambertian albedo of the bare ground", closed(0, 1)),
          FIELD(terrain, albedo_map,
                "an image of the albedo over the terrain (row 0 north): .png (sRGB) or .exr "
                "(linear); empty = albedo"),
          FIELD(terrain, snow_altitude_m,
                "snow above this height on slopes under 40 deg (m); 0 = none", closed(0, 1e4)),
          FIELD(terrain, resolution, "mountains: grid points along each axis", closed(16, 4096)),
          FIELD(terrain, seed, "mountains: the range's seed"),
          FIELD(terrain, method,
                "raycast (rays walk a pyramid of maxima in compute) or raster (seed 002's mesh, "
                "two triangles a cell, drawn with depth)",
                {}, {"raycast", "raster"})},
         {}},
        {"lab",
         {FIELD(lab, grid,
                "a density grid (.vdb, .nvdb) in vacuum for render --reference; empty = none"),
          FIELD(lab, sigma_t_per_m, "extinction at density 1 (1/m)", left_open(0, 1000)),
          FIELD(lab, albedo, "single-scattering albedo", closed(0, 1)),
          FIELD(lab, g, "Henyey-Greenstein asymmetry", open_range(-1, 1)),
          FIELD(lab, max_bounces, "scatterings after the first; 0 = single scattering",
                closed(0, 100000)),
          FIELD(lab, sun_elevation_deg, "the light's elevation", closed(-90, 90)),
          FIELD(lab, sun_azimuth_deg, "from north through east", closed(-360, 360)),
          FIELD(lab, sun_irradiance, "W/m^2 perpendicular to the light", closed(0, 1e6))},
         {}},
    };
    std::vector<std::string_view> names;
    for (int k = 0; k < kKeyframeCount; ++k) names.push_back(keyframe_name(k));
    list.push_back({"conditions.good", {}, names});
    append_keyframe_sections<0>(list, std::make_integer_sequence<int, kKeyframeCount>());
    list.push_back({"conditions.bad", {}, names});
    append_keyframe_sections<1>(list, std::make_integer_sequence<int, kKeyframeCount>());
    return list;
  }();
  return sections;
}

#undef TOP_FIELD
#undef FIELD

// ARRAY_FIELD(T, density, note[, range[, choices]]) is the key density of a table of an array
// whose tables are T (VoxelCloudParams for [[voxel_clouds]], CloudLayerParams for
// [[cloud_layers]]).
#define ARRAY_FIELD(T, name, note, ...) \
  ArrayField<T> {                       \
#name, +[](T & c) -> auto& {        \
      return c.name;                    \
    }                                   \
    , note __VA_OPT__(, ) __VA_ARGS__   \
  }
#define VOXEL_FIELD(...) ARRAY_FIELD(VoxelCloudParams, __VA_ARGS__)
#define LAYER_FIELD(...) ARRAY_FIELD(CloudLayerParams, __VA_ARGS__)

const std::vector<VoxelField>& voxel_cloud_fields() {
  static const std::vector<VoxelField> fields = {
      VOXEL_FIELD(file, ".vdb (OpenVDB) or .nvdb (NanoVDB) path; exactly one of file and preset"),
      VOXEL_FIELD(preset,
                  "generated: cumulus, cumulus-congestus, cumulonimbus; cumulus-mesh, baked "
                  "from data/meshes/cumulus.obj; or cube (1 km, density 1: the lab's test body)"),
      VOXEL_FIELD(seed, "the generated cloud's seed"),
      VOXEL_FIELD(position_m,
                  "east, north, up (m) of the base's centre; east and north in [-1e7, 1e7], up "
                  "in [-1000, 1e5] (or lat_deg, lon_deg, altitude_m)"),
      VOXEL_FIELD(scale, "multiplies the grid's size", left_open(0, 100)),
      VOXEL_FIELD(rotation_deg, "about the up axis, from north through east", closed(-360, 360)),
      VOXEL_FIELD(density, "sigma_t = grid density x this x clouds.extinction_per_m",
                  closed(0, 100)),
      VOXEL_FIELD(follow_wind, "true: moves with clouds.wind_mps; false: with wind_mps"),
      VOXEL_FIELD(wind_mps, "east, north, when follow_wind is false", closed(-200, 200)),
      VOXEL_FIELD(resolution, "voxels along the longest axis", closed(16, 256)),
  };
  return fields;
}

std::string voxel_cloud_key(size_t index) {
  return std::string(kVoxelCloudsKey) + "[" + std::to_string(index) + "]";
}

const std::vector<CloudLayerField>& cloud_layer_fields() {
  static const std::vector<CloudLayerField> fields = {
      LAYER_FIELD(genus, "the clouds drawn", {},
                  {std::begin(kCloudLayerGenera), std::end(kCloudLayerGenera)}),
      LAYER_FIELD(base_m, "its clouds' bases above the ground (fog is ground_fog)",
                  left_open(0, 2e4)),
      LAYER_FIELD(top_m, "its clouds' tops above the ground, > base_m", closed(0, 2e4)),
      LAYER_FIELD(oktas, "the sky it covers seen from the ground; 0 = none", closed(0, 8)),
      LAYER_FIELD(density, "as clouds.density", closed(0, 1)),
      LAYER_FIELD(wind_mps, "east, north (m/s)", closed(-200, 200)),
  };
  return fields;
}

#undef LAYER_FIELD
#undef VOXEL_FIELD
#undef ARRAY_FIELD

std::string cloud_layer_key(size_t index) {
  return std::string(kCloudLayersKey) + "[" + std::to_string(index) + "]";
}

bool ends_with_ignoring_case(std::string_view text, std::string_view suffix) {
  if (text.size() < suffix.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(text[text.size() - suffix.size() + i])) !=
        suffix[i])
      return false;
  return true;
}

bool is_voxel_cloud_preset(std::string_view name) {
  for (std::string_view preset : voxel::kCloudPresetNames)
    if (name == preset) return true;
  return false;
}

template <typename T>
static std::string shortest(T value) {
  char buffer[64];
  auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  return std::string(buffer, result.ptr);
}

std::string format_float(float value) {
  return shortest(value);
}
std::string format_double(double value) {
  return shortest(value);
}

// Reads `text` the way toml++ does (as a double) and narrows it like the scene reader.
static bool reads_back_as(const std::string& text, float value) {
  double parsed = 0.0;
  auto result = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (result.ec != std::errc()) return false;
  float narrowed = static_cast<float>(parsed);
  return narrowed == value || (std::isnan(narrowed) && std::isnan(value));
}

std::string toml_float(float value) {
  std::string text = format_float(value);
  // Shortest float digits can, very rarely, round differently when read as a double first;
  // the exact double value of the float always reads back.
  if (!reads_back_as(text, value)) text = format_double(static_cast<double>(value));
  // TOML reads "2" as an integer; the reader accepts that, but a float looks like one.
  if (text.find_first_of(".eni") == std::string::npos) text += ".0";
  return text;
}

std::string toml_quote(std::string_view text) {
  std::string out = "\"";
  for (char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\t':
        out += "\\t";
        break;
      case '\r':
        out += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
          char escaped[8];
          std::snprintf(escaped, sizeof escaped, "\\u%04x", static_cast<unsigned char>(c));
          out += escaped;
        } else {
          out += c;
        }
    }
  }
  return out + "\"";
}

std::string read_small_text_file(const std::string& path, const std::string& what,
                                 const std::string& too_large) {
  constexpr size_t kMaxBytes = 1u << 20;
  const std::string cannot = shorten_path_for_message(path) + ": cannot read the " + what + ": ";
  std::error_code error;
  const std::filesystem::file_status status = std::filesystem::status(path, error);
  if (std::filesystem::is_directory(status)) throw InputError(cannot + "it is a directory");
  if (std::filesystem::exists(status) && !std::filesystem::is_regular_file(status))
    throw InputError(cannot + "it is not a regular file (a device, a pipe or a socket)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(cannot + std::strerror(errno));
  // Read at most one byte more than allowed: the file may grow after the check.
  std::string text(kMaxBytes + 1, '\0');
  in.read(text.data(), std::streamsize(text.size()));
  if (in.bad()) throw InputError(cannot + "read error");
  text.resize(size_t(in.gcount()));
  if (text.size() > kMaxBytes) throw InputError(cannot + too_large);
  return text;
}

ValueShape value_shape(const FieldAccess& access) {
  return shape_of<Scene>(access);
}

bool is_integer_field(const Field& field) {
  return value_shape(field.access) == ValueShape::kInteger;
}

// A bound as validation messages print it: the float the value is compared in, or the integer.
static std::string bound_text(double bound, ValueShape shape) {
  if (shape == ValueShape::kInteger) return std::to_string(static_cast<long long>(bound));
  return format_float(static_cast<float>(bound));
}

std::string allowed_text(const Range& range, const std::vector<std::string_view>& choices,
                         ValueShape shape) {
  if (!choices.empty()) {
    std::string text;
    for (size_t i = 0; i < choices.size(); ++i) {
      text += i == 0 ? "" : (i + 1 == choices.size() ? " or " : ", ");
      text += shape == ValueShape::kString ? toml_quote(choices[i]) : std::string(choices[i]);
    }
    return text;
  }
  if (!range.given) return "";
  std::string text;
  if (range.has_off) text.append(bound_text(range.off, shape)).append(" or ");
  text.append(range.min_open ? "(" : "[").append(bound_text(range.min, shape)).append(", ");
  text.append(bound_text(range.max, shape)).append(range.max_open ? ")" : "]");
  if (shape == ValueShape::kVec2 || shape == ValueShape::kVec3) text += " each";
  return text;
}

std::string expected_integer(const std::string& allowed) {
  if (allowed.empty()) return "expected an integer";
  return std::string("expected an integer") +
         (allowed[0] == '[' || allowed[0] == '(' ? " in " : ": ") + allowed;
}

std::string allowed_text(const Field& field) {
  return allowed_text(field.range, field.choices, value_shape(field.access));
}

std::string_view unit_of(std::string_view name) {
  // Longest suffixes first: "_ev_per_s" before "_s", "_per_m3" before "_m3".
  static constexpr std::pair<std::string_view, std::string_view> kSuffixes[] = {
      {"_ev_per_s", "EV/s"},
      {"_per_m3", "1/m^3"},
      {"_g_m3", "g/m^3"},
      {"_um", "um"},
      {"_mm_per_h", "mm/h"},
      {"_per_m", "1/m"},
      {"_cd_m2", "cd/m^2"},
      {"_mps", "m/s"},
      {"_lux", "lux"},
      {"_deg", "deg"},
      {"_rad", "rad"},
      {"_km", "km"},
      {"_mm", "mm"},
      {"_sr", "sr"},
      {"_ev", "EV"},
      {"_m", "m"},
      {"_s", "s"}};
  for (const auto& [suffix, unit] : kSuffixes)
    if (name.size() > suffix.size() && name.ends_with(suffix)) return unit;
  return "";
}

static std::string comment(const std::string& allowed, std::string_view note) {
  if (allowed.empty()) return std::string(note);
  if (note.empty()) return allowed;
  return allowed + ": " + std::string(note);
}

std::string field_comment(const Field& field) {
  return comment(allowed_text(field), field.note);
}

std::string field_comment(const Range& range, const std::vector<std::string_view>& choices,
                          ValueShape shape, std::string_view note) {
  return comment(allowed_text(range, choices, shape), note);
}

}  // namespace scene_detail
}  // namespace nephele

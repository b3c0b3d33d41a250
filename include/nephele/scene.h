// nephele — scene parameters: plain structs, units in names, no Vulkan.
//
// Frame: local east-north-up (ENU). x east, y north, z up, metres; the origin
// is on the ground (altitude 0) below the start position. Azimuths are degrees
// from north through east. Directions need not be normalised but must have a
// length in [1e-6, 1e6].
//
// Every parameter has a range (in its comment; validate_scene enforces it) in which the
// scene renders finite, meaningful pixels; anything outside it is refused with one line
// naming the parameter, the value and the range.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include "nephele/conditions.h"
#include "nephele/tonemap.h"

namespace nephele {

struct CameraParams {
  // ENU, metres: east and north in [-1e9, 1e9], up in [0, 1e9] (2.6 times the Moon's distance)
  glm::vec3 position_m{0.0f, 0.0f, 2.0f};
  glm::vec3 view_dir{0.0f, 1.0f, 0.25f};   // ENU, looking direction
  // The field of view, in one of three forms (vertical_fov_deg() gives the vertical one for an
  // image's aspect): fov_deg, vertical, unless horizontal_fov_deg (then the vertical follows the
  // aspect) or focal_length_mm (horizontal: 2 atan(sensor_width_mm / (2 focal_length_mm))) is
  // given (> 0). At most one of those two.
  float fov_deg = 70.0f;             // vertical field of view, [0.01, 180)
  float horizontal_fov_deg = 0.0f;   // 0 (not given) or [0.01, 180)
  float focal_length_mm = 0.0f;      // 0 (not given) or [0.1, 1e5]
  float sensor_width_mm = 36.0f;     // the sensor's (film gate's) width, [1, 1000]: 36 full frame
  // Rotation about the looking direction (deg), [-180, 180]. Positive turns the camera
  // clockwise as its viewer sees it (an aircraft banking right, right wing down), so the image
  // turns counter-clockwise: the horizon rises to the right. 0 keeps the image's up in the
  // vertical plane through view_dir (north when looking straight up or down).
  float roll_deg = 0.0f;
  bool operator==(const CameraParams&) const = default;
};

struct SunParams {
  glm::vec3 direction{0.0f, 0.7f, 0.35f};  // ENU, towards the sun
  // Sunlight's illuminance at the top of the atmosphere, perpendicular to it (lux), [0, 1e10]:
  // 128 klx is the luminous solar constant (nephele/exposure.h). Radiances come out in cd/m^2.
  // (The old key sun.illuminance, a radiance scale with 20 for the sun, is read as x 6400 lux.)
  float illuminance_lux = 128000.0f;
  float disk_angular_radius_deg = 0.2666f;  // apparent radius of the sun disk, [0, 20]
  // Place the sun by the ephemeris for Scene::time and Scene::location instead of direction.
  // Set by a scene file or flags that give a time without a sun direction.
  bool from_time = false;
  bool operator==(const SunParams&) const = default;
};

// What fills the sky (atmosphere.model).
enum class SkyModel {
  Hillaire,   // Hillaire 2020: transmittance, multiple-scattering, sky-view and
              // aerial-perspective tables; single and multiple scattering, ozone
  Preetham,   // Preetham, Shirley and Smits 1999 analytic daylight (seed 002): cheap, turbidity
              // driven, sun above the horizon only
  Reference,  // brute force per pixel with no tables: slow, for checking the Hillaire path
};

// Which model draws the [clouds] layer (clouds.model): nephele's own, or one of the classical
// models surveyed by seed 004 ([classic], issue 23), for comparison.
enum class CloudModel {
  Nephele,  // the noise clouds marched with multiple-scattering octaves (seeds 000 and 002)
  Blinn,    // Blinn 1982: a uniform layer of small particles, low-albedo single scattering
  Gardner,  // Gardner 1985: textured ellipsoids (cumulus) or a textured sky plane (stratus)
  Kajiya,   // Kajiya and Von Herzen 1984: light array, then Romberg along each eye ray
  Nishita,  // Nishita and Nakamae 1996: metaballs, second-order anisotropic scattering, sky light
  GardnerQuadrics,  // Gardner's impressionistic scenes: convex objects of a quadric and planes
};
inline constexpr CloudModel kCloudModels[] = {CloudModel::Nephele, CloudModel::Blinn,
                                              CloudModel::Gardner, CloudModel::GardnerQuadrics,
                                              CloudModel::Kajiya, CloudModel::Nishita};

// Planet and atmosphere (Hillaire 2020, table 1 for the Earth's defaults): Rayleigh and Mie
// scattering falling off exponentially with altitude, Mie absorption, an ozone layer.
struct AtmosphereParams {
  SkyModel model = SkyModel::Hillaire;
  // Coefficients (1/m) in [0, 0.01] each: at 0.01, 100 m of air has optical depth 1.
  float planet_radius_km = 6360.0f;                // [1000, 10000]
  float atmosphere_height_km = 100.0f;             // top of the atmosphere above ground, [1, 1000]
  glm::vec3 rayleigh_scattering_per_m{5.802e-6f, 13.558e-6f, 33.1e-6f};  // sigma_s at sea level
  float rayleigh_scale_height_m = 8000.0f;         // [100, 1e5]
  float mie_scattering_per_m = 3.996e-6f;          // sigma_s at sea level
  float mie_extinction_per_m = 4.44e-6f;           // sigma_t at sea level (absorption included)
  float mie_scale_height_m = 1200.0f;              // [100, 1e5]
  float mie_g = 0.8f;                               // Cornette-Shanks asymmetry, [0, 0.999]
  glm::vec3 ozone_absorption_per_m{0.650e-6f, 1.881e-6f, 0.085e-6f};  // sigma_a at the peak
  float ozone_peak_altitude_m = 25000.0f;           // the layer's density peaks here ... [0, 1e6]
  float ozone_half_width_m = 15000.0f;  // ... and falls linearly to 0 this far away, [0, 1e6]
  float ground_albedo = 0.1f;                       // Lambertian ground, [0, 1]
  float turbidity = 2.5f;                           // Preetham's haze, [2, 10]
  int view_samples = 32;                            // samples along each sky-view LUT ray
  // Multiple scattering with its angular dependence (the light field's spherical harmonics
  // through the true phases; common/atmosphere_lut_inc.glsl), or false: Hillaire 2020's
  // isotropic Psi_ms, as nephele rendered before.
  bool angular_multiple_scattering = true;
  bool operator==(const AtmosphereParams&) const = default;
};

// One volumetric cloud layer between two spheres (seed 000, section 2.2). Altitudes in
// [0, 1e6] m and below the top of the atmosphere; winds (m/s) in [-200, 200] per component.
struct CloudParams {
  CloudModel model = CloudModel::Nephele;
  float bottom_altitude_m = 1500.0f;  // cloud layer bottom above ground
  float top_altitude_m = 4000.0f;     // cloud layer top above ground, > bottom
  float coverage = 0.45f;             // [0, 1]; 1 = sky fully covered
  // Cloud type [0, 1] (seed 002): 0 stratus, 0.25 stratocumulus, 0.5 altocumulus, 0.75 cumulus,
  // 1 cumulonimbus, blended in between; the weather map's B channel adds B - 0.5.
  float type = 0.75f;
  // Precipitation [0, 1] (seed 002): turns the clouds of the weather map's storm cells (G) into
  // cumulonimbus at 70% coverage or more (local precipitation = this x 2G, at most 1).
  float precipitation = 0.0f;
  float density = 0.5f;               // [0, 1]; scales the cloud density field (seed u_density)
  float extinction_per_m = 1.0f;      // sigma_t at density field value 1 (1/m), (0, 100]
  float attenuation = 1.0f;           // multiplier on sigma_t along view rays (seed u_attenuation), [0, 100]
  float light_attenuation = 1.0f;     // ... along light rays (seed u_attenuation2), [0, 100]
  float albedo = 0.99f;               // single-scattering albedo sigma_s / sigma_t, [0, 1]
  float phase_g_forward = 0.8f;       // forward Henyey-Greenstein lobe, [0, 1)
  float phase_g_backward = -0.3f;     // backward lobe, (-1, 0]
  float phase_lobe_weight = 0.7f;     // weight of the forward lobe, [0, 1] (seed DUAL_LOBE_WEIGHT)
  float powder_strength = 1.0f;       // [0, 1]; 0 disables the powder term (seed 1.9)
  float ambient_strength = 1.0f;      // [0, 100]; scales sky ambient light on clouds
  // Wind (seed 002, 体积云的流动效果). The shape wind moves the clouds' bodies and the weather
  // map; it grows with height by wind_shear_mps at the layer's top, and a sample at height
  // fraction h sits where the wind had carried it h x wind_skew_s longer, so tops lean and
  // anvils stream downwind: displacement = (wind + h shear) (time + h skew), the shear acting
  // over at most a cloud's lifetime (shear_time_s in clouds_inc.glsl).
  glm::vec2 wind_mps{8.0f, 2.0f};        // east, north wind speed at the layer's bottom (m/s)
  // East, north: the wind's growth up to the top (m/s). Each height drifts at its own speed,
  // so over time tops slide away from their bases (an hour at 1 m/s: 3.6 km at the top).
  glm::vec2 wind_shear_mps{1.0f, 0.5f};
  float wind_skew_s = 60.0f;             // [0, 3600]; the seed uses 200
  // The detail noise's own motion relative to the clouds' bodies (east, north, up; m/s; the
  // seed's second, detail wind is wind_mps + this): the wisps move over the bodies and, with
  // the up component, roll up their sides.
  glm::vec3 detail_drift_mps{2.0f, 0.0f, 1.0f};
  // Curl noise (seed 002, Schneider 2015) displaces the detail noise by up to this (m), most at
  // the bases, into swirls and wisps. >= 0; 0 = none.
  float curl_distortion_m = 120.0f;  // [0, 1e4]
  // A flow map of local swirls (seed 002, 局部流动效果): a divergence-free field of eddies a
  // few km across moves the shape noise at up to flow_speed_mps. The noise restarts every
  // flow_cycle_s in two phases half a cycle apart, blended, so it is never stretched further
  // than speed x cycle. 0 = none (and it costs nothing).
  float flow_speed_mps = 0.0f;  // [0, 200]
  float flow_cycle_s = 120.0f;  // [1, 86400]
  float base_noise_period_m = 4500.0f;    // horizontal period of the base 128^3 noise tile, [10, 1e6]
  float detail_noise_period_m = 400.0f;   // period of the detail 32^3 noise tile, [1, 1e5]
  float detail_erosion = 0.8f;            // [0, 1]; how much detail noise erodes the base shape
  // Side of one weather-map tile on the ground (m), [1e3, 1e7]: the map (procedural or a PNG)
  // covers this square and repeats in both directions.
  float weather_period_m = 40000.0f;
  // The procedural weather map evolves with time_s: its cloud clusters form, drift and
  // dissipate over about this time (s); the smallest cells change 8x faster. 0 = a static map.
  // Deterministic: the same seed and time give the same sky; it repeats after 6x this time.
  // 0 or [1, 1e7].
  float weather_evolution_s = 3600.0f;
  // A weather map from a PNG file (path; in a scene file relative to it); empty = procedural.
  // Channels (seed 000, 2.2.2 lays out RGBA as low coverage, high coverage, top height,
  // density; nephele gives G and B the meanings of seed 002 and Schneider 2015), values as
  // stored (no sRGB decode) in [0, 1]:
  //   R coverage: the local coverage is R + 2 coverage - 1, so at coverage 0.5 R is it;
  //   G storm cells: with precipitation > 0, G from 0.1 turns the towers into cumulonimbus
  //     (fully from 0.5) and spreads an anvil over G > 0 (fully from 1/3); nothing otherwise;
  //   B cloud type around the layer's: the local type is type + B - 0.5 (0.5 keeps `type`;
  //     the type sets how high the clouds reach, the seed's B);
  //   A density: scales `density` by 2 A (0.5 keeps it, 1 doubles it).
  // RGBA only, 8 or 16 bits per channel (16-bit values are cut to the texture's 8 bits);
  // validate_scene refuses grey, grey and alpha, and RGB, whose channels would mean something
  // else. (An EXR is read too, as RGBA with a missing alpha of 1.)
  // Orientation: the image lies on the ground as a map is drawn, row 0 (its top) north and
  // columns from west to east; it spans weather_period_m x weather_period_m (a non-square
  // image is stretched) and repeats in both directions, read with bilinear filtering. Its
  // centre lies at the origin (east 0, north 0) at time_s = 0 and moves with the wind: at
  // time t it is at wind_mps x t (east, north; m) at the layer's bottom, and higher in the
  // layer further downwind by the shear and skew (wind_shear_mps, wind_skew_s), as the
  // clouds lean. high_clouds, moving with its own wind, reads at each point the map 0.37 tiles
  // east and 0.61 tiles north of it, so its clouds do not stack over the low ones.
  std::string weather_map;
  // How the clouds scatter the sun's light (issue 42). "seed": Wrenninge's four octaves with
  // the powder term and a conservative diffuse term, as seed 002 lights them.
  // "two-stream" (experimental, stop 33): single scattering plus the two-stream field along
  // the sun's chord through each sample (common/clouds_inc.glsl, cloud_two_stream_fluxes: the
  // light going on and the light scattered back towards the sun, with absorption), nothing
  // counted twice; closer to the path tracer on seven of the eight validation views with
  // droplets, not yet within the 5% (docs/validation.md). The old key
  // clouds.two_stream_light = true / false reads as "two-stream" / "seed". "diffusion"
  // (the default since stop 58): single scattering plus the multiple-scattered light solved on a
  // regular grid around the camera (render/modules/cloud_diffusion: the diffusion equation with
  // van de Hulst's similarity scaling, the sun's beam through each cell's faces as its source);
  // the two-stream light past the grid. The closest of the three to the path tracer on the
  // validation suite and in the lab (docs/validation.md).
  std::string lighting = "diffusion";
  bool two_stream() const { return lighting == "two-stream"; }
  // What the clouds are made of (issue 42). "seed": the seed's optics, sigma_t = density field
  // x extinction_per_m, `albedo`, and two Henyey-Greenstein lobes (phase_g_*). "droplets" (the
  // default since stop 58):
  // water droplets, each genus with its liquid water content and droplet effective radius
  // ([droplets], DropletParams): sigma_t = 3 LWC / (2 rho_water r_eff), the albedo of water
  // droplets and a fitted Mie phase function (render/droplets.h); extinction_per_m, albedo and
  // the phase_g_* keys then keep their defaults (validate_scene refuses others).
  std::string optics = "droplets";
};

// The microphysics of each cloud genus for clouds.optics = "droplets" (issue 42): the liquid
// water content (g/m^3) in the cloud's core, where the noise clouds' density field is 0.1
// (kDropletCoreField, render/frame_params.h; a voxel cloud's field is its grid's density x its
// own), scaled with the field (its height gradient is the profile over height: thin bases,
// dense tops, as the adiabatic water content grows with height), and the droplets' effective
// radius (um). Between genera both blend with clouds.type as the shapes do. Defaults are typical of
// each genus (Miles, Verlinde and Clothiaux 2000 for stratiform clouds; Pruppacher and Klett 1997):
// sigma_t = 1.5 LWC / r_eff gives stratus 0.047 /m, cumulus 0.1 /m, cumulonimbus 0.15 /m.
struct DropletParams {
  float stratus_water_g_m3 = 0.25f, stratus_radius_um = 8.0f;
  float stratocumulus_water_g_m3 = 0.35f, stratocumulus_radius_um = 10.0f;
  float altocumulus_water_g_m3 = 0.2f, altocumulus_radius_um = 7.0f;
  float cumulus_water_g_m3 = 0.6f, cumulus_radius_um = 9.0f;
  float cumulonimbus_water_g_m3 = 1.5f, cumulonimbus_radius_um = 15.0f;
  bool operator==(const DropletParams&) const = default;
};

// A second, higher volumetric layer (altocumulus by default) with its own altitude range,
// coverage, type and wind. It shares the weather map (at another place on it), the noise, the
// lighting and the wind's shear, skew and detail with `clouds`. It must lie wholly above
// `clouds`, and the cirrus above both.
struct HighCloudParams {
  float bottom_altitude_m = 6000.0f;  // above ground, >= clouds.top_altitude_m when coverage > 0
  float top_altitude_m = 7000.0f;     // > bottom_altitude_m
  float coverage = 0.0f;              // [0, 1]; 0 = no high layer (and it costs nothing)
  float type = 0.5f;                  // as clouds.type; 0.5 altocumulus
  float density = 0.4f;               // [0, 1]
  glm::vec2 wind_mps{15.0f, 4.0f};    // east, north (m/s)
};

// A further volumetric layer ([[cloud_layers]]), given as a weather report gives one: its genus,
// where its clouds' bases and tops are, and the sky it covers in oktas. The renderer finds the
// shell and the coverage that draw it so (weather::cloud_shell_m, coverage_for_oktas). It shares
// the noise, the lighting and the wind's shear, skew and detail with `clouds`, reads its own
// part of the weather map, and its clouds may overlap no other layer's that is there (clouds',
// high_clouds', the others'; shells may overlap where they hold no cloud); the cirrus lies above
// it.
struct CloudLayerParams {
  // "stratus", "stratocumulus", "altocumulus", "cumulus" or "cumulonimbus".
  std::string genus = "stratocumulus";
  float base_m = 1000.0f;          // its clouds' bases, above ground, [0, 2e4]
  float top_m = 1500.0f;           // its clouds' tops, above ground, > base_m
  float oktas = 4.0f;              // [0, 8]: the sky it covers seen from the ground; 0 = none
  float density = 0.5f;            // as clouds.density, [0, 1]
  glm::vec2 wind_mps{8.0f, 2.0f};  // east, north (m/s)
  bool operator==(const CloudLayerParams&) const = default;
};
// The volumetric layers a scene can hold: clouds, high_clouds and kMaxCloudLayers - 2 more.
constexpr int kMaxCloudLayers = 6;

// How view rays cross the voxel clouds' regions (seed 002, New Three-Phases Raymarching).
enum class VoxelMarch {
  Plain,       // the noise clouds' adaptive march everywhere (the seed's baseline)
  ThreePhase,  // adaptive steps in the noise clouds, SDF sphere tracing across the voxel regions'
               // empty space, short adaptive steps inside voxel clouds
};

// How samples find the sunlight's attenuation by the voxel clouds (seed 002, SDF Shadow).
enum class VoxelShadow {
  LightMarch,  // the light march (and light volume) through the density, as for noise clouds
  SdfCone,     // cone tracing through the signed distance field (soft shadows, few lookups)
};

enum class MarchMode {
  Default,   // jittered, distance-adaptive step count, early exit, longer light march
  Baseline,  // the seed's algorithm as written: fixed 64-step march, 4-sample light march
};

// The high, thin ice-cloud layer (seed 002, "Cloud Modeling 改进"): a sheet at one altitude,
// drawn in compose (shaders/cirrus_inc.glsl) behind the volumetric clouds when the camera is
// below it and in front of everything when above, lit by the same sun and sky.
struct CirrusParams {
  float altitude_m = 9000.0f;  // above ground, [0, 1e6], above the volumetric layers when coverage > 0
  float coverage = 0.0f;       // [0, 1]; 0 = no cirrus
  // [0, 1]: 0 cirrus (fibrous streaks along the wind), 0.5 cirrostratus (a thin veil),
  // 1 cirrocumulus (rows of small cells), blended in between.
  float type = 0.0f;
  float optical_depth = 0.3f;  // vertical optical depth where the sheet is densest, [0, 4]
  glm::vec2 wind_mps{25.0f, 5.0f};  // east, north: the jet stream moves it faster than the clouds
};

// Ground fog, the "ground fog" layer of simulator image generators (render/modules/ground_fog,
// docs/ground-fog.md): a slab of fog from base_m to top_m above the ground, in which an object
// at visibility_m is seen with 2% of its contrast, fading to clear air over the top softness_m.
// Lit by the sun through the atmosphere, the clouds and the fog above, and by the sky.
struct GroundFogParams {
  float visibility_m = 0.0f;  // inside the fog (m), 0 or [1, 1e5]; 0 = no fog
  float base_m = 0.0f;        // bottom above the ground (m); 0 = down to the ground
  float top_m = 150.0f;       // top above the ground (m)
  float softness_m = 40.0f;   // the density fades out over this much below the top (m)
};

// Rain and snow (render/modules/precipitation, docs/precipitation.md): what falls from the low
// cloud layer (clouds.bottom_altitude_m) to the ground, or evaporates on the way (virga). Seen
// from afar as shafts under the precipitating clouds, as a medium whose extinction follows the
// rate by an empirical law (rain: Marshall-Palmer's drop sizes; snow, drizzle and sleet: their
// particles' area per mass and fall speed), so the visibility falls with the rate.
struct PrecipitationParams {
  float rate_mm_per_h = 0.0f;  // liquid-water equivalent (mm/h), [0, 200]; 0 = none
  std::string kind = "rain";   // "rain", "drizzle", "snow" or "sleet" (wet snow)
  // The lowest height it reaches above the ground (m): 0 = the ground; above it, virga that
  // thins out over the lower half of its fall.
  float bottom_m = 0.0f;
  // True: shafts under the precipitating clouds (the weather map's storm cells, and wherever
  // the layer is nearly closed); false: an even curtain under the whole layer.
  bool shafts = true;
  // True: the particles near the camera (within about 15 m) are drawn one by one, rain as
  // streaks, snow as flakes, falling at their speed with the wind (precipitation_layer.glsl).
  bool particles = true;
  // The camera's shutter time (s), [0, 0.1]: how long the particles are drawn out into
  // streaks; 0 freezes them.
  float shutter_s = 0.02f;
};

// Lightning in the cumulonimbus cells of the low layer (render/modules/lightning,
// docs/lightning.md): in-cloud flashes that light the cloud from inside, and cloud-to-ground
// strokes, branching bolts that flicker and light the clouds, the ground and the rain. The same
// seed and time give the same flashes.
struct LightningParams {
  float flashes_per_min = 0.0f;  // a storm cell's flashes a minute, [0, 30]; 0 = none
  float ground_share = 0.25f;    // the share of them that strike the ground, [0, 1]
  uint32_t seed = 1;             // where and when they flash
};

struct QualityParams {
  MarchMode mode = MarchMode::Default;
  int primary_steps = 64;  // [1, 1024] steps through the cloud layer
  // [1, 64] steps of the light march towards the sun, over the light volume's first voxel
  // (the rest is looked up). 4 since issue 42 (6 before): the real-time frame on lavapipe at
  // 900x600 1.33 -> 1.14 times the seed-lit one, the bench's error 4.13% either way, the
  // validation suite 98.9 -> 99.2 points.
  int light_steps = 4;
  // Temporal reprojection (default mode): each frame of an animation marches one pixel of
  // every march_stride x march_stride block of the cloud buffer and reprojects the rest from
  // the previous frame. 1, 2 or 4; 1 = every pixel every frame. A still image marches all.
  int march_stride = 4;
  // Animation frames' cloud buffer has 1 / cloud_downsample of the image's pixels per axis,
  // 1 to 4 (still images: full resolution).
  int cloud_downsample = 2;
  // Half extent (km) of the light volume: the optical depth towards the sun precomputed on a
  // grid around the camera (fine near it, coarse far away) and looked up by cloud samples
  // after a short light march. 0 = march every light ray with light_steps steps. [0, 1000].
  int light_volume_km = 150;
  VoxelMarch voxel_march = VoxelMarch::ThreePhase;
  VoxelShadow voxel_shadow = VoxelShadow::LightMarch;
  // The SDF cone's half-angle tangent (the seed's LightTangent): larger, softer shadows.
  float sdf_light_tangent = 0.1f;  // [0.001, 10]
  // Light shafts: "volumetric" (the default: the air's single scattering shadowed by the
  // clouds, beams below broken clouds, consistent with the aerial perspective), "screen" (seed
  // 002's screen-space god rays after GPU Gems 3 ch. 13 and its radial blur, which add light)
  // or "off" (the air under the clouds' base dimmed by their mean shadow instead). The screen
  // method's samples (the seed's 10), strength and decay per sample.
  std::string light_shafts = "volumetric";
  int screen_shaft_samples = 10;        // [1, 128]
  float screen_shaft_strength = 0.3f;   // [0, 10]
  float screen_shaft_decay = 0.95f;     // [0, 1]
};

struct OutputParams {
  int width = 900;    // pixels, [1, 16384]
  int height = 600;   // pixels, [1, 16384]
  // The camera's exposure (nephele/exposure.h): luminance (cd/m^2) is scaled by
  // 1 / (1.2 x 2^EV100) before the tone map. A photographer's EV100: about 15 on a sunny day
  // ("sunny 16"), 12 overcast, 8 to 10 at sunset, 3 to 5 in civil twilight, -2 to -3 under a
  // full moon. The old key output.exposure (a linear scale) is read as
  // ev100 = log2(6400 / (1.2 x exposure)) with auto_exposure false.
  // Auto exposure (the default): a reflected-light meter (K = 12.5) reads the frame's
  // log-average luminance L and exposes at log2(8 L) - exposure_compensation_ev, held within
  // [ev100_min, ev100_max]; in a sequence (and the viewer) the exposure moves towards that at
  // most adaptation_ev_per_s per second (of scene time between frames; the viewer's clock).
  bool auto_exposure = true;
  float ev100 = 15.0f;                    // manual exposure, when auto_exposure is false, [-20, 30]
  float ev100_min = -4.0f;                // auto exposure's limits, [-20, 30], min <= max: below
  float ev100_max = 17.0f;                // ev100_min a night stays dark, as the eye sees it
  float exposure_compensation_ev = 0.0f;  // auto: + brightens, [-10, 10]
  float adaptation_ev_per_s = 2.0f;       // auto, sequences and viewer, [0, 1e6]; 0 = at once
  ToneMap tonemap = ToneMap::Aces;        // the display's tone map (PNG files, the viewer)
  // Bloom and glare: the lens spreads a share bloom_strength of the light above
  // bloom_threshold_cd_m2 over a Gaussian of bloom_radius_deg (its sigma, in degrees of view),
  // keeping the image's total light (render/modules/post/post.h). Strength 0: off. Threshold 0:
  // every pixel's light, as a lens's veiling glare; above 0, only the brightest (the sun,
  // sunlit cloud edges).
  float bloom_strength = 0.0f;            // [0, 1]
  float bloom_threshold_cd_m2 = 0.0f;     // [0, 1e12]
  float bloom_radius_deg = 1.0f;          // [0.01, 30]
};

// Where the scene is on the earth: the ENU origin (on the ground below the start position).
struct LocationParams {
  float lat_deg = 0.0f;     // latitude, [-90, 90], north positive (float: ~1 m)
  float lon_deg = 0.0f;     // longitude, [-180, 360], east positive
  float altitude_m = 0.0f;  // the ground's height above sea level
};

// The weather from a report, applied when the scene is loaded: a METAR or SPECI whose cloud
// groups, wind, visibility, present weather and day and time set the clouds' layers, the
// winds, the haze, the storm growth and the time of day on the scene's date. They take
// precedence over the same keys of the other tables (docs/weather-reports.md).
//
// Or, as a report gives them (applied after the report, over it): the wind at the ground, from
// where it blows (deg clockwise from north) at a speed in knots or m/s (one of the two), which
// sets every layer's wind by a 1/7 power law (1.93 times it at 1 km and above); and the
// visibility (m), which sets the haze (what any rain or snow leaves of it).
struct WeatherReportParams {
  std::string metar;             // "" = none
  // A forecast's file (GRIB2 or GRIB1): its cloud cover around the location, valid nearest the
  // scene's time (its own when the scene has none), applied after the report; "" = none.
  std::string grib;
  float wind_from_deg = -1.0f;   // [0, 360]; -1 = not given
  float wind_speed_kt = -1.0f;   // [0, 400]; -1 = not given
  float wind_speed_mps = -1.0f;  // [0, 200]; -1 = not given
  float visibility_m = 0.0f;     // [400, 3e5]; 0 = not given
};

// The artist-driven time of day and weather of seed 003, section 4 (nephele/conditions.h):
// eight keyframe sets by local solar time in a good- and a bad-weather table, blended by
// `weather`.
enum class ConditionsMode {
  Off,      // the physical model alone
  Artist,   // the keyframes instead of it: sky colours and fog, the lights of clouds and ground
  Overlay,  // the physical sky and lights, with the keyframes' sky fog, disc fog, fog on clouds
            // and ground, and star visibility on top
};

struct ConditionsParams {
  ConditionsMode mode = ConditionsMode::Off;
  float weather = 1.0f;  // [0, 1]: 1 the good-weather table, 0 the bad
  float hour = -1.0f;    // local solar time [0, 24); -1 = from `time` and location.lon_deg
  ConditionTable good = default_good_weather();
  ConditionTable bad = default_bad_weather();
};

// A voxel cloud placed in the scene (seed 002, 体素云建模): a density grid with its signed
// distance field, from a file or generated, drawn among the noise clouds and lit as they are.
// At most kMaxVoxelClouds per scene.
struct VoxelCloudParams {
  // OpenVDB (.vdb: float grid "density", optional level set "sdf") or NanoVDB (.nvdb); in a
  // scene file relative to it. Exactly one of file and preset.
  std::string file;
  // A generated cloud (`nephele make-cloud`): "cumulus", "cumulus-congestus", "cumulonimbus",
  // with `seed`, or "cumulus-mesh", baked from the mesh data/meshes/cumulus.obj.
  std::string preset;
  uint32_t seed = 1;
  // ENU (m) of the cloud's anchor: the centre of its base. East and north in [-1e7, 1e7], up in
  // [-1e3, 1e5]. (A scene file may give lat_deg, lon_deg and altitude_m instead: enu_from_lat_lon.)
  glm::vec3 position_m{0.0f, 0.0f, 1500.0f};
  float scale = 1.0f;         // (0, 100]: multiplies the grid's size
  float rotation_deg = 0.0f;  // about the up axis, from north through east, [-360, 360]
  // [0, 100]: the cloud's field is grid density x this, as the noise clouds' density field:
  // with droplets its water is the cumulus' x field / 0.1 (kDropletCoreField), with the seed's
  // optics sigma_t = field x clouds.extinction_per_m. 0.15 gives a core of 1.5 times the
  // cumulus' water, sigma_t 0.15 /m (the seed's optics: the same), as a real one (liquid water
  // 0.5 g/m^3 in droplets of 10 um radius: 1.5 LWC / (rho r) = 0.075/m, up to twice that).
  float density = 0.15f;
  // Moves with the low layer's wind (clouds.wind_mps) when true; else with wind_mps.
  bool follow_wind = true;
  glm::vec2 wind_mps{0.0f, 0.0f};  // east, north (m/s), [-200, 200], when follow_wind is false
  int resolution = 128;            // voxels along the longest axis, [16, 256]
};
constexpr int kMaxVoxelClouds = 16;

// Particle clouds (seed 003, 3.3.2-3.3.4; issue 22): a second cloud model beside the volumetric
// one. Each cloud is a particle system spawned from Perlin noise (one particle at most per cell
// of a grid, where the noise under the cloud's envelope exceeds the threshold that gives
// `coverage`), lit on the CPU by splatting its particles towards the sun (Harris and Lastra
// 2001) and drawn as camera-facing textured quads, back to front, composited with the sky and
// the volumetric clouds in depth order. One cloud per square of `cloud_spacing_m` within
// `field_radius_m` of the origin; the field drifts with `wind_mps`.
struct ParticleCloudParams {
  float coverage = 0.0f;               // [0, 1]: share of the grid's cells holding a particle; 0 = none
  float bottom_altitude_m = 1500.0f;   // the clouds' base above ground, [0, 1e5]
  float top_altitude_m = 2700.0f;      // their highest tops, > bottom_altitude_m
  float field_radius_m = 12000.0f;     // [100, 1e6]
  float cloud_spacing_m = 2000.0f;     // [100, 1e5]
  float cell_m = 100.0f;               // the particles' grid, [1, 1e4]
  float particle_radius_m = 140.0f;    // a particle's radius at the noise's largest value, [1, 1e4]
  float noise_period_m = 900.0f;       // the Perlin noise's lattice spacing, [1, 1e6]
  // 0: a static sky (3D noise); else [1, 1e7]: time's scale in 4D noise, the sky changes over it.
  float evolution_s = 0.0f;
  glm::vec2 wind_mps{0.0f, 0.0f};      // east, north (m/s), [-200, 200] each
  float opacity = 0.5f;                // a particle's opacity at its centre, [0, 1]
  float albedo = 0.9f;                 // single-scattering albedo of a particle, [0, 1]
  float phase_g = 0.6f;                // Henyey-Greenstein asymmetry, (-1, 1)
  // true: the Rayleigh phase of Harris and Lastra's paper (the seed's reference [5]); false:
  // Henyey-Greenstein with phase_g.
  bool rayleigh_phase = false;
  // gamma of Harris and Lastra's forward scattering: the solid angle (sr) about the light's
  // direction whose scattered light counts as going on with it, [0, 4 pi].
  float forward_solid_angle_sr = 0.5f;
  // The light scattered many times, which Harris and Lastra's model leaves out: an isotropic
  // radiance albedo x I_k x sunlight / pi times this, [0, 10]; 0 = their model alone.
  float diffuse_strength = 1.0f;
  int light_buffer = 32;               // the lighting splat buffer's side: 32 or 64 texels
  // The particle layer's pixels per output pixel along each axis, [0.25, 1]: below 1, the
  // particles are drawn off-screen at a lower resolution and filtered up when composed
  // (Cantlay, GPU Gems 3, ch. 23): at 0.5 a quarter of the fragments, where filling them is
  // what costs (a CPU's Vulkan at high resolution), for softer particles. Impostor images
  // follow the layer's resolution.
  float layer_resolution = 1.0f;
  uint32_t seed = 1;
  // Impostors (seed 003, 3.3.4-3.3.6): a cloud farther than impostor_distance_m is drawn once
  // into an atlas and then as one quad, drawn again when the direction to it turns by more than
  // impostor_max_angle_deg, its distance changes by more than impostor_distance_factor, or its
  // lighting changes; at most impostor_updates_per_frame a frame, the old image fading out over
  // impostor_fade_frames. "off" draws every particle every frame; "direct" stores impostors as
  // rectangles (best fit, defragmentation at most atlas_defragmentations_per_s, else a smaller
  // image), "tiles" as tiles of atlas_tile texels with a one-texel border.
  std::string impostors = "direct";
  float impostor_distance_m = 8000.0f;      // [0, 1e7]
  float impostor_max_angle_deg = 1.5f;      // (0, 90]
  float impostor_distance_factor = 1.15f;   // (1, 10]
  float impostor_resolution = 1.0f;         // image texels per particle-layer pixel, [0.1, 4]
  int impostor_updates_per_frame = 8;       // [1, 1024]
  int impostor_fade_frames = 8;             // [1, 1000]
  int atlas_size = 2048;                    // texels a side, [256, 8192]
  int atlas_granule = 16;                   // direct: sizes rounded up to this, [1, 256]
  bool atlas_defragment = true;             // direct and tiles
  float atlas_defragmentations_per_s = 2.0f;  // [0, 1000]
  int atlas_tile = 32;                      // tiles: 16 or 32
};

// The classical cloud models of seed 004 (issue 23), drawn in place of nephele's noise clouds
// when clouds.model names one, between the [clouds] layer's altitudes.
struct ClassicCloudParams {
  // The seed's printing of the formulas where it differs from the papers (Blinn's B and Tr,
  // the Lambert phase function's factor); false: the papers' (docs/classical-clouds.md).
  bool seed_formulas = false;
  // Blinn 1982: n spheres of radius r per unit volume in the layer, optical depth
  // tau = n pi r^2 (top - bottom); phase function "constant", "anisotropic" (1 + x cos alpha),
  // "lambert", "rayleigh" or "hg", with x or g in Blinn's convention (alpha = 0: back towards
  // the light, so forward scattering is x < 0).
  std::string blinn_phase = "hg";
  float blinn_phase_x = -0.6f;               // [-0.99, 0.99] for hg, [-1, 1] for anisotropic
  float blinn_particle_radius_m = 1.0e-5f;   // (0, 1]
  float blinn_particles_per_m3 = 1.0e6f;     // [0, 1e12]: tau 0.79 over the default layer
  float blinn_albedo = 0.9f;                 // omega, [0, 1]
  // Gardner 1985: "cumulus" (an ellipsoid in a share `coverage` of the cells of
  // gardner_spacing_m over the layer), "stratus" (a sky plane at the layer's bottom) or
  // "cirrus" (a thin plane at cirrus.altitude_m, its texture stretched east-west into streaks);
  // clouds.model = gardner-quadrics draws his impressionistic cumulus in the same cells; all
  // textured by his function T with gardner_terms sines from the wavelength gardner_period_m;
  // translucency from the thresholds T1 (centre), T2 (edge) over the range D; shading
  // I = (1 - f){(1 - t)[(1 - s) I_d + s I_s] + t T} + f.
  std::string gardner_clouds = "cumulus";
  float gardner_spacing_m = 3000.0f;         // [100, 1e5]
  float gardner_period_m = 2000.0f;          // [10, 1e6]
  int gardner_terms = 6;                     // [1, 8]
  float gardner_t1 = 0.2f;                   // [0, 1]
  float gardner_t2 = 0.45f;                  // [0, 1]
  float gardner_range = 0.15f;               // D, (0, 1]
  float gardner_ambient = 0.3f;              // f, [0, 1]
  float gardner_texture = 0.4f;              // t, [0, 1]
  float gardner_specular = 0.05f;            // s, [0, 1]
  // Kajiya and Von Herzen 1984 on nephele's density: Romberg's levels (2^levels + 1 samples
  // an eye ray), or the brute-force reference march of the same integral instead.
  int kajiya_levels = 7;                     // [1, 10]
  bool kajiya_reference = false;
  // Nishita and Nakamae 1996: nishita_clouds cumulus of nishita_metaballs metaballs in all
  // (seed 004 times 338 and 358), standing on the layer's bottom within a square of
  // nishita_extent_m about nishita_center_m (east, north), on a voxel grid of nishita_voxels
  // along its longest side; sigma_t at a ball's centre (its central density q in [0.6, 1] times
  // nishita_sigma_t_per_m), single-scattering albedo; the scattering orders summed (1 or 2) and
  // the sky's light.
  int nishita_metaballs = 338;               // [1, 4096]
  int nishita_clouds = 4;                    // [1, 64], at most nishita_metaballs
  float nishita_extent_m = 8000.0f;          // [500, 1e5]
  glm::vec2 nishita_center_m{0.0f, 9000.0f}; // [-1e6, 1e6] each
  float nishita_sigma_t_per_m = 0.05f;       // (0, 10]
  float nishita_albedo = 0.99f;              // [0, 1]
  int nishita_voxels = 96;                   // [16, 192]
  int nishita_order = 2;                     // 1 or 2
  bool nishita_sky_light = true;
};

// The lab scene (issue 21): one density grid in vacuum (no planet, no air, a black background)
// lit by a distant sun, for comparing nephele's reference path tracer (Renderer::render_reference)
// with other renderers. The grid keeps its file's frame (x east, y north, z up, metres) and
// densities; the camera is the scene's.
struct LabParams {
  std::string grid;             // OpenVDB or NanoVDB file (as voxel clouds'); empty = no lab
  float sigma_t_per_m = 0.05f;  // extinction at density 1 (1/m), (0, 1000]
  float albedo = 1.0f;          // single-scattering albedo, [0, 1]
  float g = 0.8f;               // Henyey-Greenstein asymmetry, (-1, 1)
  int max_bounces = 64;         // scatterings after the first, [0, 100000]; 0 = single scattering
  float sun_elevation_deg = 45.0f;   // [-90, 90]
  float sun_azimuth_deg = 0.0f;      // from north through east, [-360, 360]
  float sun_irradiance = 1.0f;       // W/m^2, perpendicular to the light, [0, 1e6]
};

// A terrain under the clouds (issue 24): a heightfield from a file, or the procedural
// `mountains`, standing on the ground sphere in the scene's east-north-up frame (scene.h's ENU;
// heights above the ground at location.altitude_m). Lit by the sun and the sky, shadowed by
// the clouds, fogged by the air; it hides the sky and the clouds behind it.
struct TerrainParams {
  // .png (16-bit grey), .exr (its first channel), .tif/.tiff (a GeoTIFF elevation model, placed
  // by its georeferencing relative to location.lat_deg/lon_deg, heights above sea level) or
  // .obj (a mesh in metres, x east, y up, -z north, as Blender writes it, centred on center_m);
  // empty = none.
  std::string file;
  std::string preset;                  // "mountains": procedural; at most one of file and preset
  glm::vec2 extent_m{40000.0f, 40000.0f};  // east-west, north-south size (PNG, EXR, mountains), (0, 1e6]
  glm::vec2 center_m{0.0f, 0.0f};      // its centre (east, north), [-1e6, 1e6] each (not GeoTIFF)
  float height_m = 2500.0f;            // PNG, EXR: the height of the file's largest value; mountains:
                                       // the highest peak, [0, 1e4]
  float base_m = 0.0f;                 // PNG, EXR, mountains: the height of the value 0, [-1e4, 1e4]
  glm::vec3 albedo{0.13f, 0.12f, 0.09f};  // Lambertian albedo of the bare ground, [0, 1] each
  // An image of the ground's albedo over the terrain's rectangle (row 0 north): .png (sRGB) or
  // .exr (linear RGB); empty = `albedo` everywhere.
  std::string albedo_map;
  float snow_altitude_m = 0.0f;        // snow (albedo 0.8) above this height on slopes under
                                       // 40 deg, [0, 1e4]; 0 = none
  int resolution = 512;                // mountains: grid points along each axis, [16, 4096]
  // How the view rays find it: "raycast" (the default: rays walk a pyramid of the heights'
  // maxima in compute) or "raster" (seed 002's mesh: two triangles a cell drawn with depth).
  std::string method = "raycast";
  uint32_t seed = 1;                   // mountains
};

struct Scene {
  CameraParams camera;
  SunParams sun;
  AtmosphereParams atmosphere;
  CloudParams clouds;
  HighCloudParams high_clouds;
  DropletParams droplets;
  CirrusParams cirrus;
  GroundFogParams ground_fog;
  PrecipitationParams precipitation;
  LightningParams lightning;
  QualityParams quality;
  OutputParams output;
  LocationParams location;
  ConditionsParams conditions;
  WeatherReportParams weather;
  // Date and time (ISO 8601, UTC or with an offset: "2026-06-21T18:30:00Z"); empty = none (no
  // moon, and the sun from sun.direction). The sky's clock is time + time_s.
  std::string time;
  float time_s = 0.0f;       // animation time (s): moves clouds with the wind, [-1e6, 1e6]
  uint32_t noise_seed = 1;   // seeds the noise textures and the procedural weather map
  std::vector<VoxelCloudParams> voxel_clouds;
  std::vector<CloudLayerParams> cloud_layers;  // at most kMaxCloudLayers - 2
  ParticleCloudParams particle_clouds;
  ClassicCloudParams classic;
  LabParams lab;
  TerrainParams terrain;
};

// The camera's vertical field of view (deg) for an image of width / height `aspect`, from
// whichever form CameraParams gives it in: the vertical keeps its tangent's ratio to the
// horizontal, tan(v / 2) = tan(h / 2) / aspect.
float vertical_fov_deg(const CameraParams& camera, float aspect);
float vertical_fov_deg(const Scene& scene);  // for scene.output's aspect
// The horizontal field of view (deg) of a focal length on a sensor: 2 atan(width / (2 f)).
float horizontal_fov_from_focal_deg(float focal_length_mm, float sensor_width_mm);

// quality.light_shafts as its index (0 off, 1 volumetric, 2 screen); -1 for anything else.
int light_shafts_method(const std::string& name);

const char* to_string(MarchMode mode);
const char* to_string(CloudModel model);
const char* to_string(VoxelMarch mode);
const char* to_string(VoxelShadow mode);
const char* to_string(SkyModel model);
const char* to_string(ConditionsMode mode);

}  // namespace nephele

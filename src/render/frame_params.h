// Scene (user units, ENU) -> FrameParams (GPU units, planet frame), plus the per-frame
// lighting computed on the CPU with the shaders' own functions (render/glsl.h).
#pragma once

#include <optional>
#include <vector>

#include "nephele/scene.h"
#include "nephele/sky.h"
#include "render/glsl.h"
#include "render/gpu_params.h"

namespace nephele {

// The planet-frame position (m) of an ENU position (m): the ENU origin is on the ground at
// (0, 0, planet radius); ENU axes are the planet frame's axes there.
glm::vec3 planet_from_enu(const Scene& scene, const glm::vec3& enu_m);

glsl::Atmosphere make_atmosphere(const Scene& scene);  // (its type is each file's own)

// The air's transmittance from the camera to the top of the atmosphere towards unit `dir`
// (ENU; 0 when the planet is in the way), and the air's extinction at the camera (1/m).
glm::vec3 camera_air_transmittance(const Scene& scene, const glm::vec3& dir);
glm::vec3 camera_air_sigma_t(const Scene& scene);

// Hillaire's transmittance and multiple-scattering tables on the host, for the per-frame
// lighting computed on the CPU (ambient light at the clouds, sky light on the ground). The
// renderer reads them back from the GPU; compute_atmosphere_tables makes them on the CPU with
// the same functions (for callers without a device, and to test one against the other).
struct AtmosphereTables {
  std::vector<glm::vec4> transmittance;        // TRANSMITTANCE_LUT_W x TRANSMITTANCE_LUT_H
  std::vector<glm::vec4> multiple_scattering;  // MS_LUT_W x MS_LUT_H (log Psi_ms)
  // The multiple-scattering light field: MS_FIELD_COEFFS blocks of MS_FIELD_W x MS_FIELD_H side
  // by side, in two halves (rows [0, H) the field, [H, 2 H) an earlier iteration)
  std::vector<glm::vec4> ms_field;
  glsl::sampler2D transmittance_lut() const {
    return {transmittance.data(), glsl::TRANSMITTANCE_LUT_W, glsl::TRANSMITTANCE_LUT_H};
  }
  glsl::sampler2D ms_lut() const {
    return {multiple_scattering.data(), glsl::MS_LUT_W, glsl::MS_LUT_H};
  }
  glsl::sampler2D ms_field_lut() const {
    return {ms_field.data(), glsl::MS_FIELD_COEFFS * glsl::MS_FIELD_W, 2 * glsl::MS_FIELD_H};
  }
};
AtmosphereTables compute_atmosphere_tables(const Scene& scene);

// Camera basis: forward, right, up (unit vectors, up is the image's up).
struct CameraBasis {
  glm::vec3 forward, right, up;
};
// The basis of a camera without roll: right horizontal, up in the vertical plane through
// view_dir (north when looking straight up or down).
CameraBasis camera_basis(const glm::vec3& view_dir);
// The camera's basis: camera_basis(view_dir) turned about forward by roll_deg, clockwise as the
// viewer sees it: right = cos r right0 - sin r up0, up = cos r up0 + sin r right0. Roll 0 gives
// camera_basis(view_dir) bit for bit.
CameraBasis camera_basis(const CameraParams& camera);

// The light whose direct light and shadows the clouds and the ground get: the sun, or at night
// the moon once it lights the middle of the cloud layer more than the setting sun does (the
// hand-over happens where both are equally bright, after the sun has set there). The sky-view
// LUT is oriented to it.
struct KeyLight {
  glm::vec3 direction;  // ENU unit vector towards it
  float illuminance;    // at the top of the atmosphere, in the units of sun.illuminance
  bool moon = false;
};

// The sky's lights of one frame: the ephemeris (computed once: libnova's lunar series costs
// about 2 ms), the key light chosen from it, and the other of sun and moon while it still
// lights the sky (above kSecondLightMinElevationDeg; illuminance 0 when none). Sky, aerial
// perspective and the clouds' ambient light sum both, so nothing jumps when the key light
// changes; only the key light casts the clouds' direct light and shadows.
struct SkyLights {
  std::optional<Ephemeris> ephemeris;  // when the scene has a time
  KeyLight key;
  KeyLight second{glm::vec3(0.0f, 0.0f, 1.0f), 0.0f};
};
// Below this elevation the sun or moon lights no air under the atmosphere's top (100 km) for
// 1100 km around (the sky seen from the ground down to the horizon): its sky is black.
constexpr float kSecondLightMinElevationDeg = -20.0f;
SkyLights sky_lights(const Scene& scene);

// The time-of-day keyframes' conditions for the scene's hour (conditions.hour, or the local
// solar time of its date at location.lon_deg) and weather; none when conditions.mode is off.
std::optional<ConditionSet> scene_conditions(const Scene& scene,
                                             const std::optional<Ephemeris>& ephemeris);
inline KeyLight key_light(const Scene& scene) { return sky_lights(scene).key; }

// The moon's illuminance at the top of the atmosphere as a share of the sun's: the full moon's
// 2.44e-6 (magnitude -12.73 against -26.74) at 384,400 km, dimmed with the phase angle by the
// empirical law m(i) = 0.026 |i| + 4e-9 i^4 (i in degrees; Allen's Astrophysical Quantities).
double moon_illuminance_ratio(double illuminated_fraction, double distance_km);

// The atmosphere's fields of FrameParams (radii_m.xy, rayleigh, mie, ozone, sky_model): all the
// table passes read.
void set_atmosphere(gpu::FrameParams& f, const Scene& scene);


// The flow map of local swirls (clouds.flow_speed_mps) is the curl noise texture over a tile
// of this size: eddies about 4 km across (its coarsest octave has 4 cells a tile).
constexpr float kFlowMapPeriodM = 16000.0f;

// A volumetric layer that is there (layer 0, clouds, always), as the renderer draws it: its
// shell and where its clouds' bases and tops are (m above ground: weather::clouds_in_shell_m
// for clouds and high_clouds), its coverage, density, type and wind, and its slot in
// FrameParams::cloud_layers.
struct VolumetricLayer {
  glm::vec2 shell_m, clouds_m;
  float coverage, density, type;
  glm::vec2 wind_mps;
  int slot;
};
std::vector<VolumetricLayer> volumetric_layers(const Scene& scene);
// The altitudes (m above ground) of the cloud shell: from the lowest volumetric layer's bottom
// to the highest's top.
glm::vec2 cloud_shell_m(const Scene& scene);

// How far (m) the clouds' features have moved since time 0 relative to the main layer's wind
// frame (the light volume's): the wind's growth at the top, the detail noise's own wind and
// the other layers' winds. The light volume is rebuilt as this grows.
float cloud_relative_drift_m(const Scene& scene);

// The cloud field's part of the frame parameters (what noise_density_inc.glsl reads: the
// planet's and the atmosphere's radii, the layers, winds, flow, noise scales, extinction);
// make_frame_params sets it, and the host's CPU queries (render/cloud_query.cpp) alone.
void set_cloud_field(gpu::FrameParams& f, const Scene& scene);

// The noise clouds' density field in a cloud's core, where a genus holds its liquid water
// ([droplets]): the field is the seed's (its optics: sigma_t = field x 1 /m), whose cores reach
// 0.07-0.1 in the default preset (clouds.density 0.5), 0.14-0.2 in the overcast's, 0.23-0.27 in
// the stratus' (the 99th percentile and the largest value over 30 km). So the default
// cumulus' columns have a median optical depth of 6.8 (95th percentile 26), the overcast's 46
// (docs/cloud-optics.md).
constexpr float kDropletCoreField = 0.1f;

// The clouds' optics (clouds.optics, issue 42). For "droplets": each genus' sigma_t at density
// field 1 (1/m, its water at kDropletCoreField; stratus, stratocumulus, altocumulus, cumulus,
// cumulonimbus) from its liquid water and droplet radius, the droplets' effective radius at the
// main layer's type (um; the phase function's and the albedo's, one for all clouds), and the voxel
// clouds' sigma_t at density 1 (the cumulus'). The Mie fit's Henyey-Greenstein lobe is the
// diffraction peak (g 0.97-0.995: within a degree or two forwards) and carries about half the
// scattering: light scattered into it goes on as if unscattered, so the optics are delta-scaled
// (Joseph et al. 1976; DISORT's delta-M): the peak's share f leaves sigma_t and the phase function,
// sigma_t' = sigma_t (1 - omega f), albedo' = omega (1 - f) / (1 - omega f), the phase the Draine
// lobe. The same radiative transfer but for sub-degree detail around the sun, and without the
// peak's fireflies in the path tracer (next-event estimation towards the sun meets a phase
// function 4000 times isotropic's there). For "seed": extinction_per_m for every genus and
// the voxel clouds, the seed's albedo and lobes.
struct CloudOptics {
  bool droplets = false;
  float genus_sigma_t_per_m[5] = {};
  float radius_um = 0.0f;
  float voxel_sigma_t_per_m = 0.0f;
  float albedo = 1.0f;              // single-scattering albedo
  glm::vec4 mie = glm::vec4(0.0f);  // droplets: mie_fit's lobes, the Draine lobe's weight 1
  float peak_fraction = 0.0f;       // droplets: the share of scattering the peak took out
  float max_sigma_t_per_m() const;
};
CloudOptics cloud_optics(const Scene& scene);

// A window of a larger image: the scene's output.width x output.height pixels starting at
// pixel (x, y) of a full_width x full_height image of the same camera (a tile of a still too
// large for the device). Its pixels see exactly what the whole image's would.
struct ImageWindow {
  int x = 0, y = 0;
  int full_width = 0, full_height = 0;
};

gpu::FrameParams make_frame_params(const Scene& scene, int frame_index, const SkyLights& lights,
                                   const AtmosphereTables& tables,
                                   const ImageWindow* window = nullptr);
// Everything but the camera, the time and the sun (the scene as TOML): when it changes, a
// frame's history is stale.
std::string history_key(Scene scene);

inline gpu::FrameParams make_frame_params(const Scene& scene, int frame_index) {
  return make_frame_params(scene, frame_index, sky_lights(scene), compute_atmosphere_tables(scene));
}

// Fills the previous frame's camera and the wind's displacement since then (for reprojection).
void set_previous_frame(gpu::FrameParams& params, const Scene& scene, const Scene& previous);

// What the sky-view LUT depends on: the FrameParams fields sky_view.comp reads (its frame,
// sky_view_up and sky_view_forward, follows from the camera position and the sun). The camera
// position gives the LUT's up vector and altitude. The renderer recomputes the LUT only when
// the key changes.
struct SkyViewKey {
  glm::vec3 camera_pos_m, sun_dir, sun_illuminance, ground_sky_light;
  glm::vec4 second_light;
  glm::vec4 rayleigh, mie, ozone, sky_model;
  glm::ivec4 sky_options;
  glm::vec2 radii_m;   // planet, atmosphere top
  int samples;  // sky view samples (FrameParams::steps.z)
  bool operator==(const SkyViewKey&) const = default;
};
SkyViewKey sky_view_key(const gpu::FrameParams& f);
// Whether a LUT built for `built` serves `now`: the same atmosphere and samples, the sun (and
// the second light) within kSkyViewReuseSunDeg, and the camera within kSkyViewReuseM of where it was built and within 1% of its altitude (at most
// kSkyViewReuseM; the horizon's dip changes with altitude, fastest near the ground).
constexpr float kSkyViewReuseM = 50.0f;
constexpr float kSkyViewReuseSunDeg = 0.05f;
bool sky_view_reusable(const SkyViewKey& built, const SkyViewKey& now);

}  // namespace nephele

#include "render/frame_params.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "nephele/exposure.h"
#include "nephele/image.h"
#include "nephele/scene_io.h"
#include "nephele/sky.h"
#include "sky/stars.h"
#include "weather/weather_state.h"

namespace nephele {

glm::vec3 planet_from_enu(const Scene& scene, const glm::vec3& enu_m) {
  return {enu_m.x, enu_m.y, scene.atmosphere.planet_radius_km * 1000.0f + enu_m.z};
}

glsl::Atmosphere make_atmosphere(const Scene& scene) {
  const AtmosphereParams& p = scene.atmosphere;
  glsl::Atmosphere a;
  a.planet_radius_m = p.planet_radius_km * 1000.0f;
  a.top_radius_m = (p.planet_radius_km + p.atmosphere_height_km) * 1000.0f;
  a.rayleigh_sigma_s = p.rayleigh_scattering_per_m;
  a.rayleigh_height_m = p.rayleigh_scale_height_m;
  a.mie_sigma_s = p.mie_scattering_per_m;
  a.mie_sigma_t = p.mie_extinction_per_m;
  a.mie_height_m = p.mie_scale_height_m;
  a.mie_g = p.mie_g;
  a.ozone_sigma_a = p.ozone_absorption_per_m;
  a.ozone_center_m = p.ozone_peak_altitude_m;
  a.ozone_half_width_m = p.ozone_half_width_m;
  return a;
}

glm::vec3 camera_air_transmittance(const Scene& scene, const glm::vec3& dir) {
  return glsl::atmosphere_transmittance_to_top(make_atmosphere(scene),
                                               planet_from_enu(scene, scene.camera.position_m), dir, 256);
}

glm::vec3 camera_air_sigma_t(const Scene& scene) {
  return glsl::atmosphere_sigma_t(make_atmosphere(scene), scene.camera.position_m.z);
}

AtmosphereTables compute_atmosphere_tables(const Scene& scene) {
  const glsl::Atmosphere a = make_atmosphere(scene);
  AtmosphereTables t;
  const auto texel_uv = [](int i, int j, int w, int h) {
    return glm::vec2((float(i) + 0.5f) / float(w), (float(j) + 0.5f) / float(h));
  };
  constexpr int tw = glsl::TRANSMITTANCE_LUT_W, th = glsl::TRANSMITTANCE_LUT_H;
  t.transmittance.resize(size_t(tw) * th);
  for (int j = 0; j < th; ++j)
    for (int i = 0; i < tw; ++i)
      t.transmittance[size_t(j) * tw + i] =
          glm::vec4(glsl::transmittance_lut_texel(a, texel_uv(i, j, tw, th)), 1.0f);
  constexpr int mw = glsl::MS_LUT_W, mh = glsl::MS_LUT_H;
  t.multiple_scattering.resize(size_t(mw) * mh);
  for (int j = 0; j < mh; ++j)
    for (int i = 0; i < mw; ++i)
      t.multiple_scattering[size_t(j) * mw + i] = glm::vec4(
          glsl::ms_lut_texel(a, t.transmittance_lut(), texel_uv(i, j, mw, mh),
                             scene.atmosphere.ground_albedo),
          1.0f);
  // The field's iterations, as ms_field.comp runs them: iteration i writes half i mod 2.
  constexpr int fw = glsl::MS_FIELD_W, fh = glsl::MS_FIELD_H, blocks = glsl::MS_FIELD_COEFFS;
  t.ms_field.assign(size_t(fw) * blocks * fh * 2, glm::vec4(0.0f));
  for (int iteration = 0; iteration < glsl::MS_FIELD_ITERATIONS; ++iteration) {
    const size_t first_row = size_t(iteration % 2) * fh;
    for (int j = 0; j < fh; ++j)
      for (int i = 0; i < fw; ++i) {
        const glsl::MsFieldCoefficients texel =
            glsl::ms_field_texel(a, t.transmittance_lut(), t.ms_lut(), t.ms_field_lut(), iteration,
                                 texel_uv(i, j, fw, fh), scene.atmosphere.ground_albedo);
        for (int k = 0; k < blocks; ++k)
          t.ms_field[(first_row + j) * fw * blocks + size_t(k) * fw + i] =
              glm::vec4(texel.c[k], 1.0f);
      }
  }
  return t;
}

CameraBasis camera_basis(const glm::vec3& view_dir) {
  CameraBasis b;
  b.forward = glm::normalize(view_dir);
  // Looking straight up or down, "up" on the image is north.
  glm::vec3 world_up = std::abs(b.forward.z) > 0.999f ? glm::vec3(0, 1, 0) : glm::vec3(0, 0, 1);
  b.right = glm::normalize(glm::cross(b.forward, world_up));
  b.up = glm::cross(b.right, b.forward);
  return b;
}

CameraBasis camera_basis(const CameraParams& camera) {
  CameraBasis b = camera_basis(camera.view_dir);
  if (camera.roll_deg == 0.0f) return b;
  const float roll_rad = glm::radians(camera.roll_deg);
  const float c = std::cos(roll_rad), s = std::sin(roll_rad);
  const glm::vec3 right = c * b.right - s * b.up;
  b.up = c * b.up + s * b.right;
  b.right = right;
  return b;
}

namespace {

constexpr int kSkyDirections = 64;

// The sky the CPU sees: Hillaire's model through the tables, as sky_view.comp computes it.
struct CpuSky {
  glsl::Atmosphere atmosphere;
  const AtmosphereTables& tables;
  float ground_albedo;
  int ms_mode;  // MS_ANGULAR or MS_ISOTROPIC
};

// Mean, over kSkyDirections directions dir_of(i, golden angle), of the sky radiance seen from
// `pos` per unit solar illuminance (a ground hit counts with its sun-lit part).
template <typename DirOf>
glm::vec3 mean_sky(const CpuSky& sky, const glm::vec3& pos, const glm::vec3& sun, DirOf dir_of) {
  const float golden = glsl::PI * (3.0f - std::sqrt(5.0f));
  glm::vec3 sum(0.0f);
  for (int i = 0; i < kSkyDirections; ++i) {
    const glsl::SkySample s =
        glsl::sky_hillaire(sky.atmosphere, sky.tables.transmittance_lut(), sky.tables.ms_lut(),
                           sky.tables.ms_field_lut(), sky.ms_mode, false, pos, dir_of(i, golden),
                           sun, 12, sky.ground_albedo, glm::vec3(0.0f));
    sum += s.radiance + s.ground_sun;
  }
  return sum / float(kSkyDirections);
}

// Irradiance on a horizontal surface at `pos` facing up (or down) divided by pi, per unit solar
// illuminance: the cosine-weighted mean radiance over the upper (or lower) hemisphere.
glm::vec3 hemisphere_radiance(const CpuSky& sky, const glm::vec3& pos, const glm::vec3& sun,
                              bool up_side = true) {
  const glm::vec3 up = glm::normalize(pos) * (up_side ? 1.0f : -1.0f);
  const glm::vec3 east = glm::normalize(glm::cross(glm::vec3(0, 1, 0), up));
  const glm::vec3 north = glm::cross(up, east);
  return mean_sky(sky, pos, sun, [&](int i, float golden) {
    // Cosine-weighted: sin^2 of the angle from the axis uniform in [0, 1].
    float s2 = (float(i) + 0.5f) / float(kSkyDirections);
    float sin_t = std::sqrt(s2), cos_t = std::sqrt(1.0f - s2);
    return sin_t * (std::cos(golden * float(i)) * east + std::sin(golden * float(i)) * north) +
           cos_t * up;
  });
}

constexpr double kMoonRadiusKm = 1737.4;
constexpr double kMoonMeanDistanceKm = 384400.0;
constexpr double kFullMoonRatio = 2.44e-6;
// Earthshine on the moon's night side, as a share of the full moon's radiance, when the earth
// seen from the moon is full (new moon): the ashen light is a few 1e-4 of the bright limb.
constexpr double kEarthshine = 2.0e-4;

// Phase angle (rad) from the illuminated fraction k = (1 + cos i) / 2.
double phase_angle_rad(double k) { return std::acos(std::clamp(2.0 * k - 1.0, -1.0, 1.0)); }

// The disk-integrated brightness of a Lommel-Seeliger sphere at phase angle i, 1 at full
// (the law compose.comp shades the disk with): 1 - sin(i/2) tan(i/2) ln(cot(i/4)).
double lommel_seeliger_phase(double i) {
  if (i < 1e-4) return 1.0;
  if (i > glsl::PI - 1e-4) return 0.0;
  return std::max(1.0 - std::sin(i / 2) * std::tan(i / 2) * std::log(1.0 / std::tan(i / 4)), 1e-6);
}

// The middle of the cloud layer above the camera (planet frame, m), where the clouds' direct
// and ambient light are measured.
glm::vec3 cloud_layer_middle(const Scene& scene, float planet_radius_m) {
  const CloudParams& c = scene.clouds;
  return {scene.camera.position_m.x, scene.camera.position_m.y,
          planet_radius_m + 0.5f * (c.bottom_altitude_m + c.top_altitude_m)};
}

// Luminance of a unit light from `dir` reaching the middle of the cloud layer.
float direct_luminance_at_clouds(const Scene& scene, const glm::vec3& dir) {
  const glsl::Atmosphere atmosphere = make_atmosphere(scene);
  const glm::vec3 t = glsl::atmosphere_transmittance_to_top(
      atmosphere, cloud_layer_middle(scene, atmosphere.planet_radius_m), dir, 32);
  return luminance(glm::vec4(t, 0.0f));
}

}  // namespace

double moon_illuminance_ratio(double k, double distance_km) {
  const double i_deg = phase_angle_rad(k) * 180.0 / glsl::PI;
  const double dm = 0.026 * i_deg + 4e-9 * std::pow(i_deg, 4.0);
  const double d = kMoonMeanDistanceKm / distance_km;
  return kFullMoonRatio * std::pow(10.0, -0.4 * dm) * d * d;
}

// The moon disk's parameters (params_inc.glsl): where it is, which side the sun lights, how
// bright its full disk would be at the camera in units of the key light's illuminance.
static void set_moon(gpu::FrameParams& f, const Scene& scene, const glsl::Atmosphere& atmosphere,
                     const SkyLights& lights) {
  f.moon_dir = glm::vec4(0.0f, 0.0f, 1.0f, 2.0f);  // no moon
  const std::optional<Ephemeris>& e = lights.ephemeris;
  if (!e) return;
  const double radius_rad = std::asin(kMoonRadiusKm / e->moon.distance_km);
  f.moon_dir = glm::vec4(e->moon.direction, float(std::cos(radius_rad)));
  // Geocentric enough: the sun seen from the moon, from the two positions (km).
  const glm::dvec3 sun_km = glm::dvec3(e->sun.direction) * e->sun.distance_km;
  const glm::dvec3 moon_km = glm::dvec3(e->moon.direction) * e->moon.distance_km;
  const double k = e->moon_illuminated_fraction;
  f.moon_sun_dir = glm::vec4(glm::vec3(glm::normalize(sun_km - moon_km)), float(kEarthshine * (1.0 - k)));
  // Full-disk radiance: the full moon's illuminance over the disk's solid angle, scaled by the
  // empirical phase law over the Lommel-Seeliger law that compose.comp shades the disk with.
  const double solid_angle = 2.0 * glsl::PI * (1.0 - std::cos(radius_rad));
  const double full_disk = kFullMoonRatio *
                           std::pow(kMoonMeanDistanceKm / e->moon.distance_km, 2.0) / solid_angle;
  const double phase = moon_illuminance_ratio(k, e->moon.distance_km) /
                       moon_illuminance_ratio(1.0, e->moon.distance_km) /
                       lommel_seeliger_phase(phase_angle_rad(k));
  const glm::vec3 eye = planet_from_enu(scene, scene.camera.position_m);
  const glm::vec3 t = glsl::atmosphere_transmittance_to_top(atmosphere, eye, e->moon.direction, 256);
  f.moon_radiance = glm::vec4(t * float(full_disk * std::min(phase, 50.0) * scene.sun.illuminance_lux /
                                        std::max(lights.key.illuminance, 1e-30f)),
                              0.0f);
}

// The star field's rotation into this sky and the scale of its pixels; no stars without a date.
static void set_stars(gpu::FrameParams& f, const Scene& scene, const std::optional<Ephemeris>& e,
                      float tan_half_fov) {
  if (!e) return;  // f.stars.y = 0: none drawn
  const glm::mat3 m = enu_from_j2000(e->jd_ut, scene.location.lat_deg, e->local_sidereal_time_deg);
  f.star_east = glm::vec4(m[0][0], m[1][0], m[2][0], 0.0f);  // rows of m
  f.star_north = glm::vec4(m[0][1], m[1][1], m[2][1], 0.0f);
  f.star_up = glm::vec4(m[0][2], m[1][2], m[2][2], 0.0f);
  const float pixel_rad = 2.0f * tan_half_fov / float(scene.output.height);
  f.stars = glm::vec4(scene.sun.illuminance_lux, float(star_catalogue().size()), pixel_rad * pixel_rad, 0.0f);
}

// The time-of-day keyframes' set for this frame, per unit of the key light's illuminance; the
// lights of clouds and ground are set by make_frame_params from the set returned.
static std::optional<ConditionSet> set_conditions(gpu::FrameParams& f, const Scene& scene,
                                                  const SkyLights& lights) {
  f.conditions_sky_fog.w = 1.0f;  // stars fully visible
  const std::optional<ConditionSet> c = scene_conditions(scene, lights.ephemeris);
  if (!c) return c;
  // The keyframes' colours are on the old radiance scale (conditions.h): x kLegacyLuxPerUnit in
  // cd/m^2.
  const float per_unit = kLegacyLuxPerUnit / std::max(lights.key.illuminance, 1e-30f);
  f.conditions_sky = glm::vec4(c->sky_zenith_rgb * per_unit,
                               scene.conditions.mode == ConditionsMode::Artist ? 1.0f : 2.0f);
  f.conditions_sky_fog = glm::vec4(c->sky_fog_rgb * per_unit, c->star_visibility);
  f.conditions_fog_deg = glm::vec4(c->sky_fog_start_deg, c->sky_fog_end_deg,
                                   c->disk_fog_start_deg, c->disk_fog_end_deg);
  f.conditions_disk_fog = glm::vec4(c->disk_fog_rgb * per_unit, c->fog_near_m);
  f.conditions_fog = glm::vec4(c->fog_rgb * per_unit, c->fog_far_m);
  f.conditions_light =
      glm::vec4((lights.key.moon ? c->moon_light_rgb : c->sun_light_rgb) * per_unit, 0.0f);
  return c;
}

std::optional<ConditionSet> scene_conditions(const Scene& scene,
                                             const std::optional<Ephemeris>& ephemeris) {
  const ConditionsParams& p = scene.conditions;
  if (p.mode == ConditionsMode::Off) return std::nullopt;
  float hour = p.hour;
  if (hour < 0.0f && ephemeris) hour = local_solar_hour(ephemeris->jd_ut, scene.location.lon_deg);
  return conditions_at(p.good, p.bad, std::max(hour, 0.0f), p.weather);
}

SkyLights sky_lights(const Scene& scene) {
  SkyLights lights{scene_ephemeris(scene), {}};
  const std::optional<Ephemeris>& e = lights.ephemeris;
  const glm::vec3 sun = scene_sun_direction(scene, e);
  lights.key = {sun, scene.sun.illuminance_lux, false};
  if (!e || sun.z > 0.0f) return lights;  // by day the moon's sky is a millionth of the sun's
  const float moon_share =
      float(moon_illuminance_ratio(e->moon_illuminated_fraction, e->moon.distance_km));
  const KeyLight moon{e->moon.direction, scene.sun.illuminance_lux * moon_share, true};
  const float min_z = std::sin(glm::radians(kSecondLightMinElevationDeg));
  if (direct_luminance_at_clouds(scene, sun) <
      moon_share * direct_luminance_at_clouds(scene, moon.direction)) {
    lights.key = moon;
    if (sun.z > min_z) lights.second = {sun, scene.sun.illuminance_lux, false};
  } else if (moon.direction.z > min_z) {
    lights.second = moon;
  }
  return lights;
}

void set_previous_frame(gpu::FrameParams& f, const Scene& scene, const Scene& previous) {
  const CameraBasis basis = camera_basis(previous.camera);
  // ENU and planet axes coincide, so the ENU difference is the planet-frame difference,
  // without the rounding of positions 6.4e6 m from the planet's centre.
  const glm::vec3 eye_offset = previous.camera.position_m - scene.camera.position_m;
  f.prev_camera_pos_m =
      glm::vec4(eye_offset, std::tan(glm::radians(vertical_fov_deg(previous)) * 0.5f));
  f.prev_camera_forward =
      glm::vec4(basis.forward, float(previous.output.width) / float(previous.output.height));
  f.prev_camera_right = glm::vec4(basis.right, 0.0f);
  f.prev_camera_up = glm::vec4(basis.up, 0.0f);
  const glm::vec2 wind_delta =
      scene.clouds.wind_mps * scene.time_s - previous.clouds.wind_mps * previous.time_s;
  f.wind_offset_m.z = wind_delta.x;
  f.wind_offset_m.w = wind_delta.y;
}

void set_atmosphere(gpu::FrameParams& f, const Scene& scene) {
  const glsl::Atmosphere a = make_atmosphere(scene);
  f.radii_m.x = a.planet_radius_m;
  f.radii_m.y = a.top_radius_m;
  f.rayleigh = glm::vec4(a.rayleigh_sigma_s, a.rayleigh_height_m);
  f.mie = glm::vec4(a.mie_sigma_s, a.mie_sigma_t, a.mie_height_m, a.mie_g);
  f.ozone = glm::vec4(a.ozone_sigma_a, a.ozone_center_m);
  f.sky_model = glm::vec4(a.ozone_half_width_m, scene.atmosphere.ground_albedo,
                          float(static_cast<int>(scene.atmosphere.model)), scene.atmosphere.turbidity);
  f.sky_options = glm::ivec4(
      scene.atmosphere.angular_multiple_scattering ? glsl::MS_ANGULAR : glsl::MS_ISOTROPIC, 0, 0, 0);
}

std::vector<VolumetricLayer> volumetric_layers(const Scene& scene) {
  const CloudParams& c = scene.clouds;
  std::vector<VolumetricLayer> layers;
  const glm::vec2 low_m(c.bottom_altitude_m, c.top_altitude_m);
  // A storm's cells fill the whole shell.
  layers.push_back(
      {low_m,
       c.precipitation > 0.0f ? low_m : weather::clouds_in_shell_m(c.type, c.coverage, low_m),
       c.coverage, c.density, c.type, c.wind_mps, 0});
  const HighCloudParams& h = scene.high_clouds;
  const glm::vec2 high_m(h.bottom_altitude_m, h.top_altitude_m);
  if (h.coverage > 0.0f)
    layers.push_back({high_m, weather::clouds_in_shell_m(h.type, h.coverage, high_m), h.coverage,
                      h.density, h.type, h.wind_mps, 1});
  for (size_t i = 0; i < scene.cloud_layers.size() && layers.size() < size_t(kMaxCloudLayers);
       ++i) {
    const CloudLayerParams& l = scene.cloud_layers[i];
    if (!(l.oktas > 0.0f)) continue;
    layers.push_back(
        {weather::cloud_layer_shell_m(l),
         {l.base_m, l.top_m},
         weather::cloud_layer_coverage(l),
         l.density,
         weather::genus_type(weather::parse_genus(l.genus).value_or(weather::Genus::Stratocumulus)),
         l.wind_mps,
         int(layers.size())});
  }
  return layers;
}

glm::vec2 cloud_shell_m(const Scene& scene) {
  glm::vec2 shell = {scene.clouds.bottom_altitude_m, scene.clouds.top_altitude_m};
  for (const VolumetricLayer& l : volumetric_layers(scene))
    shell = {std::min(shell.x, l.shell_m.x), std::max(shell.y, l.shell_m.y)};
  return shell;
}

float cloud_relative_drift_m(const Scene& scene) {
  const CloudParams& c = scene.clouds;
  float speed_mps =
      std::max({glm::length(c.wind_shear_mps), glm::length(c.detail_drift_mps), c.flow_speed_mps});
  for (const VolumetricLayer& l : volumetric_layers(scene))
    speed_mps =
        std::max(speed_mps, glm::length(l.wind_mps - c.wind_mps) + glm::length(c.wind_shear_mps));
  return speed_mps * std::abs(scene.time_s);
}

namespace {

// The layers' GPU form. Each reads its own part of the weather map, so that its clouds are not
// stacked over the others'. Where two shells overlap (a shell holds more than its clouds: a
// cumulus' top fifth, an altocumulus' lowest 30%), each layer is drawn up to half way between
// its clouds and the other's. A slot without a layer lies beyond the atmosphere, where no
// sample reaches.
void set_cloud_layers(gpu::FrameParams& f, const Scene& scene, float planet_m, float top_m) {
  const std::vector<VolumetricLayer> layers = volumetric_layers(scene);
  std::vector<glm::vec2> band(layers.size());
  for (size_t i = 0; i < layers.size(); ++i) band[i] = layers[i].shell_m;
  for (size_t i = 0; i < layers.size(); ++i)
    for (size_t j = 0; j < layers.size(); ++j)
      if (i != j && layers[i].clouds_m.y <= layers[j].clouds_m.x) {  // i below j
        const float meet_m = 0.5f * (layers[i].clouds_m.y + layers[j].clouds_m.x);
        band[i].y = std::min(band[i].y, meet_m);
        band[j].x = std::max(band[j].x, meet_m);
      }
  const float off_m = 2.0f * (top_m - planet_m);
  for (int k = 0; k < gpu::CLOUD_LAYERS; ++k)
    f.cloud_layers[k] = {glm::vec4(planet_m + off_m, planet_m + off_m + 1.0f, 0.0f, 0.0f),
                         glm::vec4(0.0f), glm::vec4(0.0f), glm::vec4(planet_m + off_m)};
  const float precipitation = scene.clouds.precipitation;
  for (size_t i = 0; i < layers.size(); ++i) {
    const VolumetricLayer& l = layers[i];
    const float slot = float(l.slot);
    f.cloud_layers[l.slot] = {
        glm::vec4(planet_m + l.shell_m, slot * glm::vec2(0.37f, 0.61f)),
        glm::vec4(l.coverage, l.density, l.type, l.slot == 0 ? precipitation : 0.0f),
        glm::vec4(l.wind_mps * scene.time_s, l.wind_mps),
        glm::vec4(planet_m + band[i], l.slot == 0 ? 0.0f : 1.0f, 0.0f)};
  }
  f.cloud_layers[0].band_m.w = float(layers.size());  // slots 0 to size - 1
}

}  // namespace

float CloudOptics::max_sigma_t_per_m() const {
  return *std::max_element(std::begin(genus_sigma_t_per_m), std::end(genus_sigma_t_per_m));
}

CloudOptics cloud_optics(const Scene& scene) {
  CloudOptics o;
  const CloudParams& c = scene.clouds;
  o.droplets = c.optics == "droplets";
  if (!o.droplets) {
    std::fill(std::begin(o.genus_sigma_t_per_m), std::end(o.genus_sigma_t_per_m),
              c.extinction_per_m);
    o.voxel_sigma_t_per_m = c.extinction_per_m;
    o.albedo = c.albedo;
    return o;
  }
  const DropletParams& d = scene.droplets;
  const float water[5] = {d.stratus_water_g_m3, d.stratocumulus_water_g_m3,
                          d.altocumulus_water_g_m3, d.cumulus_water_g_m3,
                          d.cumulonimbus_water_g_m3};
  const float radius[5] = {d.stratus_radius_um, d.stratocumulus_radius_um, d.altocumulus_radius_um,
                           d.cumulus_radius_um, d.cumulonimbus_radius_um};
  o.radius_um = glsl::cloud_genus_blend(
      c.type, glm::vec4(radius[0], radius[1], radius[2], radius[3]), radius[4]);
  const glm::vec4 fit = glsl::mie_fit(2.0f * std::max(o.radius_um, 2.5f));
  const float omega = glsl::droplet_albedo(o.radius_um);
  o.peak_fraction = 1.0f - fit.w;
  const float kept = 1.0f - omega * o.peak_fraction;
  for (int i = 0; i < 5; ++i)
    o.genus_sigma_t_per_m[i] =
        glsl::droplet_extinction_per_m(water[i], radius[i]) * kept / kDropletCoreField;
  // A voxel cloud's field is its grid's density x its own (0.15 by default: its core holds 1.5
  // times the cumulus' water, as the seed's optics made it 0.15 /m).
  o.voxel_sigma_t_per_m = o.genus_sigma_t_per_m[3];
  o.albedo = omega * (1.0f - o.peak_fraction) / kept;
  o.mie = glm::vec4(fit.x, fit.y, fit.z, 1.0f);
  return o;
}

void set_cloud_field(gpu::FrameParams& f, const Scene& scene) {
  const CloudParams& c = scene.clouds;
  const float planet_m = scene.atmosphere.planet_radius_km * 1000.0f;
  const float top_m = (scene.atmosphere.planet_radius_km + scene.atmosphere.atmosphere_height_km) * 1000.0f;
  f.radii_m.x = planet_m;
  f.radii_m.y = top_m;
  const glm::vec2 shell_m = cloud_shell_m(scene);
  f.radii_m.z = planet_m + shell_m.x;
  f.radii_m.w = planet_m + shell_m.y;
  const CloudOptics optics = cloud_optics(scene);
  const float sigma_max = optics.max_sigma_t_per_m();
  const float* sigma = optics.genus_sigma_t_per_m;
  f.cloud_shape = glm::vec4(0.0f, 0.0f, sigma_max, optics.albedo);
  f.cloud_genus_sigma = glm::vec4(sigma[0], sigma[1], sigma[2], sigma[3]) / sigma_max;
  f.cloud_mie = optics.mie;
  const float g1 = optics.droplets
                       ? glsl::mie_mean_cosine(optics.mie)
                       : glm::mix(c.phase_g_backward, c.phase_g_forward, c.phase_lobe_weight);
  // The diffuse light is carried with the phase function's own mean cosine, except by the seed's
  // lighting with the seed's lobes, which keeps the seed's fixed droplet asymmetry.
  const bool own_g = optics.droplets || c.lighting != "seed";
  f.cloud_droplets = glm::vec4(sigma[4] / sigma_max, optics.droplets ? 1.0f : 0.0f, g1,
                               own_g ? g1 : glsl::CLOUD_DROPLET_G);
  set_cloud_layers(f, scene, planet_m, top_m);
  f.cloud_wind = glm::vec4(c.wind_shear_mps, c.wind_skew_s, glsl::shear_time_s(scene.time_s));
  f.cloud_detail_wind = glm::vec4(c.detail_drift_mps * scene.time_s, c.curl_distortion_m);
  // The flow map: the curl noise stretched over kFlowMapPeriodM.
  const double flow_phase = std::fmod(double(scene.time_s) / c.flow_cycle_s, 1.0);
  f.cloud_flow = glm::vec4(c.flow_speed_mps, c.flow_cycle_s,
                           float(flow_phase < 0.0 ? flow_phase + 1.0 : flow_phase),
                           1.0f / kFlowMapPeriodM);
  f.cloud_light = glm::vec4(c.attenuation, c.light_attenuation, c.powder_strength,
                            c.ambient_strength);
  f.cloud_phase = glm::vec4(c.phase_g_forward, c.phase_g_backward, c.phase_lobe_weight,
                            c.two_stream()              ? 1.0f
                            : c.lighting == "diffusion" ? 2.0f
                                                        : 0.0f);
  f.cloud_noise = glm::vec4(1.0f / c.base_noise_period_m, 1.0f / c.detail_noise_period_m,
                            1.0f / c.weather_period_m, c.detail_erosion);
  f.wind_offset_m = glm::vec4(c.wind_mps * scene.time_s, 0.0f, 0.0f);
}

gpu::FrameParams make_frame_params(const Scene& scene, int frame_index, const SkyLights& lights,
                                   const AtmosphereTables& tables, const ImageWindow* window) {
  const glsl::Atmosphere atmosphere = make_atmosphere(scene);
  const float planet_m = atmosphere.planet_radius_m;
  const CameraBasis basis = camera_basis(scene.camera);
  const KeyLight& key = lights.key;
  const glm::vec3 sun = key.direction;  // the key light's: the sun's, or at night the moon's
  const float w = float(scene.output.width), h = float(scene.output.height);
  const float full_w = window ? float(window->full_width) : w;
  const float full_h = window ? float(window->full_height) : h;
  // The whole image's field of view; a window spans its share of it (the same angle a pixel),
  // its centre shifted on the image plane to where its pixels lie in the whole image.
  const float full_tan_half = std::tan(glm::radians(vertical_fov_deg(scene.camera, full_w / full_h)) * 0.5f);
  const float aspect = w / h;
  const float tan_half_fov = full_tan_half * h / full_h;
  glm::vec2 shift(0.0f);
  if (window)
    shift = glm::vec2((2.0f * (float(window->x) + 0.5f * w) / full_w - 1.0f) * full_tan_half * full_w / full_h,
                      (1.0f - 2.0f * (float(window->y) + 0.5f * h) / full_h) * full_tan_half);

  gpu::FrameParams f{};
  f.camera_pos_m = glm::vec4(planet_from_enu(scene, scene.camera.position_m), tan_half_fov);
  f.camera_forward = glm::vec4(basis.forward, aspect);
  f.camera_right = glm::vec4(basis.right, shift.x);
  f.camera_up = glm::vec4(basis.up, shift.y);
  f.sun_dir = glm::vec4(sun, std::cos(glm::radians(scene.sun.disk_angular_radius_deg)));
  const glm::vec3 illuminance(key.illuminance);
  f.sun_illuminance = glm::vec4(illuminance, key.moon ? 1.0f : 0.0f);
  // The sun disk's colour. Compose hides the disk's pixels below the horizon; a disk whose
  // centre has set is not drawn at all (its last sliver is lost). None while the moon leads.
  const glm::vec3 eye(f.camera_pos_m);
  f.sun_transmittance = glm::vec4(
      key.moon ? glm::vec3(0.0f) : glsl::atmosphere_transmittance_to_top(atmosphere, eye, sun, 256),
      0.0f);
  set_moon(f, scene, atmosphere, lights);
  const std::optional<ConditionSet> conditions = set_conditions(f, scene, lights);
  set_stars(f, scene, lights.ephemeris, tan_half_fov);
  // The sky-view LUT's frame, shared by its pass and compose.
  const glsl::SkyViewFrame sky_view = glsl::sky_view_frame(eye, sun, planet_m);
  f.sky_view_up = glm::vec4(sky_view.up, sky_view.horizon_elevation_rad);
  f.sky_view_forward = glm::vec4(sky_view.forward, 0.0f);

  // Sunlight and sky light at the middle of the cloud layer above the camera: reddened by the
  // atmosphere when the sun is low.
  const glm::vec3 cloud_mid = cloud_layer_middle(scene, planet_m);
  f.sun_at_clouds = glm::vec4(
      illuminance * glsl::atmosphere_transmittance_to_top(atmosphere, cloud_mid, sun, 32), 0.0f);
  // Sky light from both of the sky's lights: what a horizontal surface at the cloud layer
  // receives from above (the sky) and from below (the lit ground and the air under the clouds),
  // cosine-weighted, and the sky light on the ground. An isotropic mean over all directions let
  // the horizon's twilight glow (at sun -12 deg 6,500 times the zenith's radiance, in a band a
  // few degrees high) light whole clouds red.
  const CpuSky sky{atmosphere, tables, scene.atmosphere.ground_albedo,
                   scene.atmosphere.angular_multiple_scattering ? glsl::MS_ANGULAR
                                                                : glsl::MS_ISOTROPIC};
  const glm::vec3 ground(scene.camera.position_m.x, scene.camera.position_m.y, planet_m + 1.0f);
  for (const KeyLight* light : {&key, &lights.second}) {
    if (light->illuminance <= 0.0f) continue;
    const glm::vec3 e(light->illuminance);
    const glm::vec3 d = light->direction;
    f.ambient_at_clouds += glm::vec4(e * hemisphere_radiance(sky, cloud_mid, d), 0.0f);
    f.ambient_below_clouds += glm::vec4(e * hemisphere_radiance(sky, cloud_mid, d, false), 0.0f);
    f.ground_sky_light += glm::vec4(e * hemisphere_radiance(sky, ground, d), 0.0f);
  }
  if (lights.second.illuminance > 0.0f)
    f.second_light =
        glm::vec4(lights.second.direction, lights.second.illuminance / key.illuminance);

  set_atmosphere(f, scene);
  if (scene.conditions.mode == ConditionsMode::Artist) {  // the keyframes light clouds and ground
    const ConditionSet& set = *conditions;
    // (On the old radiance scale: x kLegacyLuxPerUnit in cd/m^2.)
    f.sun_at_clouds =
        glm::vec4((key.moon ? set.moon_light_rgb : set.sun_light_rgb) * kLegacyLuxPerUnit, 0.0f);
    f.ambient_at_clouds = glm::vec4(set.ambient_rgb * kLegacyLuxPerUnit, 0.0f);
    f.ambient_below_clouds = f.ambient_at_clouds;
    f.ground_sky_light = f.ambient_at_clouds;
  }
  set_cloud_field(f, scene);
  const CirrusParams& ci = scene.cirrus;
  const float wind_speed = glm::length(ci.wind_mps);
  f.cirrus = glm::vec4(f.radii_m.x + ci.altitude_m, ci.coverage, ci.type, ci.optical_depth);
  f.cirrus_wind = glm::vec4(ci.wind_mps * scene.time_s,
                            wind_speed > 0.0f ? ci.wind_mps / wind_speed : glm::vec2(1.0f, 0.0f));
  set_previous_frame(f, scene, scene);
  f.size = glm::ivec4(scene.output.width, scene.output.height, frame_index,
                      int(scene.noise_seed & 0x7fffffff));
  f.steps = glm::ivec4(scene.quality.primary_steps, scene.quality.light_steps,
                       scene.atmosphere.view_samples, 0);
  // The display's exposure: output.ev100. A live display with auto exposure sets it each frame
  // from the device's meter (FrameStats::metered_luminance, exposure.h's live_ev100), as
  // nephele-view does.
  f.light_shafts = glm::vec4(float(light_shafts_method(scene.quality.light_shafts)),
                             float(scene.quality.screen_shaft_samples),
                             scene.quality.screen_shaft_strength, scene.quality.screen_shaft_decay);
  f.output_image =
      glm::vec4(float(exposure_from_ev100(scene.output.ev100)), float(int(scene.output.tonemap)),
                window ? float(window->x) : 0.0f, window ? float(window->y) : 0.0f);
  return f;
}

bool sky_view_reusable(const SkyViewKey& built, const SkyViewKey& now) {
  // The atmosphere and the samples exactly; the rest within tolerances. The LUT holds radiance
  // per unit key-light illuminance, so the key light's illuminance may change (the moon's does
  // with its phase and distance) as long as the lights' ratios stay.
  SkyViewKey same = now;
  same.camera_pos_m = built.camera_pos_m;
  same.sun_dir = built.sun_dir;
  same.sun_illuminance = built.sun_illuminance;
  same.ground_sky_light = built.ground_sky_light;
  same.second_light = built.second_light;
  if (!(same == built)) return false;
  // A sun moving with the clock (0.004 deg/s) is followed in steps of kSkyViewReuseSunDeg, the
  // second light likewise, its share of the key light's within 1%.
  const float cos_reuse = std::cos(glm::radians(kSkyViewReuseSunDeg));
  if (glm::dot(now.sun_dir, built.sun_dir) < cos_reuse) return false;
  const glm::vec4 second = now.second_light, second_built = built.second_light;
  if ((second.w > 0.0f) != (second_built.w > 0.0f)) return false;
  if (second.w > 0.0f && (std::abs(second.w - second_built.w) > 0.01f * second_built.w ||
                          glm::dot(glm::vec3(second), glm::vec3(second_built)) < cos_reuse))
    return false;
  // The sky light on the ground below the camera (per unit key light) within 2%: it lights only
  // the ground's shadowed part, and in twilight it changes by 0.2% a second.
  const glm::vec3 ground = now.ground_sky_light / glm::max(now.sun_illuminance, glm::vec3(1e-30f));
  const glm::vec3 ground_built =
      built.ground_sky_light / glm::max(built.sun_illuminance, glm::vec3(1e-30f));
  if (glm::any(glm::greaterThan(glm::abs(ground - ground_built), 0.02f * glm::abs(ground_built))))
    return false;
  // The camera: in double, positions are 6.4e6 m from the planet's centre.
  const glm::dvec3 from(built.camera_pos_m), to(now.camera_pos_m);
  const double altitude_m = std::max(glm::length(from) - double(built.radii_m.x), 0.0);
  const double climb_m = std::abs(glm::length(to) - glm::length(from));
  return glm::distance(from, to) <= kSkyViewReuseM &&
         climb_m <= std::min(0.01 * altitude_m, double(kSkyViewReuseM));
}

SkyViewKey sky_view_key(const gpu::FrameParams& f) {
  return {.camera_pos_m = glm::vec3(f.camera_pos_m),
          .sun_dir = glm::vec3(f.sun_dir),
          .sun_illuminance = glm::vec3(f.sun_illuminance),
          .ground_sky_light = glm::vec3(f.ground_sky_light),
          .second_light = f.second_light,
          .rayleigh = f.rayleigh,
          .mie = f.mie,
          .ozone = f.ozone,
          .sky_model = f.sky_model,
          .sky_options = f.sky_options,
          .radii_m = glm::vec2(f.radii_m),
          .samples = f.steps.z};
}

std::string history_key(Scene scene) {
  scene.camera = CameraParams{};
  scene.sun = SunParams{};
  scene.time_s = 0.0f;
  scene.output.ev100 = 0.0f;  // the exposure does not touch the HDR image
  scene.output.auto_exposure = false;
  return scene_to_toml(scene);
}

}  // namespace nephele

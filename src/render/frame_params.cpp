#include "render/frame_params.h"
#include "nephele/sky.h"

#include <cmath>

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
  return a;
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

namespace {

constexpr int kSkyDirections = 64;

// Mean, over kSkyDirections directions dir_of(i, golden angle), of the sky radiance seen from
// `pos` per unit solar illuminance (a ground hit counts with its sun-lit part).
template <typename DirOf>
glm::vec3 mean_sky(const glsl::Atmosphere& atmosphere, const glm::vec3& pos, const glm::vec3& sun,
                   DirOf dir_of) {
  const float golden = glsl::PI * (3.0f - std::sqrt(5.0f));
  glm::vec3 sum(0.0f);
  for (int i = 0; i < kSkyDirections; ++i) {
    const glsl::SkySample sky = glsl::sky_single_scattering(atmosphere, pos, dir_of(i, golden),
                                                            sun, 8, 4, 0.1f, glm::vec3(0.0f));
    sum += sky.radiance + sky.ground_sun;
  }
  return sum / float(kSkyDirections);
}

// Mean sky radiance over all directions at `pos` per unit solar illuminance: the light an
// isotropic scatterer receives from the sky (Fibonacci sphere).
glm::vec3 mean_sky_radiance(const glsl::Atmosphere& atmosphere, const glm::vec3& pos,
                            const glm::vec3& sun) {
  return mean_sky(atmosphere, pos, sun, [](int i, float golden) {
    float z = 1.0f - 2.0f * (float(i) + 0.5f) / float(kSkyDirections);
    float r = std::sqrt(1.0f - z * z);
    return glm::vec3(r * std::cos(golden * float(i)), r * std::sin(golden * float(i)), z);
  });
}

// Sky irradiance on a horizontal surface at `pos` divided by pi, per unit solar illuminance:
// the cosine-weighted mean sky radiance over the upper hemisphere.
glm::vec3 sky_irradiance_over_pi(const glsl::Atmosphere& atmosphere, const glm::vec3& pos,
                                 const glm::vec3& sun) {
  const glm::vec3 up = glm::normalize(pos);
  const glm::vec3 east = glm::normalize(glm::cross(glm::vec3(0, 1, 0), up));
  const glm::vec3 north = glm::cross(up, east);
  return mean_sky(atmosphere, pos, sun, [&](int i, float golden) {
    // Cosine-weighted: sin^2 of the angle from the zenith uniform in [0, 1].
    float s2 = (float(i) + 0.5f) / float(kSkyDirections);
    float sin_t = std::sqrt(s2), cos_t = std::sqrt(1.0f - s2);
    return sin_t * (std::cos(golden * float(i)) * east + std::sin(golden * float(i)) * north) +
           cos_t * up;
  });
}

}  // namespace

void set_previous_frame(gpu::FrameParams& f, const Scene& scene, const Scene& previous) {
  const CameraBasis basis = camera_basis(previous.camera.view_dir);
  // ENU and planet axes coincide, so the ENU difference is the planet-frame difference,
  // without the rounding of positions 6.4e6 m from the planet's centre.
  const glm::vec3 eye_offset = previous.camera.position_m - scene.camera.position_m;
  f.prev_camera_pos_m =
      glm::vec4(eye_offset, std::tan(glm::radians(previous.camera.fov_deg) * 0.5f));
  f.prev_camera_forward =
      glm::vec4(basis.forward, float(previous.output.width) / float(previous.output.height));
  f.prev_camera_right = glm::vec4(basis.right, 0.0f);
  f.prev_camera_up = glm::vec4(basis.up, 0.0f);
  const glm::vec2 wind_delta =
      scene.clouds.wind_mps * scene.time_s - previous.clouds.wind_mps * previous.time_s;
  f.wind_offset_m.z = wind_delta.x;
  f.wind_offset_m.w = wind_delta.y;
}

gpu::FrameParams make_frame_params(const Scene& scene, int frame_index) {
  const CloudParams& c = scene.clouds;
  const glsl::Atmosphere atmosphere = make_atmosphere(scene);
  const float planet_m = atmosphere.planet_radius_m;
  const CameraBasis basis = camera_basis(scene.camera.view_dir);
  const glm::vec3 sun = scene_sun_direction(scene);
  const float aspect = float(scene.output.width) / float(scene.output.height);
  const float tan_half_fov = std::tan(glm::radians(scene.camera.fov_deg) * 0.5f);

  gpu::FrameParams f{};
  f.camera_pos_m = glm::vec4(planet_from_enu(scene, scene.camera.position_m), tan_half_fov);
  f.camera_forward = glm::vec4(basis.forward, aspect);
  f.camera_right = glm::vec4(basis.right, 0.0f);
  f.camera_up = glm::vec4(basis.up, 0.0f);
  f.sun_dir = glm::vec4(sun, std::cos(glm::radians(scene.sun.disk_angular_radius_deg)));
  const glm::vec3 illuminance(scene.sun.illuminance);
  f.sun_illuminance = glm::vec4(illuminance, 0.0f);
  // The sun disk's colour. Compose hides the disk's pixels below the horizon; a disk whose
  // centre has set is not drawn at all (its last sliver is lost).
  const glm::vec3 eye(f.camera_pos_m);
  f.sun_transmittance =
      glm::vec4(glsl::atmosphere_transmittance_to_top(atmosphere, eye, sun, 256), 0.0f);
  // The sky-view LUT's frame, shared by its pass and compose.
  const glsl::SkyViewFrame sky_view = glsl::sky_view_frame(eye, sun, planet_m);
  f.sky_view_up = glm::vec4(sky_view.up, sky_view.horizon_elevation_rad);
  f.sky_view_forward = glm::vec4(sky_view.forward, 0.0f);

  // Sunlight and sky light at the middle of the cloud layer above the camera: reddened by the
  // atmosphere when the sun is low.
  const glm::vec3 cloud_mid(scene.camera.position_m.x, scene.camera.position_m.y,
                            planet_m + 0.5f * (c.bottom_altitude_m + c.top_altitude_m));
  f.sun_at_clouds = glm::vec4(
      illuminance * glsl::atmosphere_transmittance_to_top(atmosphere, cloud_mid, sun, 32), 0.0f);
  f.ambient_at_clouds =
      glm::vec4(illuminance * mean_sky_radiance(atmosphere, cloud_mid, sun), 0.0f);
  const glm::vec3 ground(scene.camera.position_m.x, scene.camera.position_m.y, planet_m + 1.0f);
  f.ground_sky_light =
      glm::vec4(illuminance * sky_irradiance_over_pi(atmosphere, ground, sun), 0.0f);

  f.radii_m = glm::vec4(planet_m, atmosphere.top_radius_m, planet_m + c.bottom_altitude_m,
                        planet_m + c.top_altitude_m);
  f.rayleigh = glm::vec4(atmosphere.rayleigh_sigma_s, atmosphere.rayleigh_height_m);
  f.mie = glm::vec4(atmosphere.mie_sigma_s, atmosphere.mie_sigma_t, atmosphere.mie_height_m,
                    atmosphere.mie_g);
  f.cloud_shape = glm::vec4(c.coverage, c.density, c.extinction_per_m, c.albedo);
  f.cloud_light = glm::vec4(c.attenuation, c.light_attenuation, c.powder_strength,
                            c.ambient_strength);
  f.cloud_phase = glm::vec4(c.phase_g_forward, c.phase_g_backward, c.phase_lobe_weight, 0.0f);
  f.cloud_noise = glm::vec4(1.0f / c.base_noise_period_m, 1.0f / c.detail_noise_period_m,
                            1.0f / c.weather_period_m, c.detail_erosion);
  f.wind_offset_m = glm::vec4(c.wind_mps * scene.time_s, 0.0f, 0.0f);
  set_previous_frame(f, scene, scene);
  f.size = glm::ivec4(scene.output.width, scene.output.height, frame_index,
                      int(scene.noise_seed & 0x7fffffff));
  f.steps = glm::ivec4(scene.quality.primary_steps, scene.quality.light_steps,
                       scene.atmosphere.view_samples, scene.atmosphere.light_samples);
  return f;
}

bool sky_view_reusable(const SkyViewKey& built, const SkyViewKey& now) {
  // The sky light on the ground below the camera changes with it too, by far less.
  SkyViewKey moved = now;
  moved.camera_pos_m = built.camera_pos_m;
  moved.ground_sky_light = built.ground_sky_light;
  if (!(moved == built)) return false;
  const glm::vec3 light_change = glm::abs(now.ground_sky_light - built.ground_sky_light);
  if (glm::any(glm::greaterThan(light_change, 1e-3f * glm::abs(built.ground_sky_light))))
    return false;
  // In double: positions are 6.4e6 m from the planet's centre.
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
          .rayleigh = f.rayleigh,
          .mie = f.mie,
          .radii_m = glm::vec2(f.radii_m),
          .samples = glm::ivec2(f.steps.z, f.steps.w)};
}

}  // namespace nephele

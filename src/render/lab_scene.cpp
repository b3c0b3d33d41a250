#include "render/lab_scene.h"

#include "nephele/scene_io.h"

namespace nephele {

VoxelCloudParams lab_voxel_cloud(const Scene& scene) {
  VoxelCloudParams cloud;
  cloud.file = scene.lab.grid;
  cloud.density = 1.0f;
  cloud.follow_wind = false;
  cloud.wind_mps = glm::vec2(0.0f);
  cloud.resolution = voxel::kMaxGridDim;
  return cloud;
}

Scene lab_fast_scene(const Scene& scene, const voxel::VoxelGrid& grid) {
  Scene s = scene;
  AtmosphereParams& a = s.atmosphere;
  a.model = SkyModel::Hillaire;
  a.rayleigh_scattering_per_m = glm::vec3(0.0f);
  a.mie_scattering_per_m = 0.0f;
  a.mie_extinction_per_m = 0.0f;
  a.ozone_absorption_per_m = glm::vec3(0.0f);
  a.ground_albedo = 0.0f;
  s.clouds.coverage = 0.0f;
  s.clouds.precipitation = 0.0f;
  s.high_clouds.coverage = 0.0f;
  s.cirrus.coverage = 0.0f;
  s.conditions.mode = ConditionsMode::Off;
  s.time.clear();  // no moon, no stars
  s.sun.from_time = false;
  s.sun.direction = sun_direction_from_angles(scene.lab.sun_elevation_deg, scene.lab.sun_azimuth_deg);
  s.sun.illuminance_lux = scene.lab.sun_irradiance;
  s.sun.disk_angular_radius_deg = 0.0f;  // a distant light, as the reference's: no disk in view
  // The grid's densities as the file has them: the import scales them into [0, 1].
  // The lab's own medium (sigma_t, albedo, one lobe), as the seed's optics carry it.
  s.clouds.optics = "seed";
  s.clouds.extinction_per_m = grid.file_density_scale * scene.lab.sigma_t_per_m;
  s.clouds.attenuation = 1.0f;
  s.clouds.light_attenuation = 1.0f;
  s.clouds.albedo = scene.lab.albedo;
  // One Henyey-Greenstein lobe.
  if (scene.lab.g >= 0.0f) {
    s.clouds.phase_g_forward = scene.lab.g;
    s.clouds.phase_lobe_weight = 1.0f;
  } else {
    s.clouds.phase_g_backward = scene.lab.g;
    s.clouds.phase_lobe_weight = 0.0f;
  }
  VoxelCloudParams cloud = lab_voxel_cloud(scene);
  cloud.position_m = grid.file_anchor_m + glm::vec3(0.0f, 0.0f, kLabAltitudeM);
  s.voxel_clouds = {cloud};
  s.camera.position_m.z += kLabAltitudeM;
  // The (empty) noise layer spans the grid's height: the clouds pass marches the shell from the
  // lowest layer's bottom to the highest top, with steps in proportion to its thickness.
  s.clouds.bottom_altitude_m = cloud.position_m.z + grid.origin_m.z;
  s.clouds.top_altitude_m = s.clouds.bottom_altitude_m + grid.extent_m().z;
  return s;
}

}  // namespace nephele

// nephele — the cloud field queried from the host's CPU: density, "inside a cloud?" and optical
// depth at any point and time, for avionics, sensors and gameplay. Nothing waits for the device:
// the queries run the shaders' own density function (shaders/noise_density_inc.glsl, compiled
// as C++) on copies of the noise textures, read back once when the query is made.
//
//   nephele::CloudQuery clouds = renderer.cloud_query(scene);   // Renderer or FrameRenderer
//   if (clouds.inside_cloud(aircraft_enu_m, scene.time_s)) ...
//   float t = std::exp(-clouds.optical_depth(sensor_m, target_m, scene.time_s));
//
// The noise clouds only: the layers of [clouds] and [high_clouds] (voxel clouds, particles,
// cirrus and the classical models are not in the field). Positions are ENU metres (x east,
// y north, z up from the ground at the scene's origin), as scene.camera.position_m; times are
// scene times (scene.time_s): the wind, the flow and the evolving weather move the clouds.
#pragma once

#include <glm/vec3.hpp>
#include <memory>

#include "nephele/scene.h"

namespace nephele {

class CloudQuery {
 public:
  // The density field (dimensionless, >= 0) at `enu_m`: what the clouds pass marches, at the
  // detail noise's finest level. InputError for a position or time that is not finite.
  float density(const glm::vec3& enu_m, float time_s) const;
  // The extinction coefficient there (1/m): density x clouds.extinction_per_m.
  float sigma_t_per_m(const glm::vec3& enu_m, float time_s) const;
  bool inside_cloud(const glm::vec3& enu_m, float time_s) const {
    return density(enu_m, time_s) > 0.0f;
  }
  // The optical depth (sigma_t integrated, dimensionless) along the segment from `from_m` to
  // `to_m`: midpoint samples at most `step_m` apart ([0.1, 1e4] m); exp(-depth) is the direct
  // light's transmittance through the clouds (the air's not included).
  float optical_depth(const glm::vec3& from_m, const glm::vec3& to_m, float time_s,
                      float step_m = 10.0f) const;

  const Scene& scene() const;

  struct Data;  // the scene and the textures (render/cloud_query.cpp)
  explicit CloudQuery(std::shared_ptr<const Data> data);

 private:
  std::shared_ptr<const Data> data_;
};

}  // namespace nephele

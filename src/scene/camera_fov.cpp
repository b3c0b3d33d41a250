// nephele — the camera's field of view from its three forms (scene.h, CameraParams).
#include <cmath>

#include <glm/trigonometric.hpp>

#include "nephele/scene.h"

namespace nephele {

float horizontal_fov_from_focal_deg(float focal_length_mm, float sensor_width_mm) {
  return float(2.0 * std::atan(double(sensor_width_mm) / (2.0 * double(focal_length_mm))) *
               180.0 / M_PI);
}

float vertical_fov_deg(const CameraParams& camera, float aspect) {
  double horizontal_deg = 0.0;
  if (camera.focal_length_mm > 0.0f)
    horizontal_deg = horizontal_fov_from_focal_deg(camera.focal_length_mm, camera.sensor_width_mm);
  else if (camera.horizontal_fov_deg > 0.0f)
    horizontal_deg = camera.horizontal_fov_deg;
  else
    return camera.fov_deg;
  const double half_rad = horizontal_deg * M_PI / 360.0;
  return float(2.0 * std::atan(std::tan(half_rad) / double(aspect)) * 180.0 / M_PI);
}

float vertical_fov_deg(const Scene& scene) {
  return vertical_fov_deg(scene.camera, float(scene.output.width) / float(scene.output.height));
}

}  // namespace nephele

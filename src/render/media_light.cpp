#include "render/media_light.h"

#include <algorithm>
#include <glm/geometric.hpp>

#include "render/glsl.h"

namespace nephele {

MediumLight medium_light(const gpu::FrameParams& params) {
  const glm::vec3 up = glm::normalize(glm::vec3(params.camera_pos_m));
  const float sin_elevation = glm::dot(glm::vec3(params.sun_dir), up);
  const glm::vec3 per_unit = 1.0f / glm::max(glm::vec3(params.sun_illuminance), glm::vec3(1e-20f));
  const glm::vec3 sun = glm::vec3(params.sun_transmittance);
  const glm::vec3 sky = glm::vec3(params.ground_sky_light) * per_unit;
  const float albedo = params.sky_model.y;
  const glm::vec3 ground = albedo * (sky + sun * std::max(sin_elevation, 0.0f) / glsl::PI);
  return {glm::vec4(sun, sin_elevation), 0.5f * (sky + ground)};
}

}  // namespace nephele

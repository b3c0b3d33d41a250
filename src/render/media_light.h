// nephele — the light that the media under the clouds (the ground fog, rain and snow) are lit
// by, as their uniform blocks hold it (common/slab_light_inc.glsl): per unit of the key light's
// illuminance, from the frame's parameters.
#pragma once

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include "render/gpu_params.h"

namespace nephele {

struct MediumLight {
  // rgb the sunlight at the medium's top (its beam through the atmosphere); w the sine of the
  // sun's elevation at the camera.
  glm::vec4 sun{0.0f};
  // The sky's light from above (ground_sky_light: the sky's irradiance / pi) and the ground's
  // from below (its albedo times the sky's and the sun's irradiance / pi), averaged as an even
  // field.
  glm::vec3 sky{0.0f};
};

MediumLight medium_light(const gpu::FrameParams& params);

}  // namespace nephele

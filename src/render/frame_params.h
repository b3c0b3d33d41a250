// Scene (user units, ENU) -> FrameParams (GPU units, planet frame), plus the per-frame
// lighting computed on the CPU with the shaders' own functions (render/glsl.h).
#pragma once

#include "nephele/scene.h"
#include "render/glsl.h"
#include "render/gpu_params.h"

namespace nephele {

// The planet-frame position (m) of an ENU position (m): the ENU origin is on the ground at
// (0, 0, planet radius); ENU axes are the planet frame's axes there.
glm::vec3 planet_from_enu(const Scene& scene, const glm::vec3& enu_m);

glsl::Atmosphere make_atmosphere(const Scene& scene);

// Camera basis: forward, right, up (unit vectors, up is the image's up).
struct CameraBasis {
  glm::vec3 forward, right, up;
};
CameraBasis camera_basis(const glm::vec3& view_dir);

gpu::FrameParams make_frame_params(const Scene& scene, int frame_index);

// Fills the previous frame's camera and the wind's displacement since then (for reprojection).
void set_previous_frame(gpu::FrameParams& params, const Scene& scene, const Scene& previous);

}  // namespace nephele

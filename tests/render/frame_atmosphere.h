// The atmosphere of a FrameParams as the shaders read it (frame_atmosphere_inc.glsl), for tests
// that evaluate the shaders' functions on the CPU. (glsl:: types have internal linkage, so a test
// cannot take make_atmosphere's result from the library.)
#pragma once

#include "render/glsl.h"
#include "render/gpu_params.h"

inline nephele::glsl::Atmosphere frame_atmosphere(const nephele::gpu::FrameParams& f) {
  nephele::glsl::Atmosphere a;
  a.planet_radius_m = f.radii_m.x;
  a.top_radius_m = f.radii_m.y;
  a.rayleigh_sigma_s = glm::vec3(f.rayleigh);
  a.rayleigh_height_m = f.rayleigh.w;
  a.mie_sigma_s = f.mie.x;
  a.mie_sigma_t = f.mie.y;
  a.mie_height_m = f.mie.z;
  a.mie_g = f.mie.w;
  a.ozone_sigma_a = glm::vec3(f.ozone);
  a.ozone_center_m = f.ozone.w;
  a.ozone_half_width_m = f.sky_model.x;
  return a;
}

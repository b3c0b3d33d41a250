// The pure GLSL functions of shaders/common/*_inc.glsl compiled as C++ (Bruneton's trick):
// the CPU side computes per-frame lighting with them and the tests check them against closed
// forms, so the shaders and their tests share one definition.
#pragma once

#include <glm/glm.hpp>

// The functions get internal linkage (unnamed namespace): each file that includes this one
// has its own copy, as a shader does.
// Each includer uses only some of them.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace nephele::glsl {
using namespace glm;
namespace {
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/noise_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/sky_view_inc.glsl"
#include "common/clouds_inc.glsl"
#include "common/light_volume_inc.glsl"
}  // namespace
}  // namespace nephele::glsl
#pragma GCC diagnostic pop

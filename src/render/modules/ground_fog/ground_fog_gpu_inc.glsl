// The ground fog's uniform block (GroundFogModule, set 1 "GroundFogBlock"): one definition,
// included by its medium's GLSL and by C++ (ground_fog.cpp), as params_inc.glsl is.
#ifndef NEPHELE_GROUND_FOG_GPU_INC
#define NEPHELE_GROUND_FOG_GPU_INC

#ifdef __cplusplus
namespace nephele::gpu {
using glm::vec4;
#endif

struct GroundFogGpu {
  vec4 layer;  // x base, y top (m above the ground), z the top's softness (m), w sigma_t (1/m);
               // w 0: no fog
  vec4 sun;    // rgb the sunlight at the fog's top per unit of the key light's illuminance
               // (through the atmosphere), w the sine of the sun's elevation
  vec4 sky;    // rgb the light of the sky and the ground around, scattered as from an even
               // field, per unit of the key light's illuminance; w the droplets' phase g
  vec4 keyframes;          // the time-of-day keyframes' fog: rgb its colour per unit of the key
                           // light's illuminance; w 1 when on, 0 off
  vec4 keyframes_range_m;  // x the distance it begins at, y where it is whole (m)
};

#ifdef __cplusplus
}  // namespace nephele::gpu
#endif

#endif

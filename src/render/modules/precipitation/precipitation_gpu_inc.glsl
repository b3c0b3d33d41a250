// The precipitation's uniform block (PrecipitationModule, set 1 "PrecipitationBlock"): one
// definition, included by its medium's GLSL and by C++ (precipitation.cpp).
#ifndef NEPHELE_PRECIPITATION_GPU_INC
#define NEPHELE_PRECIPITATION_GPU_INC

#ifdef __cplusplus
namespace nephele::gpu {
using glm::vec4;
#endif

// The particles near the camera are drawn in a cube of this many cells a side around the
// camera's (precipitation_particles.vert), out to 0.45 of the side.
const int PRECIPITATION_NEAR_SIDE = 30;

struct PrecipitationGpu {
  vec4 fall;  // x the lowest height it reaches, y the cloud base it falls from (m above the
              // ground), z sigma_t where it is densest (1/m; 0: none), w the particles' phase g
  vec4 sun;   // rgb the sunlight at the top per unit of the key light's illuminance, w the sine
              // of the sun's elevation (media_light.h)
  vec4 sky;   // rgb the sky's and the ground's light as an even field, per unit of the key
              // light's illuminance; w 1 shafts under the precipitating clouds, 0 an even curtain
  vec4 drift;  // xy how far the wind carries it sideways per metre of fall (east, north:
               // precipitation_drift_slope); zw unused
  // The particles near the camera (precipitation_particles_inc.glsl), each in a cell of a grid that
  // falls with them: one drawn stands for particles.x of them.
  vec4 near;       // xyz the camera in the falling grid (m, planet axes, wrapped to its period),
                   // w the cells' size (m); 0: none drawn
  vec4 streak;     // xyz how far a particle moves over the shutter (m, planet axes), w its
                   // diameter (m)
  vec4 particles;  // x how many each stands for, y the range they are drawn to (m), z the
                   // flutter's amplitude (m; snow), w its phase (rad, from the time)
};

#ifdef __cplusplus
}  // namespace nephele::gpu
#endif

#endif

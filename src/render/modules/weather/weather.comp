#version 450
// Pass 1c: procedural weather map, evolving with time (seed 000, 2.2.2; channels as in seed
// 002 and Schneider 2015): the states of the weather at steps of its time scale
// (FrameParams::weather_build, render/modules/weather/weather.h), a band of rows of each,
// 2D RGBA, tiles: R coverage, G storm cells (where precipitation doubles), B cloud type around
// the layer's (B - 0.5 is added to clouds.type), A density.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/noise_inc.glsl"
#include "common/weather_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 size = imageSize(weather_states).xy;
  ivec2 id = ivec2(gl_GlobalInvocationID.x, frame.weather_build.z + int(gl_GlobalInvocationID.y));
  int step = frame.weather_build.x + int(gl_GlobalInvocationID.z);
  if (id.x >= size.x || id.y >= size.y || int(gl_GlobalInvocationID.y) >= frame.weather_build.w ||
      int(gl_GlobalInvocationID.z) >= frame.weather_build.y)
    return;
  // The step's time in units of the weather's time scale, as doubles would give it (whole
  // steps and the remainder, also for a negative step: floor_div).
  int whole = floor_div(step, WEATHER_STEPS);
  float time = float(whole) + float(step - whole * WEATHER_STEPS) / float(WEATHER_STEPS);
  // The map evolves along the noise's third axis: the coverage field (period 6) moves one
  // lattice cell per weather_evolution_s. That axis wraps like the others, so the weather
  // repeats after 6 weather_evolution_s (6 hours at the default hour).
  vec3 uv = vec3((vec2(id) + 0.5f) / vec2(size), time / 6.0f);
  vec4 state = weather_state(uv, uint(frame.size.w));
  imageStore(weather_states, ivec3(id, step - 3 * floor_div(step, 3)), state);
}

#version 450
// Pass: the weather map the clouds read, blended between the two states of the evolving weather
// around the scene's time (FrameParams::weather_blend, render/modules/weather/weather.h), so the map
// changes smoothly from frame to frame.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 id = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(id, imageSize(weather_map_out)))) return;
  vec4 a = imageLoad(weather_states, ivec3(id, int(frame.weather_blend.y)));
  vec4 b = imageLoad(weather_states, ivec3(id, int(frame.weather_blend.z)));
  imageStore(weather_map_out, id, mix(a, b, frame.weather_blend.x));
}

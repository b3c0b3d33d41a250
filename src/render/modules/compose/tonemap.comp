#version 450
// Pass: the display image. The linear HDR image times the exposure, through the scene's tone
// map (frame.output_image.y: output.tonemap) and sRGB-encoded into 8 bits, exactly as the PNG
// writer encodes a file (common/tonemap_inc.glsl).
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/tonemap_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (p.x >= frame.size.x || p.y >= frame.size.y) return;
  vec3 c = imageLoad(color_rw, p).rgb * frame.output_image.x;
  imageStore(display_out, p, vec4(display_rgb(int(frame.output_image.y), c), 1.0f));
}

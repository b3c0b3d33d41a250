#version 450
// The terrain as a mesh (terrain.method = "raster", seed 002's mesh; render/modules/terrain/terrain.h):
// two triangles per cell of the heightfield from gl_VertexIndex (no vertex buffer), each point
// on the ground sphere as terrain_inc.glsl has it (east and north its planet-frame x and y,
// |p| = R + height), projected by the frame's camera with reversed depth (near/z). The
// fragment shader writes each pixel's distance into the terrain's image; terrain.comp lights it.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

layout(location = 0) out vec3 from_eye_out;  // the point relative to the eye (m)

const ivec2 kCorners[6] = ivec2[6](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
const float kNearM = 1.0f;

layout(push_constant) uniform DrawBlock { DrawConstants draw; };  // info.x: cells a row

void main() {
  int cell = gl_VertexIndex / 6;
  ivec2 point = ivec2(cell % draw.info.x, cell / draw.info.x) + kCorners[gl_VertexIndex % 6];
  vec2 cells = vec2(frame.terrain_grid.xy - 1);
  float h = texelFetch(terrain_heights, point, 0).r;
  vec2 en = vec2(frame.terrain_rect.x + frame.terrain_rect.z * float(point.x) / cells.x,
                 frame.terrain_rect.y - frame.terrain_rect.w * float(point.y) / cells.y);
  vec3 eye = frame.camera_pos_m.xyz;
  float r = frame.radii_m.x, u = eye.z - r;  // the planet's radius, the eye's height
  float z = sqrt(max((r + h) * (r + h) - dot(en, en), 0.0f));
  // z - eye.z without the cancellation of two numbers near the planet's radius.
  float dz = ((h - u) * (2.0f * r + h + u) - dot(en, en)) / (z + eye.z);
  vec3 v = vec3(en - eye.xy, dz);
  from_eye_out = v;
  float depth = dot(v, frame.camera_forward.xyz);
  float tan_half = frame.camera_pos_m.w, aspect = frame.camera_forward.w;
  // The image plane's point less the window's shift (math_inc.glsl, camera_ray), times depth.
  vec2 shift = vec2(frame.camera_right.w, frame.camera_up.w) * depth;
  gl_Position = vec4((dot(v, frame.camera_right.xyz) - shift.x) / (tan_half * aspect),
                     -(dot(v, frame.camera_up.xyz) - shift.y) / tan_half, kNearM, depth);
}

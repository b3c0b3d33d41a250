#version 450
// The precipitation's particles near the camera (precipitation_particles_inc.glsl): a quad
// per cell of a cube of PRECIPITATION_NEAR_SIDE^3 cells around the camera's, around its
// particle's streak in the image, wide enough for the particle or a pixel and a pixel and a
// half more for the fragments' fall-off. Those out of range or behind the camera are dropped.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "render/modules/precipitation/precipitation_particles_inc.glsl"

layout(location = 0) flat out vec3 now_out;  // the particle at the shutter's close (m, from the eye)

const vec2 kCorners[6] = vec2[6](vec2(0.0f, -1.0f), vec2(1.0f, -1.0f), vec2(1.0f, 1.0f),
                                 vec2(0.0f, -1.0f), vec2(1.0f, 1.0f), vec2(0.0f, 1.0f));
const float kNearM = 0.2f;

layout(push_constant) uniform DrawBlock { DrawConstants draw; };

// Clip space (w = the distance along the view): as camera_pixel has x and y, image y down.
vec4 clip_of(vec3 p) {
  float z = dot(p, draw.forward.xyz);
  return vec4(dot(p, draw.right.xyz) / (draw.forward.w * draw.right.w),
              -dot(p, draw.up.xyz) / draw.forward.w, z - kNearM, z);
}

void main() {
  int i = gl_VertexIndex / 6;
  const int n = PRECIPITATION_NEAR_SIDE;
  ivec3 camera_cell = ivec3(floor(precipitation.near.xyz / precipitation.near.w));
  ivec3 cell = camera_cell + ivec3(i % n, (i / n) % n, i / (n * n)) - n / 2;
  // Cells out of range or behind the camera, before their hash.
  float cell_m = precipitation.near.w;
  vec3 centre_m = (vec3(cell) + 0.5f) * cell_m - precipitation.near.xyz;
  if (length(centre_m) > precipitation.particles.y + cell_m ||
      dot(centre_m, draw.forward.xyz) < -cell_m) {
    gl_Position = vec4(2.0f, 2.0f, 2.0f, 1.0f);  // outside: the quad is dropped
    return;
  }
  vec3 now = precipitation_particle_now(cell);
  vec3 then = now - precipitation.streak.xyz;
  now_out = now;
  vec4 a = clip_of(now), b = clip_of(then);
  if (a.z <= 0.0f || b.z <= 0.0f) {
    gl_Position = vec4(2.0f, 2.0f, 2.0f, 1.0f);  // too near: the quad is dropped
    return;
  }
  // In normalised device coordinates, pixels of 2 / size.
  vec2 size = vec2(frame.size.xy);
  vec2 pa = a.xy / a.w, pb = b.xy / b.w;
  vec2 along = (pb - pa) * 0.5f * size;
  float length_px = length(along);
  vec2 u = length_px > 1e-3f ? along / length_px : vec2(0.0f, 1.0f);
  vec2 v = vec2(-u.y, u.x);
  float pixel_rad = 2.0f * frame.camera_pos_m.w / size.y;
  float width_px = precipitation.streak.w / (pixel_rad * min(a.w, b.w)) + 1.5f;
  vec2 c = kCorners[gl_VertexIndex % 6];
  vec2 end_px = mix(-width_px * u, along + width_px * u, c.x);
  vec2 p = pa + (end_px + c.y * width_px * v) * 2.0f / size;
  float w = mix(a.w, b.w, c.x);
  gl_Position = vec4(p * w, (w - kNearM) * 0.5f, w);
}

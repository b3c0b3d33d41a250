#version 450
// Particle clouds (seed 003, 3.3.4; render/modules/particle_clouds/particle_clouds.h): each particle a
// camera-facing quad (two triangles from gl_VertexIndex, no vertex buffer), drawn back to front.
// Shading per particle, Harris and Lastra's eye pass: the sunlight the CPU lighting let through
// to it (I_k) scattered towards the eye by the phase function, plus the sky's light; the
// fragment shader multiplies by its opacity (premultiplied), and the blending composes
// E_k = S_k + T_k E_{k-1}. Beside it, the multiply scattered light as an isotropic term.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"

layout(location = 0) out vec2 corner_out;        // [-1, 1]^2 across the quad
layout(location = 1) flat out vec3 radiance_out;  // scattered radiance at opacity 1
layout(location = 2) flat out vec2 tile_out;      // x its texture's tile, y its distance (km)

const vec2 kCorners[6] = vec2[6](vec2(-1.0f, -1.0f), vec2(1.0f, -1.0f), vec2(1.0f, 1.0f),
                                 vec2(-1.0f, -1.0f), vec2(1.0f, 1.0f), vec2(-1.0f, 1.0f));
const float kNearM = 1.0f;  // closer than this a quad is clipped

layout(push_constant) uniform DrawBlock { DrawConstants draw; };

void main() {
  ParticleGpu p = particle_list[gl_VertexIndex / 6];
  vec2 c = kCorners[gl_VertexIndex % 6];
  // The draw's camera: the frame's, or an impostor's view of one cloud from the same eye.
  vec3 right = draw.right.xyz, up = draw.up.xyz, forward = draw.forward.xyz;
  vec3 corner = p.position_radius.xyz + (c.x * right + c.y * up) * p.position_radius.w;
  float z = dot(corner, forward);
  float tan_half = draw.forward.w, aspect = draw.right.w;
  // Clip space with w = z: x / w and y / w are camera_pixel's (image y down); depth z - near
  // clips what is nearer than kNearM (z in [0, w] only beyond it).
  gl_Position = vec4(dot(corner, right) / (tan_half * aspect), -dot(corner, up) / tan_half,
                     z - kNearM, z);
  corner_out = c;

  float distance_m = length(p.position_radius.xyz);
  vec3 view = p.position_radius.xyz / max(distance_m, 1e-3f);
  float mu = dot(view, frame.sun_dir.xyz);
  float phase = frame.particle_shading.z > 0.5f ? rayleigh_phase(mu)
                                                : henyey_greenstein(frame.particle_shading.y, mu);
  float light = p.shading.x;
  // The sky's light from all around (the mean of above and below), dimmed inside the cloud
  // half as much as the sunlight.
  vec3 ambient = 0.5f * (frame.ambient_at_clouds.rgb + frame.ambient_below_clouds.rgb);
  // Beyond the seed's model: the light scattered many times, isotropic (diffuse_strength).
  float diffuse = frame.particle_light.x / PI;
  radiance_out = frame.particle_shading.x * (frame.sun_at_clouds.rgb * light * (phase + diffuse) +
                                             ambient * (0.5f + 0.5f * light));
  tile_out = vec2(p.shading.y, distance_m * 1e-3f);
}

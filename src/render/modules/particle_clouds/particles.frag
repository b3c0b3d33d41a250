#version 450
// Particle clouds: a particle's texel, its opacity = the centre's opacity x particle_profile
// (the CPU lighting's splat) x its procedural texture's detail (mean 1); premultiplied.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/particle_inc.glsl"

layout(location = 0) in vec2 corner;
layout(location = 1) flat in vec3 radiance;
layout(location = 2) flat in vec2 tile;

layout(location = 0) out vec4 layer_out;  // LAYER_PARTICLES of the image layers
layout(location = 1) out vec4 depth_out;  // LAYER_PARTICLE_DEPTH

void main() {
  float q2 = dot(corner, corner);
  if (q2 >= 1.0f) discard;
  // The tile's texels, half a texel in from its edges so the filter never reads a neighbour.
  float inset = 1.0f - 1.0f / float(PARTICLE_TEXTURE_SIZE);
  vec2 uv = vec2((tile.x + 0.5f + 0.5f * corner.x * inset) / float(PARTICLE_TEXTURES),
                 0.5f + 0.5f * corner.y * inset);
  float detail = 2.0f * textureLod(particle_textures, uv, 0.0f).r;
  float alpha = min(frame.particle_shading.w * particle_profile(q2) * detail, 1.0f);
  layer_out = vec4(radiance * alpha, alpha);
  depth_out = vec4(tile.y * alpha, 0.0f, 0.0f, alpha);
}

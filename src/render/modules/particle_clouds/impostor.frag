#version 450
// Impostors: the quad's texel from its image in the atlas (premultiplied), mixed with the
// image it replaces while that fades out, so that an update never pops.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/impostor_inc.glsl"

layout(location = 0) in vec2 uv;
layout(location = 1) flat in int index;

layout(location = 0) out vec4 layer_out;  // LAYER_PARTICLES of the image layers
layout(location = 1) out vec4 depth_out;  // LAYER_PARTICLE_DEPTH

// The atlas method, fixed per pipeline: lavapipe runs both sides of a branch, and the tiles'
// lookup (a buffer read, divisions) tripled the direct method's cost per fragment.
layout(constant_id = 0) const int METHOD = IMPOSTOR_DIRECT;

vec4 image_texel(vec4 image, ImpostorGpu im) {
  vec2 atlas = vec2(textureSize(impostor_atlas, 0));
  vec2 texel;
  if (METHOD == IMPOSTOR_DIRECT) {
    texel = impostor_direct_texel(image, uv);
  } else {
    int across = int(image.y);
    vec2 size = vec2(image.z, image.w);
    ivec2 tile = impostor_tile_of(uv, size, im.info.y, across);
    int slot = impostor_tile_slots[int(image.x) + tile.y * across + tile.x];
    texel = impostor_tile_texel(uv, size, im.info.y, tile, slot, int(atlas.x) / im.info.y);
  }
  return textureLod(impostor_atlas, texel / atlas, 0.0f);
}

void main() {
  ImpostorGpu im = impostor_list[index];
  float fade = im.right.w;
  vec4 color = image_texel(im.image_new, im);
  // The image fading out, read only while there is one: a loop of at most one trip rather
  // than a branch, which lavapipe would run for every quad.
  for (int i = 0; i < (fade < 1.0f ? 1 : 0); ++i) color = mix(image_texel(im.image_old, im), color, fade);
  layer_out = color;
  depth_out = vec4(im.up.w * color.a, 0.0f, 0.0f, color.a);
}

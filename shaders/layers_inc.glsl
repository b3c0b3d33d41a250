// Reading the image layers compose blends over the clouds (params_inc.glsl's LAYER_*;
// render/image_layers.h). GLSL only; the includer includes bindings_inc.glsl.
#ifndef NEPHELE_LAYERS_INC
#define NEPHELE_LAYERS_INC

// Layer `layer` at image pixel `pixel`, clamped to the image.
vec4 layer_texel(int layer, ivec2 pixel) {
  ivec2 size = textureSize(layers, 0).xy;
  return texelFetch(layers, ivec3(clamp(pixel, ivec2(0), size - 1), layer), 0);
}

// Layer `layer` at image position uv ([0, 1]^2), filtered bilinearly, where the layer is drawn
// into the top-left `share` of the array's width and height (a lower resolution than the
// image's): as a texture of that part's size, clamped at its edges, would be.
vec4 layer_sample(int layer, vec2 uv, vec2 share) {
  vec2 half_texel = 0.5f / vec2(textureSize(layers, 0).xy);
  vec2 st = clamp(uv * share, half_texel, share - half_texel);
  return textureLod(layers, vec3(st, float(layer)), 0.0f);
}

#endif

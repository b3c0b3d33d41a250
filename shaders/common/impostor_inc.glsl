// Where an impostor's image is read in the atlas (render/modules/impostors/impostors.h), shared with the
// CPU (the tests check that bilinear filtering never reads a neighbour's texels).
#ifndef NEPHELE_IMPOSTOR_INC
#define NEPHELE_IMPOSTOR_INC

// Direct storage: the texel coordinate (texel centres at +0.5) of uv in [0, 1]^2 across the
// image whose texels are (x0, y0, x1, y1), kept half a texel inside it.
vec2 impostor_direct_texel(vec4 texels, vec2 uv) {
  vec2 lo = vec2(texels.x, texels.y), hi = vec2(texels.z, texels.w);  // (no swizzles in C++)
  return clamp(mix(lo, hi, uv), lo + 0.5f, hi - 0.5f);
}

// Tiles: each tile of `tile` texels holds tile - 2 of the image's in each axis, with a one-texel
// border repeating its neighbours'. The tile under uv of an image of `size` texels, `across`
// tiles wide.
ivec2 impostor_tile_of(vec2 uv, vec2 size, int tile, int across) {
  float inner = float(tile - 2);
  ivec2 last = ivec2(across, int(ceil(size.y / inner))) - 1;
  return clamp(ivec2(floor(uv * size / inner)), ivec2(0), last);
}

// The atlas texel coordinate of uv in tile `t` stored in `slot` (slots row-major, `per_row` a
// row): within [1, tile - 1] of the tile, so a bilinear footprint stays inside it.
vec2 impostor_tile_texel(vec2 uv, vec2 size, int tile, ivec2 t, int slot, int per_row) {
  float inner = float(tile - 2);
  vec2 local = clamp(uv * size - vec2(t) * inner, vec2(0.0f), vec2(inner)) + 1.0f;
  return vec2(float(slot % per_row), float(slot / per_row)) * float(tile) + local;
}

#endif

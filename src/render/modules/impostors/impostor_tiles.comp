#version 450
// Impostors, tiles method (seed 003, 3.3.6): splits the images drawn into the scratch image
// this frame into the atlas's tiles, each with a one-texel border repeating its neighbours'
// texels (the image's edge texels at its edges), so bilinear filtering inside a tile is right.
// One invocation a texel; z: the job (one tile) after the batch's first.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform DrawBlock { DrawConstants draw; };  // info.x: the first job

void main() {
  ImpostorTileJob job = impostor_tile_jobs[draw.info.x + int(gl_GlobalInvocationID.z)];
  int tile = job.tile.w;
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (texel.x >= tile || texel.y >= tile) return;
  int per_row = imageSize(impostor_atlas_out).x / tile;
  ivec2 slot_origin = ivec2(job.tile.x % per_row, job.tile.x / per_row) * tile;
  // The image texel this tile texel repeats: border texels their neighbours'.
  ivec2 image = clamp(job.tile.yz * (tile - 2) + texel - 1, ivec2(0), job.source.zw - 1);
  imageStore(impostor_atlas_out, slot_origin + texel,
             texelFetch(impostor_scratch, job.source.xy + image, 0));
}

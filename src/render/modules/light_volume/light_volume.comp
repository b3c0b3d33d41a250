#version 450
// Pass: light volume. For each voxel of the light volume's grid (common/light_volume_inc.glsl),
// the optical depth of the cloud field towards the sun; the clouds pass then looks it up
// instead of marching every light ray (Kajiya and Von Herzen's two passes, seed 004). Built
// from the top down (stop 67): a voxel of the lower half marches towards the sun up to the
// altitude of the layer LIGHT_VOLUME_LAYERS_UP above it and takes the rest of the way from the
// volume there (Catmull-Rom between that layer's voxels); the upper half marches to the shell's
// top. Before, every voxel marched in 32 steps, and no further than twice the shell's
// thickness: a still's volume took 0.91 s on lavapipe, now 0.52, and the light of a low sun
// crosses all the cloud on its way (the suite's sunset 15.2 -> 12.1% off the path tracer).
// Rebuilt when the sun, the clouds or the grid's centre change, into a second volume, a band
// of rows a frame (FrameParams::light_volume_build), while the clouds pass reads the last one
// completed: the work is spread over frames. dispatch.values: x the band's first row, y its
// rows (row r: layer LIGHT_VOLUME_Z - 1 - r / LIGHT_VOLUME_XY, line r mod LIGHT_VOLUME_XY; a
// band lies within one group of LIGHT_VOLUME_LAYERS_UP layers, which reads only the layers
// above it).
#extension GL_GOOGLE_include_directive : require

const int MARCH_MODE = 0;
// False compiles the voxel clouds' code out (LightVolumeModule, from FrameParams::voxel_info.x),
// or the flow map's reads (from FrameParams::cloud_flow.x).
layout(constant_id = 0) const bool WITH_VOXELS = true;
layout(constant_id = 1) const bool WITH_FLOW = true;
#define CLOUD_FIELD_VARIANTS
layout(local_size_x = 8, local_size_y = 8) in;

// The detail noise over the grid's own cell (set in main), whatever the view.
float grid_footprint_m = 0.0f;
#define NOISE_DETAIL_FOOTPRINT_M(pos) grid_footprint_m
#include "cloud_field_inc.glsl"
#include "dispatch_inc.glsl"

// The steps of the march up to the layer it reads, one a layer crossed.
const int SEGMENT_STEPS = LIGHT_VOLUME_LAYERS_UP;
// The march of the top layers to the shell's top.
const int WHOLE_STEPS = 16;

// The volume being built at layer z at the horizontal place of pos (the planet frame's xy, as
// light_volume_lookup reads it): Catmull-Rom between its voxels' centres, for a chain of
// resamplings from layer to layer blurs the shadows where bilinear ones would.
float built_depth(vec3 pos, int z, float half_m) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - frame.light_volume_build.xy;
  vec2 g = light_volume_coord(offset, half_m) * float(LIGHT_VOLUME_XY) - 0.5f;
  vec2 g0 = floor(g), f = g - g0;
  vec2 f2 = f * f, f3 = f2 * f;
  vec2 w[4] = vec2[4](-0.5f * f3 + f2 - 0.5f * f, 1.5f * f3 - 2.5f * f2 + 1.0f,
                      -1.5f * f3 + 2.0f * f2 + 0.5f * f, 0.5f * f3 - 0.5f * f2);
  float depth = 0.0f;
  for (int j = 0; j < 4; ++j) {
    float line = 0.0f;
    int y = clamp(int(g0.y) + j - 1, 0, LIGHT_VOLUME_XY - 1);
    for (int i = 0; i < 4; ++i) {
      int x = clamp(int(g0.x) + i - 1, 0, LIGHT_VOLUME_XY - 1);
      line += w[i].x * imageLoad(light_volume_out, ivec3(x, y, z)).r;
    }
    depth += w[j].y * line;
  }
  return max(depth, 0.0f);
}

// The altitude (radius, m) of layer z's voxel centres.
float layer_radius_m(int z) {
  return mix(frame.radii_m.z, frame.radii_m.w, (float(z) + 0.5f) / float(LIGHT_VOLUME_Z));
}

void main() {
  int row = dispatch.values.x + int(gl_GlobalInvocationID.y);
  ivec3 v = ivec3(gl_GlobalInvocationID.x, row % LIGHT_VOLUME_XY,
                  LIGHT_VOLUME_Z - 1 - row / LIGHT_VOLUME_XY);
  if (v.x >= LIGHT_VOLUME_XY || int(gl_GlobalInvocationID.y) >= dispatch.values.y || v.z < 0)
    return;
  float half_m = frame.light_volume_build.z;
  vec2 offset = light_volume_offset_m((vec2(v.xy) + 0.5f) / float(LIGHT_VOLUME_XY), half_m);
  // Cloud space -> this frame's planet frame; the point at the voxel's altitude.
  vec2 xy = frame.light_volume_build.xy + offset + frame.wind_offset_m.xy;
  vec3 pos = point_at_radius(xy, layer_radius_m(v.z));
  vec3 sun = frame.sun_dir.xyz;
  grid_footprint_m = light_volume_voxel_m(length(offset), half_m, LIGHT_VOLUME_XY);
  int above = v.z + LIGHT_VOLUME_LAYERS_UP;
  float depth;
  if (above < LIGHT_VOLUME_Z) {
    // Where the light reaches the layer above (inside that layer's sphere, the ray leaves it).
    float up_m = ray_sphere(pos, sun, layer_radius_m(above)).y;
    depth = march_light(pos, sun, 0.0f, up_m, SEGMENT_STEPS) +
            built_depth(pos + sun * up_m, above, half_m);
  } else {
    depth = march_light(pos, sun, 0.0f, ray_sphere(pos, sun, frame.radii_m.w).y, WHOLE_STEPS);
  }
  imageStore(light_volume_out, v, vec4(depth));
}

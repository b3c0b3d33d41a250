#version 450
// Pass: light volume. For each voxel of the light volume's grid (common/light_volume_inc.glsl),
// the optical depth of the cloud field towards the sun, marched once with many steps; the
// clouds pass then looks it up instead of marching every light ray (Kajiya and Von Herzen's
// two passes, seed 004). Rebuilt when the sun, the clouds or the grid's centre change, into a
// second volume, a band of rows a frame (FrameParams::light_volume_rows), while the clouds
// pass reads the last one completed: the work is spread over frames.
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

const int VOLUME_LIGHT_STEPS = 32;  // converged to ~0.4% (measured against 64)

void main() {
  int row = frame.light_volume_rows.x + int(gl_GlobalInvocationID.y);
  ivec3 v = ivec3(gl_GlobalInvocationID.x, row % LIGHT_VOLUME_XY, row / LIGHT_VOLUME_XY);
  if (v.x >= LIGHT_VOLUME_XY || int(gl_GlobalInvocationID.y) >= frame.light_volume_rows.y ||
      v.z >= LIGHT_VOLUME_Z)
    return;
  float half_m = frame.light_volume_build.z;
  vec2 offset = light_volume_offset_m((vec2(v.xy) + 0.5f) / float(LIGHT_VOLUME_XY), half_m);
  // Cloud space -> this frame's planet frame; the point at the voxel's altitude.
  vec2 xy = frame.light_volume_build.xy + offset + frame.wind_offset_m.xy;
  float h = (float(v.z) + 0.5f) / float(LIGHT_VOLUME_Z);
  float r = mix(frame.radii_m.z, frame.radii_m.w, h);
  vec3 pos = point_at_radius(xy, r);
  vec3 sun = frame.sun_dir.xyz;
  grid_footprint_m = light_volume_voxel_m(length(offset), half_m, LIGHT_VOLUME_XY);
  float depth = march_light(pos, sun, 0.0f, light_ray_length(pos, sun), VOLUME_LIGHT_STEPS);
  imageStore(light_volume_out, v, vec4(depth));
}

#version 450
// The reference path tracer (issue 21), lab scene: voxel cloud 0's density grid in vacuum
// (no planet, no air, black background) with sigma_t = grid density x path_medium.x, lit by
// a distant sun of irradiance path_light.w. Unbiased: delta tracking samples collisions,
// ratio tracking estimates the sun's transmittance at each (next-event estimation), the
// phase function (Henyey-Greenstein) is sampled exactly (common/path_inc.glsl). Each
// invocation adds path_info.y paths to its pixel's sums in path_sum and path_squares; the host
// dispatches until it has the samples or the time it was asked for.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "voxel_field_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

// The lab works in its own frame (FrameParams::path_eye_m): grid coordinates of a point there.
vec3 lab_grid_coord(VoxelCloudGpu c, vec3 p) {
  return vec3(dot(c.to_grid_x.xyz, p) + c.to_grid_x.w, dot(c.to_grid_y.xyz, p) + c.to_grid_y.w,
              dot(c.to_grid_z.xyz, p) + c.to_grid_z.w);
}

vec3 lab_grid_dir(VoxelCloudGpu c, vec3 d) {
  return vec3(dot(c.to_grid_x.xyz, d), dot(c.to_grid_y.xyz, d), dot(c.to_grid_z.xyz, d));
}

// The medium for path_inc.glsl: the grid's box and its trilinear density, as the fast mode
// samples them (voxel_lookup), without the surface erosion the clouds pass adds.
float pt_sigma_t(vec3 p) {
  VoxelCloudGpu c = frame.voxel_clouds[0];
  vec3 u = lab_grid_coord(c, p);
  if (voxel_box_distance(u, c.dims.xyz) > 0.0f) return 0.0f;
  return voxel_lookup(c, u).x * c.anchor_m.w * frame.path_medium.x;
}

// Where the ray (o, d) is inside the grid's box: slabs in grid coordinates (voxels, the map
// being a rotation and a scale, t stays in metres).
vec2 pt_bounds(vec3 o, vec3 d) {
  VoxelCloudGpu c = frame.voxel_clouds[0];
  vec3 u = lab_grid_coord(c, o);
  vec3 du = lab_grid_dir(c, d);
  vec3 inv = 1.0f / mix(vec3(1e-30f), du, greaterThan(abs(du), vec3(1e-30f)));
  vec3 t0 = -u * inv, t1 = (c.dims.xyz - u) * inv;
  vec3 near = min(t0, t1), far = max(t0, t1);
  return vec2(max(max(near.x, near.y), max(near.z, 0.0f)), min(far.x, min(far.y, far.z)));
}

// The majorant grid: the grid's bricks (VOXEL_BRICK^3 voxels, as voxel_lookup cuts them: brick
// b spans grid coordinates [8 b + 1/2, 8 b + 8 1/2)). An empty brick (not stored: no density
// within it or its filter's reach) has majorant 0 and is crossed in one step; a stored one the
// grid's largest extinction (path_medium.w). Along the line u(o) + t du, so that successive
// calls agree on where a boundary is. Without the grid (path_eye_m.w = 0), one segment.
vec2 pt_majorant_segment(vec3 o, vec3 d, float t) {
  if (frame.path_eye_m.w == 0.0f) return vec2(frame.path_medium.w, 1e30f);
  VoxelCloudGpu c = frame.voxel_clouds[0];
  vec3 du = lab_grid_dir(c, d);
  vec3 u = lab_grid_coord(c, o) + du * t;
  // The brick a thousandth of a voxel ahead: a point on a boundary belongs to the next one.
  vec3 ahead = clamp(u + du * (1e-3f * c.dims.w), vec3(0.5f), c.dims.xyz - 0.5f);
  ivec3 b = min(ivec3(floor((ahead - 0.5f) / float(VOXEL_BRICK))), c.bricks.xyz - 1);
  float page = texelFetch(voxel_pages, ivec3(b.xy, b.z + c.bricks.w), 0).r;
  vec3 lo = vec3(b * VOXEL_BRICK) + 0.5f;
  vec3 boundary = mix(lo, lo + float(VOXEL_BRICK), greaterThan(du, vec3(0.0f)));
  vec3 to_boundary = (boundary - u) / mix(vec3(1e-30f), du, greaterThan(abs(du), vec3(1e-30f)));
  // Boundaries behind (the outer bricks reach the box's faces) do not end the segment.
  to_boundary = mix(vec3(1e30f), to_boundary, greaterThan(to_boundary, vec3(0.0f)));
  float end = t + max(min(to_boundary.x, min(to_boundary.y, to_boundary.z)), 1e-3f * c.dims.w);
  return vec2(page < 0.0f ? 0.0f : frame.path_medium.w, end);
}

#include "common/path_inc.glsl"

void main() {
  ivec2 size = imageSize(path_sum);
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= size.x || pixel.y >= size.y) return;
  vec4 sum = imageLoad(path_sum, pixel);
  vec4 squares = imageLoad(path_squares, pixel);
  uint pixel_key = uint(pixel.y * size.x + pixel.x);
  for (int k = 0; k < frame.path_info.y; ++k) {
    uint sample_index = uint(frame.path_info.x + k);
    uint stream = pt_stream(pixel_key, sample_index, uint(frame.path_info.z));
    // A random point in the pixel (box filter).
    float jx = pt_uniform(stream, 0u), jy = pt_uniform(stream, 1u);
    vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                          frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x) + jx - 0.5f,
                          float(pixel.y) + jy - 0.5f, float(size.x), float(size.y));
    float radiance = pt_path_radiance(frame.path_eye_m.xyz, dir, frame.path_light.xyz,
                                      frame.path_light.w, 0.0f, frame.path_medium.y,
                                      frame.path_medium.z, frame.path_info.w,
                                      pt_hash(stream ^ 0x68bc21ebu));
    sum += vec4(vec3(radiance), 1.0f);
    squares += vec4(vec3(radiance * radiance), 0.0f);
  }
  imageStore(path_sum, pixel, sum);
  imageStore(path_squares, pixel, squares);
}

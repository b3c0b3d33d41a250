// The voxel clouds' density and signed distance at a point (seed 002, 体素云建模), read from the
// brick atlas through the page table (common/params_inc.glsl, VoxelCloudGpu). GLSL only.
#ifndef NEPHELE_VOXEL_FIELD_INC
#define NEPHELE_VOXEL_FIELD_INC

#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/voxel_inc.glsl"

#ifndef NOISE_DETAIL_FOOTPRINT_M  // (m) the detail noise's mip level, noise_density_inc.glsl
#define NOISE_DETAIL_FOOTPRINT_M(pos) (distance(pos, frame.camera_pos_m.xyz) * frame.cloud_shape.x)
#endif

// What the voxel clouds hold at a point.
struct VoxelSample {
  float density;  // density field (as the noise clouds', sigma_t = density x cloud_shape.z)
  float sdf_m;    // signed distance (m) to the nearest voxel cloud: a lower bound outside
  float region_m; // distance (m) to the nearest voxel cloud's box: 0 inside one
  float voxel_m;  // the voxel's edge of the nearest box (m)
  int cloud;      // the nearest cloud (by sdf_m)
};

vec3 voxel_grid_coord(VoxelCloudGpu c, vec3 p) {
  vec3 d = p - c.anchor_m.xyz;
  return vec3(dot(c.to_grid_x.xyz, d) + c.to_grid_x.w, dot(c.to_grid_y.xyz, d) + c.to_grid_y.w,
              dot(c.to_grid_z.xyz, d) + c.to_grid_z.w);
}

// (density, signed distance in voxels) of a cloud's grid at u (inside its box).
vec2 voxel_lookup(VoxelCloudGpu c, vec3 u) {
  vec3 uc = clamp(u, vec3(0.5f), c.dims.xyz - 0.5f);
  ivec3 b = min(ivec3(floor((uc - 0.5f) / float(VOXEL_BRICK))), c.bricks.xyz - 1);
  float page = texelFetch(voxel_pages, ivec3(b.xy, b.z + c.bricks.w), 0).r;
  int index = int(max(page, 0.0f));
  ivec3 origin = ivec3(index % VOXEL_ATLAS_BRICKS, (index / VOXEL_ATLAS_BRICKS) % VOXEL_ATLAS_BRICKS,
                       index / (VOXEL_ATLAS_BRICKS * VOXEL_ATLAS_BRICKS)) * VOXEL_BRICK_TEXELS;
  // Texel k of brick b holds voxel VOXEL_BRICK b + k, centred at grid coordinate VOXEL_BRICK b + k + 0.5.
  vec3 coord = (vec3(origin) + uc - vec3(b * VOXEL_BRICK)) / vec3(textureSize(voxel_atlas, 0));
  vec2 texel = textureLod(voxel_atlas, coord, 0.0f).rg;
  return page < 0.0f ? vec2(0.0f, -page) : texel;
}

// Erodes a voxel cloud's density at its surface with the detail noise at a raised frequency
// (seed 002, transition 1: "raise the voxel clouds' detail noise frequency to sharpen their
// surface"), in the cloud's own frame so the detail moves with it.
// Far away, the mip level of the pixel's footprint (as the noise clouds' detail): the finest
// level would sparkle.
float voxel_surface_erosion(float density, float sdf_voxels, vec3 u, float voxel_m, vec3 p) {
  float skin = saturate(1.0f + sdf_voxels / 3.0f);  // 1 at the surface, 0 three voxels in
  float eroded = density;
  // Deeper than the skin, or where there is no cloud, erosion changes nothing: a loop of one
  // trip or none (a CPU device, lavapipe, still runs its body once when no lane needs it).
  for (int k = 0; k < (skin > 0.0f && density > 0.0f ? 1 : 0); ++k) {
    float frequency = frame.cloud_noise.y * frame.voxel_light.w;
    float footprint_texels = NOISE_DETAIL_FOOTPRINT_M(p) *
                             frequency * float(textureSize(detail_noise, 0).x);
    vec3 d = textureLod(detail_noise, u * voxel_m * frequency, log2(max(footprint_texels, 1e-6f))).rgb;
    float detail = d.r * 0.625f + d.g * 0.25f + d.b * 0.125f;
    eroded = saturate(remap(density, detail * frame.voxel_light.z * skin, 1.0f, 0.0f, 1.0f));
  }
  return eroded;
}

VoxelSample voxel_field(vec3 p) {
  VoxelSample s = VoxelSample(0.0f, 1e9f, 1e9f, 1.0f, 0);
  for (int i = 0; i < frame.voxel_info.x; ++i) {
    VoxelCloudGpu c = frame.voxel_clouds[i];
    vec3 u = voxel_grid_coord(c, p);
    float box = voxel_box_distance(u, c.dims.xyz);
    vec2 v = vec2(0.0f, box);
    // A loop of one trip or none. A CPU device (lavapipe, Mesa 22.3) runs both sides of a
    // branch for every lane, and this body once even when no lane of the batch is in the box:
    // each voxel cloud costs its texture reads at every sample.
    for (int k = 0; k < (box <= 0.0f ? 1 : 0); ++k) {
      v = voxel_lookup(c, u);
      v.x = voxel_surface_erosion(v.x, v.y, u, c.dims.w, p);
    }
    s.density += v.x * c.anchor_m.w;
    if (v.y * c.dims.w < s.sdf_m) {
      s.sdf_m = v.y * c.dims.w;
      s.voxel_m = c.dims.w;
      s.cloud = i;
    }
    s.region_m = min(s.region_m, box * c.dims.w);
  }
  return s;
}

// How far (m) from p along dir the ray leaves the voxel clouds' boxes that contain p (0 in none).
float voxel_region_exit_m(vec3 p, vec3 dir) {
  float exit_m = 0.0f;
  for (int i = 0; i < frame.voxel_info.x; ++i) {
    VoxelCloudGpu c = frame.voxel_clouds[i];
    vec3 u = voxel_grid_coord(c, p);
    if (voxel_box_distance(u, c.dims.xyz) > 0.0f) continue;
    vec3 du = vec3(dot(c.to_grid_x.xyz, dir), dot(c.to_grid_y.xyz, dir), dot(c.to_grid_z.xyz, dir));
    vec3 far_plane = mix(-u, c.dims.xyz - u, greaterThanEqual(du, vec3(0.0f)));
    vec3 t = far_plane / mix(vec3(1e-30f), du, greaterThan(abs(du), vec3(1e-30f)));
    exit_m = max(exit_m, min(t.x, min(t.y, t.z)));
  }
  return exit_m;
}

// Where the ray (p, dir) is inside any voxel cloud's box: (its first entry, its last exit)
// in metres along the ray, from 0 on; empty (y <= x) when it meets no box.
vec2 voxel_boxes_segment(vec3 p, vec3 dir) {
  vec2 segment = vec2(1e30f, -1e30f);
  for (int i = 0; i < frame.voxel_info.x; ++i) {
    VoxelCloudGpu c = frame.voxel_clouds[i];
    vec3 u = voxel_grid_coord(c, p);
    vec3 du = vec3(dot(c.to_grid_x.xyz, dir), dot(c.to_grid_y.xyz, dir), dot(c.to_grid_z.xyz, dir));
    vec3 inv = 1.0f / mix(vec3(1e-30f), du, greaterThan(abs(du), vec3(1e-30f)));
    vec3 t0 = -u * inv, t1 = (c.dims.xyz - u) * inv;
    vec3 near = min(t0, t1), far = max(t0, t1);
    float enter = max(max(near.x, near.y), max(near.z, 0.0f));
    float exit = min(far.x, min(far.y, far.z));
    if (exit > enter) segment = vec2(min(segment.x, enter), max(segment.y, exit));
  }
  return segment;
}

// Steps of an SDF cone trace (sdf_cone_trace).
const int SDF_SHADOW_STEPS = 16;

// The sunlight's path from p through voxel cloud `cloud` (the one p is in) traced through its
// signed distance field (seed 002, SDF Shadow): outside the cloud each step crosses what the
// distance field says is empty, and the cone's visibility (sdf_cone_visibility, the seed's
// LightTangent frame.voxel_light.x) is taken where the path comes nearer the cloud again;
// inside, each step goes as deep as the distance to the surface, and the optical depth adds
// the step's length times the mean of the densities at its two ends (the trapezoid rule: the
// density at the start alone under-counts a path going deeper). It ends where the path leaves
// the cloud's box, after SDF_SHADOW_STEPS, or once the cloud is opaque (optical depth
// `opaque`). density_p is the density field at p. Returns (x) the optical depth (density field x m), (y) the visibility, (z) how far
// it went (m), (w) 1 if it left the box: the rest of the light's path (other clouds, the noise
// clouds) is looked up from there.
vec4 sdf_cone_trace(vec3 p, vec3 sun, int cloud, float opaque, float density_p) {
  VoxelCloudGpu c = frame.voxel_clouds[cloud];
  vec3 u = voxel_grid_coord(c, p);
  vec3 du = vec3(dot(c.to_grid_x.xyz, sun), dot(c.to_grid_y.xyz, sun), dot(c.to_grid_z.xyz, sun));
  float t = 0.0f, depth = 0.0f, visibility = 1.0f, previous = -1e9f;
  float last_step_m = 0.0f, last_density = 0.0f;
  float left = 0.0f;
  for (int k = 0; k < SDF_SHADOW_STEPS && depth < opaque; ++k) {
    vec3 q = u + du * t;
    if (voxel_box_distance(q, c.dims.xyz) > 0.0f) {  // out of the cloud's box
      left = 1.0f;
      break;
    }
    vec2 v = voxel_lookup(c, q);
    // At p the density the march found there (eroded); beyond, the grid's own: the steps are
    // a voxel or longer, too far apart for the erosion's fine detail, which they would alias
    // (and its reads were a sixth of the frame on a CPU device).
    float density = k == 0 ? density_p : v.x * c.anchor_m.w;
    depth += 0.5f * (last_density + density) * last_step_m;
    float sdf_m = v.y * c.dims.w;
    if (sdf_m >= 0.0f && t > 0.0f && sdf_m < previous)
      visibility = sdf_cone_visibility(visibility, sdf_m, t, frame.voxel_light.x);
    last_step_m = max(abs(sdf_m), c.dims.w);
    last_density = density;
    previous = sdf_m;
    t += last_step_m;
  }
  // The last step, whose end was not sampled: at its start's density.
  depth += last_density * last_step_m * (left > 0.0f ? 0.5f : 1.0f);
  return vec4(depth, visibility, t, left);
}

// The noise clouds' weight at a point region_m from a voxel region: 0 inside one, rising to 1
// over frame.voxel_light.y (seed 002, transition 1: a low-resolution noise cloud never cuts
// into a close voxel cloud).
float voxel_noise_fade(float region_m) {
  return frame.voxel_info.x > 0 ? smoothstep(0.0f, frame.voxel_light.y, region_m) : 1.0f;
}

#endif

// Pure functions of the voxel clouds (shaders/voxel_field_inc.glsl samples them), shared with
// the CPU (src/render/glsl.h) so that the tests check the sphere tracer's rules.
#ifndef NEPHELE_VOXEL_INC
#define NEPHELE_VOXEL_INC

// Distance (voxels) from grid coordinate u to the grid's box [0, dims]; 0 inside.
float voxel_box_distance(vec3 u, vec3 dims) {
  vec3 q = max(max(-u, u - dims), vec3(0.0f));
  return length(q);
}

// A sphere tracer's step (m) from a point whose sampled signed distance is sdf_m (the field is
// trilinear between texels and exact to within a voxel: one voxel less is safe), never shorter
// than min_step_m: near a surface the trace would otherwise crawl (seed 002: "increase the
// step manually near surfaces and box edges"). min_step_m below the cloud's sampling step
// keeps the tracer from stepping over a cloud's edge.
float voxel_sphere_step(float sdf_m, float voxel_m, float min_step_m) {
  return max(sdf_m - voxel_m, min_step_m);
}

// The sphere tracer's shortest step (m) after `slow_steps` steps in a row that the distance
// field could not lengthen past it (a ray running along a surface): fine_step_m at first,
// doubling with each, at most coarse_step_m (seed 002: "after stepping slowly for a while,
// enlarge the step manually"). A ray grazing a cloud then crosses it as the noise clouds'
// coarse steps would, instead of crawling along it at the fine step.
float voxel_min_step_m(float fine_step_m, float coarse_step_m, int slow_steps) {
  return min(fine_step_m * exp2(float(min(slow_steps, 16))), coarse_step_m);
}

// The SDF cone's visibility (seed 002, SDF Shadow): a cone of half-angle tangent `tangent`
// around the light ray that passes an occluder at distance sdf_m, t_m along the ray, is left
// open by saturate(sdf / (t tangent)); the soft shadow is the least over the trace.
float sdf_cone_visibility(float visibility, float sdf_m, float t_m, float tangent) {
  return min(visibility, clamp(sdf_m / max(t_m * tangent, 1e-3f), 0.0f, 1.0f));
}

#endif

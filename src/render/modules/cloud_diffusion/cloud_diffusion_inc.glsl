// The cloud diffusion's field as the clouds' march reads it (clouds.comp): the multiple-
// scattered light of the clouds, solved on a regular grid in cloud space (CloudDiffusionModule,
// diffusion_solve.comp) as a fluence phi and a flux vector E per unit of the sun's irradiance
// (the light scattered at least once; single scattering is the march's own). The radiance of a
// P1 field, (phi + 3 E . w) / 4 pi, scattered by a phase function of mean cosine g1 towards
// the viewer. Needs cloud_field_inc.glsl (frame, altitude_fraction).
#ifndef NEPHELE_CLOUD_DIFFUSION_INC
#define NEPHELE_CLOUD_DIFFUSION_INC

#include "render/modules/cloud_diffusion/cloud_diffusion_gpu_inc.glsl"

layout(std140, set = 1, binding = 0) uniform CloudDiffusionBlock { CloudDiffusionGpu diffusion; };
layout(set = 1, binding = 1) uniform sampler3D cloud_diffusion_field;

// The grid coordinates ([0, 1]^3) of a point of the planet frame.
vec3 diffusion_coord(vec3 pos) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - diffusion.grid.xy;
  return vec3(0.5f + 0.5f * offset / diffusion.grid.z, altitude_fraction(pos));
}

// Whether the field covers pos: in use, and two cells or more inside the grid's sides (the
// cells at its sides lose their light through them).
bool diffusion_covers(vec3 pos) {
  if (diffusion.grid.w < 0.5f) return false;
  vec2 c = diffusion_coord(pos).xy;
  float margin = 2.0f / float(DIFFUSION_XY);
  return all(greaterThan(c, vec2(margin))) && all(lessThan(c, vec2(1.0f - margin)));
}

// The multiple-scattered light a cloud sample at pos scatters towards a viewer looking along
// `dir`, per unit of the sun's irradiance and of albedo (as cloud_sun_light's y).
float diffusion_radiance(vec3 pos, vec3 dir, float g1) {
  vec4 f = textureLod(cloud_diffusion_field, diffusion_coord(pos), 0.0f);
  // The light propagating towards the viewer travels along -dir.
  return max(f.x - 3.0f * g1 * dot(f.yzw, dir), 0.0f) / (4.0f * PI);
}

#endif

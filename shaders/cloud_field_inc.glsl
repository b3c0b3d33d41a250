// The cloud density field and the light reaching a point of it, shared by the passes that
// sample clouds (clouds.comp, light_volume.comp). Reads the noise and weather textures, so it
// is GLSL only (unlike common/*_inc.glsl). The includer defines the int MARCH_MODE (0 default,
// 1 the seed's baseline) before including this file.
#ifndef NEPHELE_CLOUD_FIELD_INC
#define NEPHELE_CLOUD_FIELD_INC

#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/clouds_inc.glsl"
#include "common/light_volume_inc.glsl"

const int LIGHT_NEAR_STEPS = 3;  // light march steps before the light volume takes over
const vec3 SEED_EXTINCTION_MULT = vec3(0.8f, 0.8f, 1.0f);  // listing B.3

float altitude_fraction(vec3 pos) {
  return cloud_height_fraction(length(pos), frame.radii_m.z, frame.radii_m.w);
}

// Cloud density field (dimensionless, listing B.1); sigma_t = field * cloud_shape.z.
float cloud_density(vec3 pos, bool with_detail) {
  float h = altitude_fraction(pos);
  if (h <= 0.0f || h >= 1.0f) return 0.0f;
  vec2 ground_xy = pos.xy - frame.wind_offset_m.xy;  // clouds drift with the wind
  vec4 weather = textureLod(weather_map, ground_xy * frame.cloud_noise.z + 0.5f, 0.0f);
  float coverage = cloud_local_coverage(weather.r, weather.g, frame.cloud_shape.x);
  if (coverage <= 0.0f) return 0.0f;
  float shape_gradient = cloud_shape_gradient(h, weather.b);
  if (shape_gradient <= 0.0f) return 0.0f;
  float density_gradient =
      cloud_density_gradient(h) * weather.a * 2.0f * frame.cloud_shape.y;

  float altitude_m = length(pos) - frame.radii_m.x;
  vec3 uvw = vec3(ground_xy, altitude_m) * frame.cloud_noise.x;
  vec4 base = textureLod(base_noise, uvw, 0.0f);
  if (MARCH_MODE == 1) {
    // Seed: low-frequency noise 85% plus detail noise 15%, then coverage and height shape.
    float detail = textureLod(detail_noise, vec3(ground_xy, altitude_m) * frame.cloud_noise.y, 0.0f).r;
    float noise = base.r * 0.85f + detail * 0.15f;
    return cloud_apply_coverage(noise * shape_gradient, coverage) * density_gradient;
  }
  // Schneider: Worley fBm (GBA) carves the Perlin-Worley (R), coverage cuts, detail erodes.
  float worley = base.g * 0.625f + base.b * 0.25f + base.a * 0.125f;
  float shape = saturate(remap(base.r, worley - 1.0f, 1.0f, 0.0f, 1.0f));
  shape = cloud_apply_coverage(shape * shape_gradient, coverage);
  if (shape <= 0.0f) return 0.0f;
  if (with_detail) {
    vec3 d = textureLod(detail_noise, vec3(ground_xy, altitude_m) * frame.cloud_noise.y, 0.0f).rgb;
    shape = cloud_erode(shape, d.r * 0.625f + d.g * 0.25f + d.b * 0.125f, h,
                        frame.cloud_noise.w);
  }
  return shape * density_gradient;
}

// Optical depth (density field x metres) along the sun from pos over [t0, t1], n midpoint
// steps growing linearly (short near pos, where the light changes fastest); the detail noise
// counts within the first LIGHT_DETAIL_M metres.
const float LIGHT_DETAIL_M = 1.0e9f;
float march_light(vec3 pos, vec3 sun, float t0, float t1, int n) {
  float unit = (t1 - t0) / float(n * (n + 1) / 2);
  float t = t0;
  float depth = 0.0f;
  for (int i = 1; i <= n; ++i) {
    float s = unit * float(i);
    float mid = t + 0.5f * s;
    depth += cloud_density(pos + sun * mid, mid < LIGHT_DETAIL_M) * s;
    t += s;
  }
  return depth;
}

// How far along the sun the light is traced: to the top of the layer, at most two layer
// thicknesses (for a low sun, so a sample near the base still sees the dense tops above it).
float light_ray_length(vec3 pos, vec3 sun) {
  float thickness = frame.radii_m.w - frame.radii_m.z;
  return min(ray_sphere(pos, sun, frame.radii_m.w).y, 2.0f * thickness);
}

float light_volume_at(ivec3 i) {
  return light_volume[(i.z * LIGHT_VOLUME_XY + i.y) * LIGHT_VOLUME_XY + i.x];
}

// Whether pos is inside the light volume's horizontal extent (and the volume is in use).
bool light_volume_covers(vec3 pos) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - frame.light_volume.xy;
  return frame.light_volume.w > 0.5f && max(abs(offset.x), abs(offset.y)) < frame.light_volume.z;
}

// The size of the light volume's voxels at pos (the largest of their three sides).
float light_volume_voxel_at(vec3 pos) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - frame.light_volume.xy;
  float half_m = frame.light_volume.z;
  return max(max(light_volume_voxel_m(offset.x, half_m, LIGHT_VOLUME_XY),
                 light_volume_voxel_m(offset.y, half_m, LIGHT_VOLUME_XY)),
             (frame.radii_m.w - frame.radii_m.z) / float(LIGHT_VOLUME_Z));
}

// The light volume's optical depth at pos (trilinear).
float light_volume_lookup(vec3 pos) {
  vec2 offset = pos.xy - frame.wind_offset_m.xy - frame.light_volume.xy;
  float half_m = frame.light_volume.z;
  float h = altitude_fraction(pos);
  vec3 coord = vec3(light_volume_coord(offset.x, half_m), light_volume_coord(offset.y, half_m), h);
  vec3 g = clamp(coord * vec3(LIGHT_VOLUME_XY, LIGHT_VOLUME_XY, LIGHT_VOLUME_Z) - 0.5f,
                 vec3(0.0f), vec3(LIGHT_VOLUME_XY - 1, LIGHT_VOLUME_XY - 1, LIGHT_VOLUME_Z - 1));
  ivec3 i0 = ivec3(floor(g));
  ivec3 i1 = min(i0 + 1, ivec3(LIGHT_VOLUME_XY - 1, LIGHT_VOLUME_XY - 1, LIGHT_VOLUME_Z - 1));
  vec3 f = g - vec3(i0);
  float x00 = mix(light_volume_at(i0), light_volume_at(ivec3(i1.x, i0.y, i0.z)), f.x);
  float x10 = mix(light_volume_at(ivec3(i0.x, i1.y, i0.z)), light_volume_at(ivec3(i1.x, i1.y, i0.z)), f.x);
  float x01 = mix(light_volume_at(ivec3(i0.x, i0.y, i1.z)), light_volume_at(ivec3(i1.x, i0.y, i1.z)), f.x);
  float x11 = mix(light_volume_at(ivec3(i0.x, i1.y, i1.z)), light_volume_at(i1), f.x);
  return mix(mix(x00, x10, f.y), mix(x01, x11, f.y), f.z);
}

// Optical depth towards the sun from pos (without the view-independent extinction scale).
float light_optical_depth(vec3 pos, vec3 sun) {
  if (MARCH_MODE == 1) {
    // Listing B.2: three steps of 1% of the layer thickness, the fourth six times longer.
    float step_m = (frame.radii_m.w - frame.radii_m.z) * 0.01f;
    float depth = 0.0f;
    for (int i = 0; i < 4; ++i) {
      float s = i == 3 ? step_m * 6.0f : step_m;
      pos += sun * s;
      depth += cloud_density(pos, true) * s;
    }
    return depth;
  }
  float length_m = light_ray_length(pos, sun);
  if (light_volume_covers(pos)) {
    // March the first voxel (where the volume is too coarse for the light's fast change
    // at a cloud's surface), look the rest up where that march ends.
    float near_m = min(light_volume_voxel_at(pos), length_m);
    float depth = march_light(pos, sun, 0.0f, near_m, frame.steps.y);
    if (near_m < length_m) depth += light_volume_lookup(pos + sun * near_m);
    return depth;
  }
  return march_light(pos, sun, 0.0f, length_m, frame.steps.y);
}

#endif

// Rain and snow as a medium of compose.comp and the stars (media_inc.glsl, generated from the
// modules' folders): what the precipitation between the eye and a layer at `distance_m` along
// `dir` does to the layer's light, read from the froxels its pass marched
// (precipitation.comp) at that distance along the ray, between two of its samples, with the
// particles near the camera that its raster pass drew in front (precipitation_particles.frag);
// and the light it lets reach a surface, from the field at the surface.
#ifndef NEPHELE_PRECIPITATION_MEDIUM
#define NEPHELE_PRECIPITATION_MEDIUM

#include "layers_inc.glsl"
#include "render/modules/precipitation/precipitation_field_inc.glsl"

layout(set = 1, binding = 4) uniform sampler3D precipitation_froxels;
layout(set = 1, binding = 5) uniform sampler3D precipitation_depth;

vec4 precipitation_medium(vec3 eye, vec3 dir, float distance_m, float cloud_light, out float depth_m) {
  depth_m = 0.0f;
  if (precipitation.fall.z <= 0.0f) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  vec2 stretch = precipitation_stretch(eye, dir);
  float t_m = distance_m > 0.0f ? min(distance_m, stretch.y) : stretch.y;
  if (t_m <= stretch.x) return vec4(0.0f, 0.0f, 0.0f, 1.0f);
  float k = precipitation_sample_at(t_m, stretch, precipitation_horizontal(eye, dir));
  // Where the ray lies in the image, as the pass placed its texels (the caller may not be a
  // pass over the pixels: the stars draw each star); the two samples around the distance,
  // mixed by the texture's filter between their slices' centres.
  vec2 image = vec2(frame.size.xy);
  vec2 uv = (camera_pixel(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                          frame.camera_pos_m.w, frame.camera_forward.w, dir, image.x, image.y,
                          vec2(frame.camera_right.w, frame.camera_up.w)) +
             0.5f) /
            image;
  vec3 at = vec3(uv, (k + 0.5f) / float(PRECIPITATION_STEPS + 1));
  vec4 m = textureLod(precipitation_froxels, at, 0.0f);
  float depth_km = textureLod(precipitation_depth, at, 0.0f).r;
  depth_m = m.a < 1.0f ? 1000.0f * depth_km / (1.0f - m.a) : 0.0f;
  m.rgb *= cloud_light;
  // The particles near the camera in front (precipitation_particles.frag), where they are
  // drawn: their light comes from metres away, no air in front of it.
  if (precipitation.near.w > 0.0f) {
    vec4 p = layer_texel(LAYER_PRECIPITATION, ivec2(uv * image));
    float medium = (1.0f - p.a) * (1.0f - m.a);
    depth_m *= medium / max(p.a + medium, 1e-6f);
    m = vec4(p.rgb + (1.0f - p.a) * m.rgb, (1.0f - p.a) * m.a);
  }
  return m;
}

// The share of the sun's (x) and the sky's (y) light that reaches a surface at `pos` through
// the precipitation above it: both as diffuse light through the shaft's column (the particles
// scatter forward).
vec2 precipitation_surface_light(vec3 pos) {
  if (precipitation.fall.z <= 0.0f) return vec2(1.0f);
  float altitude_m = length(pos) - frame.radii_m.x;
  float tau_up = precipitation_tau_above(precipitation_share_at(pos).x, altitude_m);
  float g = precipitation.fall.w;
  float mu_sun = max(precipitation.sun.w, 0.05f);
  return vec2(cloud_diffuse_transmittance(tau_up / mu_sun, g), cloud_diffuse_transmittance(tau_up, g));
}

#endif

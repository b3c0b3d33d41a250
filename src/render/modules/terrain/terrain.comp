#version 450
// Pass: the terrain (render/modules/terrain/terrain.h), before the clouds, one thread per pixel: the
// view ray cast against the heightfield (terrain_inc.glsl; or its distance read from the mesh
// drawn with depth, RASTER) and the point it hits lit as a
// Lambertian surface by the key light (the sun, or the moon at night) through the air
// (transmittance table), the clouds' shadow (cloud_shadow_at) and the terrain's own, and by the
// sky's radiance over the hemisphere about its normal (the sky-view table, 8 cosine-weighted
// directions; the ground's radiance below the horizon), dimmed under clouds as the flat
// ground's is. Writes its radiance per unit key-light illuminance and its distance; compose
// puts the air in front of it.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "common/sky_view_inc.glsl"
#include "frame_atmosphere_inc.glsl"
#include "sky_light_inc.glsl"
const int MARCH_MODE = 0;  // cloud_field_inc.glsl's lookups
#include "cloud_field_inc.glsl"
#include "terrain_inc.glsl"
#include "media_inc.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
// RASTER (specialization constant) 1: the view rays' distances come from the mesh drawn with
// depth (terrain.vert/.frag, terrain.method = "raster") instead of the ray cast.
layout(constant_id = 0) const int RASTER = 0;

const int SKY_DIRECTIONS = 8;
const float SNOW_ALBEDO = 0.8f;
const float SNOW_MAX_SLOPE_COS = 0.766f;  // cos 40 deg

// The mean radiance over the hemisphere about n, cosine-weighted (irradiance / pi).
vec3 hemisphere_radiance(vec3 n) {
  SkyViewFrame f = sky_view_frame_from(frame.sky_view_up, frame.sky_view_forward);
  vec3 t = normalize(abs(n.z) < 0.9f ? cross(n, vec3(0.0f, 0.0f, 1.0f)) : cross(n, vec3(1.0f, 0.0f, 0.0f)));
  vec3 b = cross(n, t);
  vec3 sum = vec3(0.0f);
  for (int k = 0; k < SKY_DIRECTIONS; ++k) {
    float u = (float(k) + 0.5f) / float(SKY_DIRECTIONS);
    float phi = 2.39996323f * float(k);  // the golden angle
    float r = sqrt(u);
    vec3 d = t * (r * cos(phi)) + b * (r * sin(phi)) + n * sqrt(1.0f - u);
    sum += sky_radiance(f, d);
  }
  return sum / float(SKY_DIRECTIONS);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (pixel.x >= frame.size.x || pixel.y >= frame.size.y) return;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x),
                        float(pixel.y), float(frame.size.x), float(frame.size.y),
                        vec2(frame.camera_right.w, frame.camera_up.w));
  vec3 eye = frame.camera_pos_m.xyz;
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  float t_max = ground.x > 0.0f ? ground.x : 1.0e9f;  // the ground sphere hides what is below it
  float t = RASTER == 1 ? imageLoad(layers_out, ivec3(pixel, LAYER_SURFACES)).a : terrain_ray(eye, dir, t_max, false);
  if (t > t_max) t = 0.0f;
  if (t <= 0.0f) {
    imageStore(layers_out, ivec3(pixel, LAYER_SURFACES), vec4(0.0f));
    return;
  }
  vec3 p = eye + dir * t;
  vec3 n = terrain_normal(p);
  vec3 up = normalize(p);
  vec3 sun = frame.sun_dir.xyz;
  float height_m = length(p) - frame.radii_m.x;
  // Snow on the gentler slopes above its line, fading in over 150 m.
  float snow = frame.terrain_shape.w > 0.0f
                   ? saturate((height_m - frame.terrain_shape.w) / 150.0f) *
                         saturate((dot(n, up) - SNOW_MAX_SLOPE_COS) / 0.1f)
                   : 0.0f;
  vec3 bare = frame.terrain_albedo.w > 0.5f
                  ? textureLod(terrain_albedo_map, terrain_cell(p.xy) / (terrain_points() - 1.0f), 0.0f).rgb
                  : frame.terrain_albedo.rgb;
  vec3 albedo = mix(bare, vec3(SNOW_ALBEDO), snow);
  float cos_sun = dot(n, sun);
  float clouds = cloud_shadow_at(p, sun, t, 8);  // half the flat ground's samples: 40 ms less at 640 x 400 on lavapipe
  // The sunlight the clouds scatter down (ground_light.comp), as on flat ground, shared with the
  // diffuse light of the cloud towards the sun (cloud_ground_light_shares).
  vec3 cloud_light = texelFetch(ground_light, ivec2(0), 0).gba;
  vec2 shares = cloud_ground_light_shares(clouds, cloud_transport_g(), cloud_light);
  vec3 direct = vec3(0.0f);
  for (int i = 0; i < (cos_sun > 0.0f ? 1 : 0); ++i) {  // a loop, not a branch: see compose
    // Lifted 5 m off the surface: altitudes |p| - R are floats good to half a metre.
    float self = terrain_ray(p + n * 5.0f, sun, 1.0e9f, true) > 0.0f ? 0.0f : 1.0f;
    direct = transmittance_to_light(frame_atmosphere(), transmittance_lut, false, p, sun) *
             (cos_sun * shares.x * self / PI);
  }
  float sky_share = cloud_ground_sky_share(clouds, texelFetch(ground_light, ivec2(0), 0).r);
  vec2 media = media_surface_light(p);  // what a fog above lets through, of the sun's and the sky's
  vec3 radiance = albedo * (direct * media.x + (hemisphere_radiance(n) * sky_share + cloud_light * shares.y) * media.y);
  imageStore(layers_out, ivec3(pixel, LAYER_SURFACES), vec4(radiance, t));
}

#version 450
// Pass 5: stars. One invocation per star of the catalogue (data/stars.csv): its J2000
// direction turned into the sky of the date and place, projected into the image and added to
// the pixel it falls in as radiance = irradiance / the pixel's solid angle, dimmed by the air
// (extinction grows towards the horizon), by the media (the ground fog: media_inc.glsl) and by
// the clouds and the translucent layers (the particle clouds: layer_list_inc.glsl) in front of
// it.
// Stars fade as the sky brightens by themselves: a magnitude-0 star is 1e-11 of the sun, far
// below a day sky.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "dispatch_inc.glsl"
#include "common/math_inc.glsl"
#include "frame_atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "terrain_inc.glsl"
#include "media_inc.glsl"
#include "layer_list_inc.glsl"

layout(local_size_x = 64) in;

void main() {
  int i = int(gl_GlobalInvocationID.x);
  if (i >= int(frame.stars.y)) return;
  StarGpu star = star_list[i];
  vec3 dir = vec3(dot(frame.star_east.xyz, star.dir_j2000.xyz),
                  dot(frame.star_north.xyz, star.dir_j2000.xyz),
                  dot(frame.star_up.xyz, star.dir_j2000.xyz));
  vec3 eye = frame.camera_pos_m.xyz;
  if (ray_sphere(eye, dir, frame.radii_m.x).x > 0.0f) return;  // below the horizon
  int width = frame.size.x;
  int height = frame.size.y;
  vec2 q = camera_pixel(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, dir, float(width),
                        float(height),
                        vec2(frame.camera_right.w, frame.camera_up.w));
  ivec2 pixel = ivec2(floor(q + 0.5f));
  if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(pixel, ivec2(width, height)))) return;
  vec3 air = transmittance_to_light(frame_atmosphere(), transmittance_lut, false, eye, dir);
  // The clouds in front hide it, except in the sky layer (dispatch.values.x 1: what is behind them).
  vec2 uv = (vec2(pixel) + 0.5f) / vec2(width, height);
  float cloud = dispatch.values.x == 1
                    ? 1.0f
                    : textureLod(clouds_a, uv, 0.0f).a * layers_transmittance(uv);
  if (terrain_distance_at(uv) > 0.0f) cloud = 0.0f;  // behind the terrain
  float visibility = frame.conditions_sky_fog.w;  // the keyframes' star visibility, 1 when off
  float media = media_in_front(eye, dir, 0.0f, 1.0f).a;  // their transmittance towards the sky
  vec3 radiance =
      star.irradiance.rgb * frame.stars.x / frame.stars.z * air * cloud * visibility * media;
  imageStore(color_rw, pixel, imageLoad(color_rw, pixel) + vec4(radiance, 0.0f));
}

#version 450
// Pass: Nishita and Nakamae's first-order light on their voxel grid (render/modules/
// metaball_clouds.h). Per voxel: the sun's transmittance from the voxel's centre to where its
// ray leaves the grid, and the sky's light reaching it, (1 / 4 pi) sum over
// NISHITA_SKY_DIRECTIONS of the sky's radiance (the sky-view table by direction: its
// luminance distribution, as the paper has it) or, below the horizontal, the lit ground's, times
// the transmittance that way; scattered isotropically, so one rgb mean radiance per voxel.
// Writes slab 1: (sun transmittance, sky light rgb per unit key-light illuminance).
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/sky_view_inc.glsl"
#include "nishita_volume_inc.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main() {
  ivec3 v = ivec3(gl_GlobalInvocationID);
  ivec3 dims = nishita_dims();
  if (any(greaterThanEqual(v, dims))) return;
  float voxel_m = nishita_voxel_m();
  vec3 p = nishita_corner() + (vec3(v) + 0.5f) * voxel_m;
  vec3 light = frame.sun_dir.xyz;
  float sun = exp(-nishita_optical_depth(p, light, voxel_m));
  vec3 sky = vec3(0.0f);
  if (frame.classic_nishita_light.w > 0.5f) {
    SkyViewFrame sky_frame = sky_view_frame_from(frame.sky_view_up, frame.sky_view_forward);
    float rows = float(textureSize(sky_view_lut, 0).y / 2);
    vec3 below = frame.ambient_below_clouds.rgb / max(frame.sun_illuminance.rgb, vec3(1e-20f));
    for (int i = 0; i < NISHITA_SKY_DIRECTIONS; ++i) {
      vec3 d = nishita_sphere_dir(i, NISHITA_SKY_DIRECTIONS);
      vec3 radiance = d.z > 0.0f
                          ? textureLod(sky_view_lut, sky_view_texcoord(sky_view_uv(sky_frame, d), rows, 0.0f), 0.0f).rgb
                          : below;
      sky += radiance * exp(-nishita_optical_depth(p, d, 2.0f * voxel_m));
    }
    sky /= float(NISHITA_SKY_DIRECTIONS);
  }
  ivec3 out_v = ivec3(v.x, v.y, v.z + dims.z);
  imageStore(nishita_volume_out, out_v, vec4(sun, sky));
}

#version 450
// Pass: the lighting for the host (render/modules/host_lighting/host_lighting.h), one workgroup: the clouds'
// transmittance at the camera towards the key and the second light (cloud_shadow_at), the
// clouds' sigma_t there, the share of the clear sky's light under the clouds (as the terrain's
// sky light is dimmed), and the sky's radiance about the camera (the sky-view table) projected
// on the nine real spherical harmonics of bands 0 to 2, over SH_ROWS x 2 SH_ROWS cells of
// latitude and longitude weighted by their solid angles.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/atmosphere_inc.glsl"
#include "common/atmosphere_lut_inc.glsl"
#include "common/clouds_inc.glsl"
#include "common/sh_inc.glsl"
#include "frame_atmosphere_inc.glsl"
#include "sky_light_inc.glsl"
const int MARCH_MODE = 0;  // cloud_field_inc.glsl's lookups
#include "cloud_field_inc.glsl"

const int THREADS = 64;
const int SH_ROWS = 64;
layout(local_size_x = THREADS) in;

shared vec3 partial[THREADS][9];


void main() {
  uint id = gl_LocalInvocationID.x;
  SkyViewFrame f = sky_view_frame_from(frame.sky_view_up, frame.sky_view_forward);
  vec3 sum[9];
  for (int k = 0; k < 9; ++k) sum[k] = vec3(0.0f);
  const int cells = SH_ROWS * 2 * SH_ROWS;
  for (int c = int(id); c < cells; c += THREADS) {
    int row = c / (2 * SH_ROWS), column = c % (2 * SH_ROWS);
    float z0 = 1.0f - 2.0f * float(row) / float(SH_ROWS), z1 = 1.0f - 2.0f * float(row + 1) / float(SH_ROWS);
    float z = 0.5f * (z0 + z1);  // equal solid angles: cells of equal height in z
    float phi = (float(column) + 0.5f) / float(2 * SH_ROWS) * 2.0f * PI;
    float s = sqrt(max(1.0f - z * z, 0.0f));
    vec3 d = vec3(s * cos(phi), s * sin(phi), z);
    float solid_angle = 4.0f * PI / float(cells);
    vec3 radiance = sky_radiance(f, d);
    Sh9 basis = sh9_basis(d);
    for (int k = 0; k < 9; ++k) sum[k] += radiance * (basis.y[k] * solid_angle);
  }
  for (int k = 0; k < 9; ++k) partial[id][k] = sum[k];
  barrier();
  for (uint stride = THREADS / 2; stride > 0; stride /= 2) {
    if (id < stride)
      for (int k = 0; k < 9; ++k) partial[id][k] += partial[id + stride][k];
    barrier();
  }
  if (id != 0) return;
  vec3 eye = frame.camera_pos_m.xyz;
  // The key light from the light volume where it covers the camera (as the clouds are lit);
  // the second light, which the volume does not follow, from 16 samples.
  float key = cloud_shadow_at(eye, frame.sun_dir.xyz, 1.0e9f, 16);
  float second = frame.second_light.w > 0.0f ? cloud_shadow_at(eye, frame.second_light.xyz, 0.0f, 16) : 1.0f;
  float sigma_t = cloud_density(eye, true) * frame.cloud_shape.z;
  float sky_share = cloud_ground_sky_share(key, texelFetch(ground_light, ivec2(0), 0).r);
  host_lighting_out[0] = vec4(key, second, sigma_t, sky_share);
  for (int k = 0; k < 9; ++k) host_lighting_out[1 + k] = vec4(partial[0][k], 0.0f);
}

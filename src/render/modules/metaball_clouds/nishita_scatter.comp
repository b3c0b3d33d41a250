#version 450
// Pass: Nishita and Nakamae's second order (render/modules/metaball_clouds/metaball_clouds.h). Each voxel
// gathers the sunlight scattered once by the voxels within NISHITA_GATHER_RADIUS of it: from
// voxel u at distance d, travelling along s = (v - u) / d, the irradiance
// E_u = sigma_s rho_u dV T_sun(u) p(-light . s) exp(-tau(u, v)) / d^2 per unit key-light
// illuminance, tau from the density at u, halfway and at v. Their anisotropy is kept as the
// sums (sum E_u, sum E_u s), from which the march scatters towards the eye
// (classic_inc.glsl, nishita_second_order). Within the voxel itself, where most of it comes
// from in a dense cloud (a free path shorter than a voxel), the light is integrated as from a
// uniform sphere of the voxel's volume. Writes slab 2.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "nishita_volume_inc.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

void main() {
  ivec3 v = ivec3(gl_GlobalInvocationID);
  ivec3 dims = nishita_dims();
  if (any(greaterThanEqual(v, dims))) return;
  float voxel_m = nishita_voxel_m();
  float sigma_t = frame.classic_nishita_light.x, albedo = frame.classic_nishita_light.y;
  vec3 light = frame.sun_dir.xyz;
  vec3 p_v = nishita_corner() + (vec3(v) + 0.5f) * voxel_m;
  float rho_v = nishita_texel(0, v).r;
  // The voxel's own light, as from a sphere of its volume (radius a) of its density about its
  // centre: integral of sigma_s rho T p(s) exp(-sigma_t rho r) / r^2 dV
  // = albedo (1 - exp(-sigma_t rho a)) T, travelling on average along the phase's mean
  // cosine times the light's direction (away from the sun).
  float a_m = voxel_m * 0.6203505f;  // (3 / (4 pi))^(1/3)
  float g_mean = mix(frame.cloud_phase.y, frame.cloud_phase.x, frame.cloud_phase.z);
  float total = albedo * (1.0f - exp(-sigma_t * rho_v * a_m)) * nishita_texel(1, v).r;
  vec3 flux = total * g_mean * -light;
  const int r = NISHITA_GATHER_RADIUS;
  for (int z = -r; z <= r; ++z)
    for (int y = -r; y <= r; ++y)
      for (int x = -r; x <= r; ++x) {
        ivec3 o = ivec3(x, y, z);
        int d2 = x * x + y * y + z * z;
        if (d2 == 0 || d2 > r * r) continue;
        ivec3 u = v + o;
        if (any(lessThan(u, ivec3(0))) || any(greaterThanEqual(u, dims))) continue;
        float rho_u = nishita_texel(0, u).r;
        if (rho_u <= 0.0f) continue;
        float d_m = sqrt(float(d2)) * voxel_m;
        vec3 s = -vec3(o) / sqrt(float(d2));
        float rho_mid = nishita_sample(0, p_v - 0.5f * vec3(o) * voxel_m).r;
        float tau = sigma_t * d_m * (rho_u + 2.0f * rho_mid + rho_v) * 0.25f;
        float phase = dual_lobe_hg(frame.cloud_phase.x, frame.cloud_phase.y, frame.cloud_phase.z,
                                   dot(-light, s));
        float e = albedo * sigma_t * rho_u * voxel_m * voxel_m * voxel_m * nishita_texel(1, u).r *
                  phase * exp(-tau) / (d_m * d_m);
        total += e;
        flux += e * s;
      }
  imageStore(nishita_volume_out, ivec3(v.x, v.y, v.z + 2 * dims.z), vec4(total, flux));
}

#version 450
// Pass: cloud diffusion, the field the clouds read (cloud_diffusion_inc.glsl): per cell the
// fluence phi and the flux vector E (the mean of its opposite faces' fluxes,
// diffusion_conductance, less the light the clear air brings back). A cell of clear air next
// to cloud takes the light gathered in it (diffusion_exchange.comp), or where none was, what
// its cloudy neighbours' faces towards it hold, the face's fluence 2 E_n and their flux, so that
// the trilinear field a sample reads near a cloud's surface is the surface's and not half of it.
// The gather's set to read: EXCHANGE_READ_SET (diffusion_exchange_inc.glsl).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bindings_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_exchange_inc.glsl"

layout(set = 1, binding = 2, rgba32f) uniform readonly image3D cloud_diffusion_medium;
layout(set = 1, binding = 3, rgba32f) uniform readonly image3D cloud_diffusion_phi;
layout(set = 1, binding = 4, rgba32f) uniform writeonly image3D cloud_diffusion_field_out;

void main() {
  ivec3 c = diffusion_cell(gl_GlobalInvocationID.xy);
  int cascade = diffusion_cascade(c);
  if (!diffusion_in_grid(c, cascade)) return;
  float d = imageLoad(cloud_diffusion_medium, c).x;
  float phi = imageLoad(cloud_diffusion_phi, c).r;
  vec3 h = diffusion_cell_m(cascade);
  vec3 flux = vec3(0.0f);
  float surface = 0.0f;
  int surfaces = 0;
  for (int k = 0; k < 6; ++k) {
    int axis = k >> 1;
    ivec3 step = ivec3(0);
    step[axis] = (k & 1) == 0 ? 1 : -1;
    ivec3 n = c + step;
    bool inside = diffusion_in_grid(n, cascade);
    if (!inside && axis < 2) continue;  // none through the grid's sides
    float d_n = inside ? imageLoad(cloud_diffusion_medium, n).x : 0.0f;
    float phi_n = inside ? imageLoad(cloud_diffusion_phi, n).r : 0.0f;
    if (d > 0.0f) {
      // Out of this cell through the face, along step; towards clear air, less what it brings
      // back.
      float back = d_n <= 0.0f && inside ? 4.0f * exchange_incoming(n, EXCHANGE_READ_SET, -step)
                                         : 0.0f;
      float out_flux = d_n > 0.0f ? diffusion_conductance(d, d_n, h[axis],
                                                          diffusion_limiter(phi, phi_n, h[axis])) *
                                        (phi - phi_n)
                                  : diffusion_open_conductance(d, h[axis]) * (phi - back);
      flux[axis] += 0.5f * out_flux * float(step[axis]);
    } else if (d_n > 0.0f) {
      // Clear air next to cloud: the cloud's face, its flux out E_n (along -step) and its
      // fluence 2 E_n.
      float e_n = diffusion_open_conductance(d_n, h[axis]) * phi_n;
      flux[axis] -= e_n * float(step[axis]);
      surface += 2.0f * e_n;
      surfaces += 1;
    }
  }
  if (d <= 0.0f) {
    vec4 xy, z;
    exchange_load(c, EXCHANGE_READ_SET, xy, z);
    phi = surfaces > 0 ? surface / float(surfaces) : 0.0f;
    if (z.z > 0.0f) {
      phi = z.z;
      flux = vec3(xy.x - xy.y, xy.z - xy.w, z.x - z.y);
    }
  }
  imageStore(cloud_diffusion_field_out, c, vec4(phi, flux));
}

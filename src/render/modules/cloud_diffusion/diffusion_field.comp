#version 450
// Pass: cloud diffusion, the field the clouds read (cloud_diffusion_inc.glsl): per cell the
// fluence phi and the flux vector E (the mean of its opposite faces' fluxes,
// diffusion_face_flux). A cell of clear air next to cloud takes what its cloudy neighbours'
// faces towards it hold, the face's fluence 2 E_n and their flux, so that the trilinear field a
// sample reads near a cloud's surface is the surface's and not half of it.
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bindings_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"

layout(set = 1, binding = 2, rgba32f) uniform readonly image3D cloud_diffusion_medium;
layout(set = 1, binding = 3, r32f) uniform readonly image3D cloud_diffusion_phi;
layout(set = 1, binding = 4, rgba32f) uniform writeonly image3D cloud_diffusion_field_out;

void main() {
  ivec3 c = diffusion_cell(gl_GlobalInvocationID.xy);
  int cascade = diffusion_cascade(c);
  if (!diffusion_in_grid(c, cascade)) return;
  vec4 m = imageLoad(cloud_diffusion_medium, c);
  float phi = imageLoad(cloud_diffusion_phi, c).r;
  vec3 h = diffusion_cell_m(cascade);
  vec3 beam = -frame.sun_dir.xyz;
  vec3 flux = vec3(0.0f);
  float surface = 0.0f;
  int surfaces = 0;
  for (int k = 0; k < 6; ++k) {
    int axis = k >> 1;
    ivec3 step = ivec3(0);
    step[axis] = (k & 1) == 0 ? 1 : -1;
    ivec3 n = c + step;
    bool inside = diffusion_in_grid(n, cascade);
    // Past the grid's sides the clouds go on: no flux through them (a deck cut there would
    // lose its light sideways).
    if (!inside && axis < 2) continue;
    vec4 m_n = inside ? imageLoad(cloud_diffusion_medium, n) : vec4(0.0f);
    float phi_n = inside ? imageLoad(cloud_diffusion_phi, n).r : 0.0f;
    if (m.x > 0.0f) {
      // Out of this cell through the face, along step.
      bool open = m_n.x <= 0.0f;
      float out_flux = diffusion_face_flux(phi, m, phi_n, m_n, open, h[axis],
                                           beam[axis] * float(step[axis]),
                                           open ? 0.0f : diffusion_limiter(phi, phi_n, h[axis]));
      flux[axis] += 0.5f * out_flux * float(step[axis]);
    } else if (m_n.x > 0.0f) {
      // Into this cell of clear air, out of the cloudy neighbour (along -step).
      float in_flux = diffusion_face_flux(phi_n, m_n, 0.0f, m, true, h[axis],
                                          -beam[axis] * float(step[axis]), 0.0f);
      flux[axis] -= in_flux * float(step[axis]);
      surface += 2.0f * in_flux;
      surfaces += 1;
    }
  }
  if (m.x <= 0.0f) phi = surfaces > 0 ? surface / float(surfaces) : 0.0f;
  imageStore(cloud_diffusion_field_out, c, vec4(phi, flux));
}

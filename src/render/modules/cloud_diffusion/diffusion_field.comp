#version 450
// Pass: cloud diffusion, the field the clouds read (cloud_diffusion_inc.glsl): per cell the
// fluence phi and the flux vector E (the mean of its opposite faces' fluxes,
// diffusion_face_flux).
#extension GL_GOOGLE_include_directive : require

layout(local_size_x = 8, local_size_y = 8) in;

#include "common/bindings_inc.glsl"
#include "render/modules/cloud_diffusion/diffusion_grid_inc.glsl"

layout(set = 1, binding = 2, rgba32f) uniform readonly image3D cloud_diffusion_medium;
layout(set = 1, binding = 3, r32f) uniform readonly image3D cloud_diffusion_phi;
layout(set = 1, binding = 4, rgba32f) uniform writeonly image3D cloud_diffusion_field_out;

void main() {
  ivec3 c = diffusion_cell(gl_GlobalInvocationID.xy);
  if (!diffusion_in_grid(c)) return;
  vec4 m = imageLoad(cloud_diffusion_medium, c);
  float phi = imageLoad(cloud_diffusion_phi, c).r;
  vec3 h = diffusion_cell_m();
  vec3 beam = -frame.sun_dir.xyz;
  vec3 flux = vec3(0.0f);
  for (int k = 0; k < 6; ++k) {
    int axis = k >> 1;
    ivec3 step = ivec3(0);
    step[axis] = (k & 1) == 0 ? 1 : -1;
    ivec3 n = c + step;
    bool inside = diffusion_in_grid(n);
    // Past the grid's sides the clouds go on: no flux through them (a deck cut there would
    // lose its light sideways).
    if (!inside && axis < 2) continue;
    vec4 m_n = inside ? imageLoad(cloud_diffusion_medium, n) : vec4(0.0f);
    float phi_n = inside ? imageLoad(cloud_diffusion_phi, n).r : 0.0f;
    // Out of this cell through the face, along step.
    float out_flux = diffusion_face_flux(phi, m, phi_n, m_n, !inside, h[axis],
                                         beam[axis] * float(step[axis]));
    flux[axis] += 0.5f * out_flux * float(step[axis]);
  }
  imageStore(cloud_diffusion_field_out, c, vec4(phi, flux));
}

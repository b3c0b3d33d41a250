// The cloud diffusion's exchange through clear air (diffusion_exchange.comp): per cell of
// clear air next to cloud, the light that the clouds' faces around it send into it, as the
// partial currents J (per unit area and of the sun's irradiance) crossing it along +x, -x,
// +y, -y (image xy) and +z, -z (image z, x and y), and its fluence phi (image z, z). Other
// cells hold 0. Two sets, one read and one written by each gather, dispatch-chosen.
#ifndef NEPHELE_DIFFUSION_EXCHANGE_INC
#define NEPHELE_DIFFUSION_EXCHANGE_INC

layout(set = 1, binding = 5, rgba32f) uniform image3D cloud_diffusion_exchange_xy_a;
layout(set = 1, binding = 6, rgba32f) uniform image3D cloud_diffusion_exchange_z_a;
layout(set = 1, binding = 7, rgba32f) uniform image3D cloud_diffusion_exchange_xy_b;
layout(set = 1, binding = 8, rgba32f) uniform image3D cloud_diffusion_exchange_z_b;

// The partial currents (+x, -x, +y, -y), (+z, -z, phi, 0) of cell c in set `which`.
void exchange_load(ivec3 c, int which, out vec4 xy, out vec4 z) {
  xy = which == 0 ? imageLoad(cloud_diffusion_exchange_xy_a, c)
                  : imageLoad(cloud_diffusion_exchange_xy_b, c);
  z = which == 0 ? imageLoad(cloud_diffusion_exchange_z_a, c)
                 : imageLoad(cloud_diffusion_exchange_z_b, c);
}

void exchange_store(ivec3 c, int which, vec4 xy, vec4 z) {
  if (which == 0) {
    imageStore(cloud_diffusion_exchange_xy_a, c, xy);
    imageStore(cloud_diffusion_exchange_z_a, c, z);
  } else {
    imageStore(cloud_diffusion_exchange_xy_b, c, xy);
    imageStore(cloud_diffusion_exchange_z_b, c, z);
  }
}

// The partial current of clear cell c crossing it along the unit axis vector `step` (into the
// cloud cell c + step): the light the clear air brings to that cloud's face.
float exchange_incoming(ivec3 c, int which, ivec3 step) {
  int axis = step.x != 0 ? 0 : (step.y != 0 ? 1 : 2);
  int slot = 2 * axis + (step.x + step.y + step.z > 0 ? 0 : 1);
  vec4 v = slot < 4 ? (which == 0 ? imageLoad(cloud_diffusion_exchange_xy_a, c)
                                  : imageLoad(cloud_diffusion_exchange_xy_b, c))
                    : (which == 0 ? imageLoad(cloud_diffusion_exchange_z_a, c)
                                  : imageLoad(cloud_diffusion_exchange_z_b, c));
  return v[slot & 3];
}

#endif

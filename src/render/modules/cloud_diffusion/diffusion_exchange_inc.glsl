// The cloud diffusion's exchange through clear air (diffusion_exchange.comp): per cell of
// clear air next to cloud, the light that the clouds' faces around it send into it, as the
// partial currents J (per unit area and of the sun's irradiance) crossing it along +x, -x,
// +y, -y, +z and -z, and its fluence phi. Other cells hold 0. Two sets, one read and one
// written by each gather.
#ifndef NEPHELE_DIFFUSION_EXCHANGE_INC
#define NEPHELE_DIFFUSION_EXCHANGE_INC

// The set read (0 or 1; the gather writes the other): a specialization constant, not a
// dispatch value, so that a CPU device (lavapipe), which runs both sides of every branch, loads
// one set's images and not both's (a still's 8 gathers and their inflow 2.0 -> 1.2 s on
// lavapipe, stop 67).
layout(constant_id = 0) const int EXCHANGE_READ_SET = 0;

// Each set is one image twice the grid's width: texel (2x, y, z) holds cell (x, y, z)'s
// (+x, -x, +y, -y), texel (2x + 1, y, z) its (+z, -z, phi, 0), so that one partial current is
// one load.
layout(set = 1, binding = 5, rgba32f) uniform image3D cloud_diffusion_exchange_a;
layout(set = 1, binding = 6, rgba32f) uniform image3D cloud_diffusion_exchange_b;

vec4 exchange_texel(ivec3 c, int which, int half_index) {
  ivec3 t = ivec3(2 * c.x + half_index, c.yz);
  return which == 0 ? imageLoad(cloud_diffusion_exchange_a, t)
                    : imageLoad(cloud_diffusion_exchange_b, t);
}

// The partial currents (+x, -x, +y, -y), (+z, -z, phi, 0) of cell c in set `which`.
void exchange_load(ivec3 c, int which, out vec4 xy, out vec4 z) {
  xy = exchange_texel(c, which, 0);
  z = exchange_texel(c, which, 1);
}

void exchange_store(ivec3 c, int which, vec4 xy, vec4 z) {
  ivec3 t = ivec3(2 * c.x, c.yz);
  if (which == 0) {
    imageStore(cloud_diffusion_exchange_a, t, xy);
    imageStore(cloud_diffusion_exchange_a, t + ivec3(1, 0, 0), z);
  } else {
    imageStore(cloud_diffusion_exchange_b, t, xy);
    imageStore(cloud_diffusion_exchange_b, t + ivec3(1, 0, 0), z);
  }
}

// The partial current of clear cell c crossing it along the unit axis vector `step` (into the
// cloud cell c + step): the light the clear air brings to that cloud's face.
float exchange_incoming(ivec3 c, int which, ivec3 step) {
  int axis = step.x != 0 ? 0 : (step.y != 0 ? 1 : 2);
  int slot = 2 * axis + (step.x + step.y + step.z > 0 ? 0 : 1);
  return exchange_texel(c, which, slot >> 2)[slot & 3];
}

#endif

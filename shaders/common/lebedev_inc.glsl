// Lebedev's 14-point rule on the sphere (exact to degree 5): the 6 axes, weight 4 pi / 15, and
// the 8 diagonals, weight 4 pi 3 / 40. The cloud diffusion's exchange through clear air
// (diffusion_exchange.comp) gathers the light coming into a cell along these directions into
// its fluence and its six partial currents. Pure; compiled as C++ too (render/glsl.h). The
// includer includes math_inc.glsl.
#ifndef NEPHELE_LEBEDEV_INC
#define NEPHELE_LEBEDEV_INC

const int LEBEDEV_POINTS = 14;

// Point k's direction in whole steps: k < 6 an axis (+x, -x, +y, -y, +z, -z), else a diagonal.
ivec3 lebedev_step(int k) {
  ivec3 o = ivec3(0);
  if (k < 6)
    o[k >> 1] = (k & 1) == 0 ? 1 : -1;
  else
    o = ivec3(((k - 6) & 1) * 2 - 1, ((k - 6) & 2) - 1, ((k - 6) >> 1 & 2) - 1);
  return o;
}

// The partial current that light arriving from point k's direction feeds along `axis`: 2 axis
// where it travels along +axis (it comes from the -axis side), 2 axis + 1 along -axis; -1 where
// the direction lies across the axis. Slots: +x, -x, +y, -y, +z, -z.
int lebedev_current_slot(int k, int axis) {
  int o = lebedev_step(k)[axis];
  return o == 0 ? -1 : 2 * axis + (o < 0 ? 0 : 1);
}

// Point k's weight (the weights sum to 4 pi).
float lebedev_weight(int k) { return 4.0f * PI * (k < 6 ? 1.0f / 15.0f : 3.0f / 40.0f); }

// A partial current, the integral of L |cos| over a hemisphere, is not a polynomial: of an
// isotropic radiance L the rule gives 4 pi (1 / 15 + 0.3 / sqrt 3) L = 0.9595 pi L, of a
// radiance linear in the direction exactly. What to add to each of its partial currents, from
// the fluence phi (exact for both), so that a P1 field's are exact: phi / (4 pi) times what
// it misses of pi.
float lebedev_current_correction(float phi) {
  const float rule = 4.0f * PI * (1.0f / 15.0f + 0.3f / sqrt(3.0f));
  return phi * (PI - rule) / (4.0f * PI);
}

#endif

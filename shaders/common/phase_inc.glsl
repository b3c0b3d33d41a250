// Phase functions (1/sr). Convention: mu = dot(view ray direction, direction towards the light),
// so mu = 1 when looking straight at the sun: light passing straight on to the eye (forward
// scattering). With that convention every lobe below peaks at mu = 1 for g > 0.
#ifndef NEPHELE_PHASE_INC
#define NEPHELE_PHASE_INC

// Henyey-Greenstein (seed 000, formula 1.8); g in (-1, 1), integrates to 1 over the sphere.
float henyey_greenstein(float g, float mu) {
  float gg = g * g;
  return (1.0f / (4.0f * PI)) * (1.0f - gg) / pow(max(1.0f + gg - 2.0f * g * mu, 1e-6f), 1.5f);
}

// Two HG lobes (seed 000, listing B.2): `weight` forward lobe g_forward, the rest g_backward.
float dual_lobe_hg(float g_forward, float g_backward, float weight, float mu) {
  return mix(henyey_greenstein(g_backward, mu), henyey_greenstein(g_forward, mu), weight);
}

// Rayleigh phase, 3/(16 pi) (1 + mu^2). (Seed 000 formula 1.12 prints 3 pi/16 (1 + cos):
// a typesetting slip; this normalised form integrates to 1.)
float rayleigh_phase(float mu) { return 3.0f / (16.0f * PI) * (1.0f + mu * mu); }

// Cornette-Shanks Mie phase (seed 000 formula 1.13, with the (1 - g^2) numerator of the
// original paper), normalised to 1 over the sphere.
float cornette_shanks_phase(float g, float mu) {
  float gg = g * g;
  return 3.0f / (8.0f * PI) * (1.0f - gg) * (1.0f + mu * mu) /
         ((2.0f + gg) * pow(max(1.0f + gg - 2.0f * g * mu, 1e-6f), 1.5f));
}

// The Cornette-Shanks phase's Legendre moments lambda_l = 2 pi integral of p(mu) P_l(mu) dmu
// for l = 0, 1, 2: by the Funk-Hecke theorem, scattering an incident radiance field through
// the phase function scales its spherical harmonics of degree l by lambda_l. The phase is
// Henyey-Greenstein's (moments g^l) times 3 (1 + mu^2) / (2 (2 + g^2)); mu^2 P_l expands by
// Legendre's recurrence into P_(l-2), P_l and P_(l+2). g = 0 gives Rayleigh's (1, 0, 1/10).
vec3 cornette_shanks_moments(float g) {
  float g2 = g * g;
  float scale = 3.0f / (2.0f * (2.0f + g2));
  float l1 = scale * (1.6f * g + 0.4f * g2 * g);
  float l2 = scale * ((32.0f / 21.0f) * g2 + (12.0f / 35.0f) * g2 * g2 + 2.0f / 15.0f);
  return vec3(1.0f, l1, l2);
}

#endif

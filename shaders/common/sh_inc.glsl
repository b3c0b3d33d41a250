// Real spherical harmonics of bands 0 to 2 (nine functions): the sky's light given to a host
// (host_lighting.comp, nephele::HostLighting) and the multiple-scattering field's six even ones
// (atmosphere_lut_inc.glsl). Pure; compiled as C++ too (render/glsl.h). The includer includes
// math_inc.glsl.
// Order (l, m) = (0, 0), (1, -1), (1, 0), (1, 1), (2, -2), (2, -1), (2, 0), (2, 1), (2, 2), with
// Y_1,-1 ~ y, Y_1,0 ~ z, Y_1,1 ~ x (Ramamoorthi and Hanrahan 2001, their constants).
#ifndef NEPHELE_SH_INC
#define NEPHELE_SH_INC

struct Sh9 {
  float y[9];
};

Sh9 sh9_basis(vec3 d) {
  Sh9 s;
  s.y[0] = 0.2820948f;
  s.y[1] = 0.4886025f * d.y;
  s.y[2] = 0.4886025f * d.z;
  s.y[3] = 0.4886025f * d.x;
  s.y[4] = 1.0925484f * d.x * d.y;
  s.y[5] = 1.0925484f * d.y * d.z;
  s.y[6] = 0.3153916f * (3.0f * d.z * d.z - 1.0f);
  s.y[7] = 1.0925484f * d.x * d.z;
  s.y[8] = 0.5462742f * (d.x * d.x - d.y * d.y);
  return s;
}

// The clamped cosine's coefficient for function k: irradiance E(n) = sum_k A_k L_k Y_k(n),
// A = pi, 2 pi / 3, pi / 4 for bands 0, 1, 2.
float sh9_cosine_lobe(int k) { return k == 0 ? PI : k < 4 ? 2.0f * PI / 3.0f : 0.25f * PI; }

#endif

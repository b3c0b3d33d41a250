// Clouds made of water droplets (issue 42; clouds.optics = "droplets"): extinction from the
// liquid water content and the droplets' effective radius, their albedo, and a fitted Mie phase
// function. Pure functions, shared by the passes and the CPU (render/glsl.h); tests in
// tests/unit/droplets_test.cpp. Convention for mu as in phase_inc.glsl.
#ifndef NEPHELE_DROPLETS_INC
#define NEPHELE_DROPLETS_INC

// sigma_t (1/m) of droplets of effective radius r_eff holding `water_g_m3` of liquid water per
// m^3: each droplet's extinction cross-section is twice its geometric one (Q_ext = 2 for
// droplets much larger than the wavelength), so sigma_t = 2 pi integral r^2 n(r) dr and, with
// LWC = 4/3 pi rho_w integral r^3 n(r) dr and r_eff = integral r^3 n / integral r^2 n,
// sigma_t = 3 LWC / (2 rho_w r_eff); with LWC in g/m^3, rho_w = 1e6 g/m^3 and r_eff in um
// that is 1.5 LWC / r_eff.
float droplet_extinction_per_m(float water_g_m3, float radius_um) {
  return 1.5f * water_g_m3 / radius_um;
}

// The single-scattering albedo of water droplets at 550 nm: weakly absorbing spheres far larger
// than the wavelength absorb Q_abs = 4 x kappa (n^3 - (n^2 - 1)^1.5) / n of their cross-section
// (geometric optics), x = 2 pi r / lambda the size parameter, n = 1.333 and kappa = 1.96e-9
// water's refractive index (Hale and Querry 1973): with Q_ext = 2, 1 - omega = 2.52 x kappa,
// 5.6e-7 for r_eff = 10 um.
float droplet_albedo(float radius_um) {
  float x = 2.0f * PI * radius_um / 0.55f;
  return 1.0f - 2.52f * x * 1.96e-9f;
}

// Draine's phase function (Draine 2003): Henyey-Greenstein times (1 + alpha mu^2), normalised;
// alpha = 1 and g = 0 give Rayleigh's.
float draine_phase(float g, float alpha, float mu) {
  float gg = g * g;
  return (1.0f / (4.0f * PI)) * (1.0f - gg) / pow(max(1.0f + gg - 2.0f * g * mu, 1e-6f), 1.5f) *
         (1.0f + alpha * mu * mu) / (1.0f + alpha * (1.0f + 2.0f * gg) / 3.0f);
}

// The Mie phase function of a cloud's droplet size distribution fitted by droplet diameter d
// (um, 5 <= d <= 50) as Jendersie and d'Eon 2023 ("An Approximate Mie Scattering Function for
// Fog and Cloud Rendering"): a Henyey-Greenstein lobe for the diffraction peak and a Draine
// lobe for the rest. Returns (x) the HG lobe's g, (y) the Draine lobe's g, (z) its alpha,
// (w) its weight.
vec4 mie_fit(float diameter_um) {
  float d = diameter_um;
  return vec4(exp(-0.0990567f / (d - 1.67154f)), exp(-2.20679f / (d + 3.91029f) - 0.428934f),
              exp(3.62489f - 8.29288f / (d + 5.52825f)),
              exp(-0.599085f / (d - 0.641583f) - 0.665888f));
}

// The fitted Mie phase function (1/sr) of mie_fit's parameters.
float mie_phase(vec4 fit, float mu) {
  return mix(henyey_greenstein(fit.x, mu), draine_phase(fit.y, fit.z, mu), fit.w);
}

// Its mean cosine: HG's is g; Draine's g (1 + alpha (3 + 2 g^2) / 5) / (1 + alpha (1 + 2 g^2) / 3).
float mie_mean_cosine(vec4 fit) {
  float g = fit.y, gg = g * g;
  float draine = g * (1.0f + fit.z * (3.0f + 2.0f * gg) / 5.0f) / (1.0f + fit.z * (1.0f + 2.0f * gg) / 3.0f);
  return mix(fit.x, draine, fit.w);
}

// A value per genus blended by cloud type as the shapes are (0 stratus, 0.25 stratocumulus,
// 0.5 altocumulus, 0.75 cumulus, 1 cumulonimbus): `st_to_cu` the first four, `cb` the last.
float cloud_genus_blend(float type, vec4 st_to_cu, float cb) {
  float x = clamp(type, 0.0f, 1.0f) * 4.0f;
  float lo = x < 1.0f ? st_to_cu.x : (x < 2.0f ? st_to_cu.y : (x < 3.0f ? st_to_cu.z : st_to_cu.w));
  float hi = x < 1.0f ? st_to_cu.y : (x < 2.0f ? st_to_cu.z : (x < 3.0f ? st_to_cu.w : cb));
  return mix(lo, hi, x - min(floor(x), 3.0f));
}

#endif

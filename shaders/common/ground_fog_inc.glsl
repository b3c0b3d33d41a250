// A ground-fog layer (the "ground fog" of simulator image generators): a slab of fog between a
// base and a top altitude (m above mean sea level, as nephele's other altitudes), of a given
// visibility inside, whose density fades to zero over a soft top. Its optical depth along a
// straight ray has a closed form, so a render pass needs no ray marching through it.
//
// Geometry: flat earth. A fog layer is a few hundred metres thick and, at the visibilities of
// fog (under 1 km, WMO), opaque after a few kilometres; over 10 km the earth's curvature
// lowers the ground by d^2 / (2 R) = 8 m. The caller may pass altitudes taken on the sphere
// (z = |p| - R at each end of a segment): the segment's altitude is then taken as linear along
// it. Only the sun's slant path, long near the horizon, is taken on the sphere.
//
// The layer: density 0 below the base (a lifted fog's clear air under it; a base at or below
// the terrain gives fog down to the ground, where the rays end), 1 from the base to
// top - soft, then falling as a smoothstep to 0 at the top: with w = (top - z) / soft, the
// height below the top in units of the softness, density = w^2 (3 - 2 w), continuous and with
// a continuous slope at both ends of the fade. Zero softness is a hard top (density 1 up to
// and including the top).
//
// Fog droplets (micrometres, in visible light) scatter almost without absorbing: a
// single-scattering albedo of about 1. Pure functions, also compiled as C++ (src/render/glsl.h
// conventions; needs math_inc.glsl's saturate and KOSCHMIEDER).
#ifndef NEPHELE_GROUND_FOG_INC
#define NEPHELE_GROUND_FOG_INC

struct GroundFog {
  float base_m;         // altitude of the layer's bottom (m above mean sea level)
  float top_m;          // altitude of its top, >= base_m
  float soft_m;         // thickness of the fade below the top, in [0, top_m - base_m]
  float sigma_t_per_m;  // extinction in the layer's body (density 1)
  float albedo;         // single-scattering albedo sigma_s / sigma_t (about 1 for fog)
};

// Extinction (1/m) that gives the visibility `visibility_m` (Koschmieder): 3.912 / V. The fog's
// own, the air's Rayleigh extinction (1.2e-5 per m at 550 nm) left aside: under 0.5% of a fog's
// (V < 1 km). A visibility under 1 mm is taken as 1 mm.
float ground_fog_sigma_t_per_m(float visibility_m) {
  return KOSCHMIEDER / max(visibility_m, 1e-3f);
}

// A layer from its weather description. A top below the base gives an empty layer (top =
// base); the softness is clamped to [0, thickness], so the fade starts at the base at most.
GroundFog ground_fog_layer(float base_m, float top_m, float soft_m, float visibility_m,
                           float albedo) {
  GroundFog f;
  f.base_m = base_m;
  f.top_m = max(top_m, base_m);
  f.soft_m = clamp(soft_m, 0.0f, f.top_m - base_m);
  f.sigma_t_per_m = ground_fog_sigma_t_per_m(visibility_m);
  f.albedo = albedo;
  return f;
}

// w = (top - z) / soft clamped to [0, 1]: 1 at and below top - soft, 0 at and above the top.
// A hard top (soft 0) gives 1 up to and including the top, 0 above it.
float ground_fog_fade_w(GroundFog f, float altitude_m) {
  if (f.soft_m > 0.0f) return saturate((f.top_m - altitude_m) / f.soft_m);
  return altitude_m <= f.top_m ? 1.0f : 0.0f;
}

// Relative density (0 to 1) at altitude z: 0 below the base, 1 in the body, w^2 (3 - 2 w) in
// the fade (1 - smoothstep(top - soft, top, z)).
float ground_fog_density(GroundFog f, float altitude_m) {
  if (altitude_m < f.base_m) return 0.0f;
  float w = ground_fog_fade_w(f, altitude_m);
  return w * w * (3.0f - 2.0f * w);
}

// Mean of the fade's density w^2 (3 - 2 w) over w in [a, b] (either order; a = b: its value):
// (integral of 3 w^2 - 2 w^3 from a to b) / (b - a), with the differences of cubes and of
// fourth powers divided out, so that no difference of nearby numbers is divided by a small one.
float ground_fog_fade_mean(float a, float b) {
  return (a * a + a * b + b * b) - 0.5f * (a + b) * (a * a + b * b);
}

// Integral of the density over altitude from lo_m to hi_m (lo_m <= hi_m), in metres of fog at
// density 1: the overlaps with the body and with the fade, each a difference of clamped
// altitudes (exact for nearby ones), the fade's weighted by its mean density there.
float ground_fog_integral_m(GroundFog f, float lo_m, float hi_m) {
  float fade_bottom_m = f.top_m - f.soft_m;
  float body = clamp(hi_m, f.base_m, fade_bottom_m) - clamp(lo_m, f.base_m, fade_bottom_m);
  float fade = clamp(hi_m, fade_bottom_m, f.top_m) - clamp(lo_m, fade_bottom_m, f.top_m);
  if (fade <= 0.0f) return body;
  return body + fade * ground_fog_fade_mean(ground_fog_fade_w(f, lo_m), ground_fog_fade_w(f, hi_m));
}

// The profile's cumulative integral C(z) = integral of the density from below the base to z:
// 0 below the base, (top - soft - base) + soft / 2 above the top.
float ground_fog_cumulative_m(GroundFog f, float altitude_m) {
  return ground_fog_integral_m(f, f.base_m, max(altitude_m, f.base_m));
}

// The column above z, integral of the density from z to the top: C(top) - C(z), computed
// without that difference (accurate near the top, where it is small).
float ground_fog_column_above_m(GroundFog f, float altitude_m) {
  return ground_fog_integral_m(f, min(altitude_m, f.top_m), f.top_m);
}

// Mean density along a straight segment from altitude z0 to z1 (altitude linear along it):
// (C(z1) - C(z0)) / (z1 - z0), either order. A segment under a micrometre of altitude (a
// horizontal ray; |z1 - z0| below float's resolution on a GPU that flushes denormals) takes
// the density at its middle, the limit as z1 -> z0.
float ground_fog_mean_density(GroundFog f, float z0_m, float z1_m) {
  float lo = min(z0_m, z1_m);
  float hi = max(z0_m, z1_m);
  float dz = hi - lo;
  if (dz < 1e-6f) return ground_fog_density(f, 0.5f * (lo + hi));
  return ground_fog_integral_m(f, lo, hi) / dz;
}

// Optical depth of the fog along a straight segment of length `length_m` from altitude z0 to
// z1: sigma_t L (C(z1) - C(z0)) / (z1 - z0); sigma_t L density(z0) for a horizontal one.
float ground_fog_optical_depth(GroundFog f, float z0_m, float z1_m, float length_m) {
  return f.sigma_t_per_m * length_m * ground_fog_mean_density(f, z0_m, z1_m);
}

// The fog in front of a surface at distance `length_m` along a ray from altitude z0 to z1, lit
// uniformly inside the fog (in-scattered radiance L_in per unit sigma_s, the same everywhere):
// rgb the light it adds per unit of L_in, albedo (1 - T), exact for any density along the ray
// (the integral of sigma_s(t) T(t) dt is albedo (1 - T)); a the transmittance T = exp(-tau).
// The convention of compose.comp's air_in_front: seen = surface a + rgb L_in.
vec4 ground_fog_in_front(GroundFog f, float z0_m, float z1_m, float length_m) {
  float transmittance = exp(-ground_fog_optical_depth(f, z0_m, z1_m, length_m));
  return vec4(vec3(f.albedo * (1.0f - transmittance)), transmittance);
}

// Integral of g(x) / sqrt(mu^2 + b x) over x in [x0, x1] (0 <= x0 <= x1), for g the fog's
// density at altitude z + x (constant 1 in the body; the fade's cubic when `fade`): with
// s = sqrt(mu^2 + b x), dx / s = 2 ds / b, a polynomial in s of degree 6 at most, which
// 4-point Gauss-Legendre integrates exactly. 2 (s1 - s0) / b = 2 (x1 - x0) / (s0 + s1) and the
// nodes' x = x0 + (x1 - x0) tau (2 s0 + (s1 - s0) tau) / (s0 + s1) avoid s^2 - mu^2.
float ground_fog_slant_piece(GroundFog f, float z_m, float mu, float b, float x0, float x1,
                             bool fade) {
  if (x1 <= x0) return 0.0f;
  float s0 = sqrt(mu * mu + b * x0);
  float s1 = sqrt(mu * mu + b * x1);
  float scale = (x1 - x0) / (s0 + s1);  // (s1 - s0) / b
  if (!fade) return 2.0f * scale;
  float ds = b * scale;  // s1 - s0
  float mean = 0.0f;
  for (int i = 0; i < 4; ++i) {
    // Gauss-Legendre on [0, 1]: nodes (1 +- 0.33998) / 2 and (1 +- 0.86114) / 2.
    float node = i < 2 ? 0.3399810436f : 0.8611363116f;
    float weight = i < 2 ? 0.3260725774f : 0.1739274226f;
    float tau = 0.5f + ((i & 1) == 0 ? -0.5f : 0.5f) * node;
    float x = x0 + scale * tau * (2.0f * s0 + ds * tau);
    mean += weight * ground_fog_density(f, z_m + x);
  }
  return 2.0f * scale * mean;
}

// Optical depth of the fog to the sun from altitude z, for the sun at elevation sine mu
// (`sun_sin_elevation`) on a planet of radius `planet_radius_m`. A straight ray from radius
// r = R + z climbs to r + x after a distance t with (r + x)^2 = r^2 + 2 r mu t + t^2, so
// dt / dx = (r + x) / sqrt(r^2 mu^2 + x (2 r + x)) ~ 1 / sqrt(mu^2 + 2 x / r) (x << r: within
// 3 x / 4 r, 4e-5 for a 300 m layer), and
//   tau = sigma_t integral over x of density(z + x) / sqrt(mu^2 + 2 x / r) dx,
// in closed form per piece of the profile (ground_fog_slant_piece). A high sun gives the
// flat-earth column / mu; at the horizon it stays finite (the column of a uniform layer of
// thickness h times sqrt(r / 2 h)). A sun below the horizon is taken at the horizon (the
// atmosphere's transmittance darkens it). Below the base it is computed from the base: the
// clear air under the fog does not dim the sun.
float ground_fog_sun_optical_depth(GroundFog f, float altitude_m, float sun_sin_elevation,
                                   float planet_radius_m) {
  float z = clamp(altitude_m, f.base_m, f.top_m);
  float h = f.top_m - z;
  if (h <= 0.0f) return 0.0f;
  float mu = saturate(sun_sin_elevation);
  float b = 2.0f / (planet_radius_m + z);
  float body_end = max(f.top_m - f.soft_m - z, 0.0f);
  return f.sigma_t_per_m * (ground_fog_slant_piece(f, z, mu, b, 0.0f, body_end, false) +
                            ground_fog_slant_piece(f, z, mu, b, body_end, h, true));
}

// Transmittance of the fog to the sunlight at altitude z: exp(-ground_fog_sun_optical_depth).
float ground_fog_sun_transmittance(GroundFog f, float altitude_m, float sun_sin_elevation,
                                   float planet_radius_m) {
  return exp(-ground_fog_sun_optical_depth(f, altitude_m, sun_sin_elevation, planet_radius_m));
}

#endif

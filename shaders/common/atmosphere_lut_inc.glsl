// The physically based sky of Hillaire 2020 ("A Scalable and Production Ready Sky and
// Atmosphere Rendering Technique", EGSR): Rayleigh and Mie scattering (Mie with absorption),
// ozone absorption, single scattering plus all orders of multiple scattering, from the ground to
// space, on a spherical planet.
//   - Transmittance LUT (section 4, Bruneton's parameterisation): transmittance from a point at
//     radius r to the top of the atmosphere along a direction at cosine mu from the zenith.
//   - Multiple-scattering LUT (section 5.5.2): Psi_ms(altitude, sun zenith), the radiance that
//     all orders of scattering >= 2 add per unit scattering coefficient, from the second order
//     computed with an isotropic phase over 64 directions and the geometric series 1/(1 - f_ms)
//     of its transfer factor f_ms.
//   - The multiple-scattering light field (below, MS_ANGULAR, the default): the light scattered
//     at least once, as spherical harmonics at each altitude and sun zenith angle, scattered
//     towards the eye through the true phase functions instead of Psi_ms's isotropic one.
//   - sky_hillaire(): the radiance along a view ray (section 5.3 and 5.4), integrated with the
//     energy-conserving step of section 5.6.3, single scattering lit through the transmittance
//     and multiple scattering from Psi_ms. With `exact` true it uses no table at all: the sun's
//     transmittance is integrated numerically and Psi_ms evaluated in place. That is the
//     brute-force reference the tables are checked against (on the GPU the reference is split
//     in two passes, sky_reference_psi.comp and sky_reference.comp: lavapipe ends any shader
//     invocation after 65535 loop iterations in all, and one exact pixel takes about a million).
// Radiances are per unit solar illuminance at the top of the atmosphere (1/sr).
// Pure functions; GLSL passes the tables as sampler2D parameters, and src/render/glsl.h gives C++
// a sampler2D of its own, so the CPU computes the same values from tables read back.
#ifndef NEPHELE_ATMOSPHERE_LUT_INC
#define NEPHELE_ATMOSPHERE_LUT_INC

#include "common/sh_inc.glsl"

const int TRANSMITTANCE_LUT_W = 256;  // mu
const int TRANSMITTANCE_LUT_H = 64;   // r
const int MS_LUT_W = 64;              // sun zenith cosine (log Psi_ms bends most along it)
const int MS_LUT_H = 32;              // altitude
const int MS_DIRECTIONS_SQRT = 8;     // 64 directions per Psi_ms (Hillaire's count)
const int MS_SAMPLES = 20;            // samples along each of them
const int TRANSMITTANCE_SAMPLES = 64;  // samples per transmittance LUT texel
const float MS_LUT_FLOOR = 1e-20f;      // Psi_ms stored as log(Psi_ms + floor)
const int EXACT_SUN_SAMPLES = 16;      // sun transmittance integrated in place (reference)
// The multiple-scattering light field (ms_field_texel): its table's size in sun zenith cosine
// and altitude, its spherical harmonics (degrees 0-2 even in y: 6 per colour, one block of
// MS_FIELD_W columns each), the directions and steps each texel integrates, and the
// iterations that make it consistent with itself (ms_field_texel).
const int MS_FIELD_W = 64;
const int MS_FIELD_H = 32;
const int MS_FIELD_COEFFS = 6;
const int MS_FIELD_THETA = 12;  // bands in cos(zenith angle)
const int MS_FIELD_PHI = 6;     // azimuths over the half circle y >= 0 (the field is even in y)
const int MS_FIELD_SAMPLES = 16;
const int MS_FIELD_ITERATIONS = 3;
// How multiple scattering reaches a view ray (FrameParams::sky_options.x).
const int MS_ISOTROPIC = 0;  // Hillaire 2020: Psi_ms, scattered with an isotropic phase
const int MS_ANGULAR = 1;    // the light field's spherical harmonics through the true phases
// (MS_ANGULAR + 1 reads the field's other half, where its iterations leave an earlier one.)

// Maps [0, 1] onto texel centres of an n-texel axis and back (Bruneton 2017): the ends of the
// range are sampled exactly rather than half a texel in.
float unit_to_texcoord(float x, float n) { return 0.5f / n + x * (1.0f - 1.0f / n); }
float texcoord_to_unit(float u, float n) { return (u - 0.5f / n) / (1.0f - 1.0f / n); }

// Transmittance LUT coordinates of (r, mu), Bruneton 2017 section 4.1: x_r = rho / H with rho the
// distance to the horizon, x_mu the distance to the top of the atmosphere between its least
// (straight up) and greatest (towards the horizon) values. Directions below the horizon clamp
// to the horizon: the caller has found them blocked by the planet.
vec2 transmittance_lut_uv(Atmosphere a, float r, float mu) {
  float R = a.planet_radius_m;
  float top = a.top_radius_m;
  float H = sqrt((top - R) * (top + R));
  float h = clamp(r - R, 0.0f, top - R);
  r = R + h;
  float rho = sqrt(h * (r + R));
  float disc = (top - r) * (top + r) + r * r * mu * mu;
  float d = max(-r * mu + sqrt(max(disc, 0.0f)), 0.0f);
  float d_min = top - r;
  float d_max = rho + H;
  float x_mu = d_max > d_min ? saturate((d - d_min) / (d_max - d_min)) : 0.0f;
  return vec2(unit_to_texcoord(x_mu, float(TRANSMITTANCE_LUT_W)),
              unit_to_texcoord(rho / H, float(TRANSMITTANCE_LUT_H)));
}

// The inverse: (r, mu) of LUT coordinates.
vec2 transmittance_lut_r_mu(Atmosphere a, vec2 uv) {
  float R = a.planet_radius_m;
  float top = a.top_radius_m;
  float H = sqrt((top - R) * (top + R));
  float x_mu = saturate(texcoord_to_unit(uv.x, float(TRANSMITTANCE_LUT_W)));
  float x_r = saturate(texcoord_to_unit(uv.y, float(TRANSMITTANCE_LUT_H)));
  float rho = H * x_r;
  float r = sqrt(rho * rho + R * R);
  float d_min = top - r;
  float d_max = rho + H;
  float d = d_min + x_mu * (d_max - d_min);
  float mu = d <= 0.0f ? 1.0f : ((top - r) * (top + r) - d * d) / (2.0f * r * d);
  return vec2(r, clamp(mu, -1.0f, 1.0f));
}

// One transmittance LUT texel: integrated to the top, past the horizon, never into the ground.
vec3 transmittance_lut_texel(Atmosphere a, vec2 uv) {
  vec2 r_mu = transmittance_lut_r_mu(a, uv);
  vec3 pos = vec3(0.0f, 0.0f, r_mu.x);
  vec3 dir = vec3(sqrt(max(1.0f - r_mu.y * r_mu.y, 0.0f)), 0.0f, r_mu.y);
  return exp(-atmosphere_optical_depth_to_top(a, pos, dir, TRANSMITTANCE_SAMPLES));
}

// Transmittance from `pos` to the light along unit `dir`: 0 when the planet is in the way. From
// space the light enters the atmosphere where the ray does. `exact` integrates it in place.
vec3 transmittance_to_light(Atmosphere a, sampler2D lut, bool exact, vec3 pos, vec3 dir) {
  // The planet is in the way below the geometric horizon, cos = -sqrt(1 - R^2 / r^2); from a
  // point at or below the ground (float rounding at the end of a ground ray) below the local
  // horizontal. (A ray_sphere test lets a point a millimetre underground see the sun through
  // the planet.)
  float r = length(pos);
  float h = r - a.planet_radius_m;
  float mu = dot(pos, dir) / r;
  float horizon = h <= 0.0f ? 0.0f : -sqrt(h * (r + a.planet_radius_m)) / r;
  if (mu < horizon) return vec3(0.0f);
  if (dot(pos, pos) > a.top_radius_m * a.top_radius_m) {
    vec2 top = ray_sphere(pos, dir, a.top_radius_m);
    if (top.x <= 0.0f) return vec3(1.0f);
    pos += dir * top.x;
  }
  if (exact) return exp(-atmosphere_optical_depth_to_top(a, pos, dir, EXACT_SUN_SAMPLES));
  r = length(pos);
  return vec3(textureLod(lut, transmittance_lut_uv(a, r, dot(pos, dir) / r), 0.0f));
}

// Multiple-scattering LUT coordinates: u the cosine of the sun's zenith angle, v the altitude.
vec2 ms_lut_uv(Atmosphere a, float altitude_m, float cos_sun_zenith) {
  return vec2(unit_to_texcoord(saturate(0.5f + 0.5f * cos_sun_zenith), float(MS_LUT_W)),
              unit_to_texcoord(saturate(altitude_m / (a.top_radius_m - a.planet_radius_m)),
                               float(MS_LUT_H)));
}

// Psi_ms at `pos` for the sun in unit direction `sun` (Hillaire 2020, equations 5-10), with a
// Lambertian ground of albedo `ground_albedo`: the second order of scattering L_2 and the
// transfer factor f_ms, both averaged over MS_DIRECTIONS_SQRT^2 stratified directions with an
// isotropic phase, give Psi_ms = L_2 / (1 - f_ms).
vec3 ms_psi(Atmosphere a, sampler2D t_lut, bool exact, vec3 pos, vec3 sun, float ground_albedo) {
  vec3 l2 = vec3(0.0f);
  vec3 f_ms = vec3(0.0f);
  const float ISOTROPIC = 1.0f / (4.0f * PI);
  // Directions around the local zenith: any frame will do for a uniform sphere.
  vec3 up = normalize(pos);
  vec3 e1 = normalize(abs(up.x) < 0.9f ? cross(up, vec3(1.0f, 0.0f, 0.0f))
                                      : cross(up, vec3(0.0f, 1.0f, 0.0f)));
  vec3 e2 = cross(up, e1);
  for (int i = 0; i < MS_DIRECTIONS_SQRT; ++i) {
    for (int j = 0; j < MS_DIRECTIONS_SQRT; ++j) {
      float cos_t = 1.0f - 2.0f * (float(i) + 0.5f) / float(MS_DIRECTIONS_SQRT);
      float sin_t = sqrt(max(1.0f - cos_t * cos_t, 0.0f));
      float phi = 2.0f * PI * (float(j) + 0.5f) / float(MS_DIRECTIONS_SQRT);
      vec3 dir = sin_t * (cos(phi) * e1 + sin(phi) * e2) + cos_t * up;
      vec2 ground = ray_sphere(pos, dir, a.planet_radius_m);
      vec2 top = ray_sphere(pos, dir, a.top_radius_m);
      bool hits_ground = ground.x > 0.0f;
      float t_max = hits_ground ? ground.x : max(top.y, 0.0f);
      vec3 throughput = vec3(1.0f);
      float dt = t_max / float(MS_SAMPLES);
      for (int k = 0; k < MS_SAMPLES; ++k) {
        vec3 x = pos + dir * ((float(k) + 0.5f) * dt);
        AtmosphereMedium m = atmosphere_medium(a, length(x) - a.planet_radius_m);
        vec3 sigma_s = m.scattering_r + vec3(m.scattering_m);
        vec3 step_t = exp(-m.extinction * dt);
        // Energy-conserving integration over the step (Hillaire 2015, 2020 section 5.6.3).
        vec3 weight = throughput * (vec3(1.0f) - step_t) / max(m.extinction, vec3(1e-12f));
        vec3 t_sun = transmittance_to_light(a, t_lut, exact, x, sun);
        l2 += weight * sigma_s * t_sun * ISOTROPIC;
        f_ms += weight * sigma_s;
        throughput *= step_t;
      }
      if (hits_ground) {
        vec3 g = pos + dir * ground.x;
        vec3 n = normalize(g);
        vec3 t_sun = transmittance_to_light(a, t_lut, exact, n * (a.planet_radius_m + 1.0f), sun);
        l2 += throughput * t_sun * max(dot(n, sun), 0.0f) * ground_albedo / PI;
      }
    }
  }
  float count = float(MS_DIRECTIONS_SQRT * MS_DIRECTIONS_SQRT);
  l2 /= count;
  f_ms /= count;
  return l2 / max(vec3(1.0f) - f_ms, vec3(1e-3f));
}

// One multiple-scattering LUT texel: log Psi_ms at the texel's altitude and sun zenith angle.
// The log, because Psi_ms falls by orders of magnitude as the sun sets: read linearly, a texel
// spanning the terminator overestimated the twilight sky by 3x near the ground; interpolated in
// log it is right within a few %.
vec3 ms_lut_texel(Atmosphere a, sampler2D t_lut, vec2 uv, float ground_albedo) {
  float cos_sun = 2.0f * saturate(texcoord_to_unit(uv.x, float(MS_LUT_W))) - 1.0f;
  float altitude_m =
      saturate(texcoord_to_unit(uv.y, float(MS_LUT_H))) * (a.top_radius_m - a.planet_radius_m);
  vec3 pos = vec3(0.0f, 0.0f, a.planet_radius_m + max(altitude_m, 1.0f));
  vec3 sun = vec3(sqrt(max(1.0f - cos_sun * cos_sun, 0.0f)), 0.0f, cos_sun);
  return log(ms_psi(a, t_lut, false, pos, sun, ground_albedo) + vec3(MS_LUT_FLOOR));
}

// Psi_ms at `pos`: from the LUT, or (`exact`) evaluated in place.
vec3 multiple_scattering_at(Atmosphere a, sampler2D t_lut, sampler2D ms_lut, bool exact, vec3 pos,
                            vec3 sun, float ground_albedo) {
  if (exact) return ms_psi(a, t_lut, true, pos, sun, ground_albedo);
  float r = length(pos);
  vec2 uv = ms_lut_uv(a, r - a.planet_radius_m, dot(pos, sun) / r);
  vec3 psi = exp(vec3(textureLod(ms_lut, uv, 0.0f)));
  return max(psi - vec3(MS_LUT_FLOOR), vec3(0.0f));
}

// The multiple-scattering light field (the default, MS_ANGULAR). Psi_ms treats the light that
// reaches a point after one or more scatterings as if it came equally from every direction,
// and scatters it with an isotropic phase. It does not: by day it is brightest from near the
// horizon and around the sun, and Rayleigh's phase sends horizontal light on horizontally, so
// the horizon was 11-14% too dark against the zenith and the sunset horizon too red. The field
// is that light itself: at each altitude and sun zenith angle, the sky seen from the point,
// projected on spherical harmonics of degree <= 2 in a frame with z up and x towards the sun's
// azimuth (the field is even in y: 6 functions), iterated until the sky it is computed from
// scatters the field itself (ms_field_texel). A view ray scatters it through the Rayleigh and
// Cornette-Shanks phases exactly (Funk-Hecke: degree l scaled by the phase's Legendre moment
// lambda_l; Rayleigh's phase has no degree above 2, so for air nothing is truncated).

// The 6 real orthonormal spherical harmonics even in y, at unit `d` in the field's frame:
// Y00, Y10 (z), Y11 (x) and Y20, Y21 (xz), Y22 (x^2 - y^2).
struct ShBasis {
  vec3 low;   // Y00, Y10, Y11
  vec3 high;  // Y20, Y21, Y22
};

ShBasis sh_basis(vec3 d) {
  Sh9 y = sh9_basis(d);
  ShBasis b;
  b.low = vec3(y.y[0], y.y[2], y.y[3]);
  b.high = vec3(y.y[6], y.y[7], y.y[8]);
  return b;
}

// The field's frame at `pos` for the sun in unit direction `sun`: rows x (towards the sun's
// azimuth), y, z (up). With the sun at the zenith any azimuth will do.
mat3 ms_field_frame(vec3 pos, vec3 sun) {
  vec3 up = normalize(pos);
  vec3 x = sun - dot(sun, up) * up;
  if (dot(x, x) < 1e-12f) x = abs(up.x) < 0.9f ? vec3(1.0f, 0.0f, 0.0f) : vec3(0.0f, 1.0f, 0.0f);
  x = normalize(x - dot(x, up) * up);
  return mat3(x, cross(up, x), up);  // columns; transpose(frame) * d is d in the frame
}

// The field's table coordinates in [0, 1]^2: x the sun's zenith cosine, linear; y the
// altitude, as the square root of its share of the atmosphere's height (the field changes most
// in the lowest kilometres, where the air is densest).
vec2 ms_field_unit(Atmosphere a, float altitude_m, float cos_sun) {
  return vec2(saturate(0.5f + 0.5f * cos_sun),
              sqrt(saturate(altitude_m / (a.top_radius_m - a.planet_radius_m))));
}

// Texture coordinates of coefficient block `k` of half `half` of the field's texture (see
// ms_field_texel) at table coordinates `unit`: each block is MS_FIELD_W columns wide, each half
// MS_FIELD_H rows high, and both are read within their texel centres, so the filter never mixes
// two coefficients or two halves.
vec2 ms_field_texcoord(vec2 unit, int k, int half_index) {
  float u = unit_to_texcoord(unit.x, float(MS_FIELD_W));
  float v = unit_to_texcoord(unit.y, float(MS_FIELD_H));
  return vec2((float(k) + u) / float(MS_FIELD_COEFFS), 0.5f * (float(half_index) + v));
}

// The spherical-harmonic coefficients c_k (k as sh_basis orders them) at table coordinates
// `unit`, from their stored form (block 0 log of F0 = c00 Y00 plus MS_LUT_FLOOR, blocks 1-5
// c_k / c00).
struct MsFieldCoefficients {
  vec3 c[MS_FIELD_COEFFS];
};

MsFieldCoefficients ms_field_read(sampler2D field, vec2 unit, int half_index) {
  MsFieldCoefficients f;
  vec3 f0 = max(exp(vec3(textureLod(field, ms_field_texcoord(unit, 0, half_index), 0.0f))) -
                    vec3(MS_LUT_FLOOR), vec3(0.0f));
  f.c[0] = f0 / 0.2820948f;
  for (int k = 1; k < MS_FIELD_COEFFS; ++k)
    f.c[k] = f.c[0] * vec3(textureLod(field, ms_field_texcoord(unit, k, half_index), 0.0f));
  return f;
}

// What multiple scattering adds per unit scattering coefficient at a point, for light
// scattered by air (Rayleigh) and by aerosols (Mie) towards the eye looking along `dir`.
struct MsScattering {
  vec3 rayleigh;
  vec3 mie;
};

// The field (half `half_index`) at `pos` scattered towards a view along unit `dir`.
MsScattering ms_field_scattering(Atmosphere a, sampler2D field, int half_index, vec3 pos,
                                 vec3 sun, vec3 dir) {
  float r = length(pos);
  MsFieldCoefficients f =
      ms_field_read(field, ms_field_unit(a, r - a.planet_radius_m, dot(pos, sun) / r), half_index);
  ShBasis y = sh_basis(transpose(ms_field_frame(pos, sun)) * dir);
  vec3 f0 = f.c[0] * y.low.x;
  vec3 f1 = f.c[1] * y.low.y + f.c[2] * y.low.z;
  vec3 f2 = f.c[3] * y.high.x + f.c[4] * y.high.y + f.c[5] * y.high.z;
  vec3 lambda_m = cornette_shanks_moments(a.mie_g);
  MsScattering s;
  s.rayleigh = max(f0 + 0.1f * f2, vec3(0.0f));
  s.mie = max(f0 + lambda_m.y * f1 + lambda_m.z * f2, vec3(0.0f));
  return s;
}

// The sky light on a horizontal surface at the ground, facing up, per unit illuminance (its
// irradiance over pi), from the field's half `half_index` at altitude 0 for the sun at cosine
// `cos_sun` from the zenith: the clamped cosine scales degree l by pi, 2 pi / 3 and pi / 4
// (Ramamoorthi and Hanrahan 2001); at the zenith only Y00, Y10 and Y20 are not 0.
vec3 ms_field_ground_sky(sampler2D field, int half_index, float cos_sun) {
  MsFieldCoefficients f = ms_field_read(field, vec2(saturate(0.5f + 0.5f * cos_sun), 0.0f),
                                        half_index);
  return max(0.2820948f * f.c[0] + (2.0f / 3.0f) * 0.4886025f * f.c[1] +
                 0.25f * 0.6307831f * f.c[3],
             vec3(0.0f));
}

// Psi_ms as MsScattering (isotropic: the same for air and aerosols).
MsScattering ms_isotropic(vec3 psi) {
  MsScattering s;
  s.rayleigh = psi;
  s.mie = psi;
  return s;
}

// Multiple scattering at `pos` towards a view along `dir`: Psi_ms for both (MS_ISOTROPIC, and
// always when `exact`), or the light field through the phases (MS_ANGULAR).
MsScattering multiple_scattering_towards(Atmosphere a, sampler2D t_lut, sampler2D ms_lut,
                                         sampler2D ms_field, int ms_mode, bool exact, vec3 pos,
                                         vec3 sun, vec3 dir, float ground_albedo) {
  if (ms_mode >= MS_ANGULAR && !exact)
    return ms_field_scattering(a, ms_field, ms_mode - MS_ANGULAR, pos, sun, dir);
  return ms_isotropic(multiple_scattering_at(a, t_lut, ms_lut, exact, pos, sun, ground_albedo));
}

// A view ray's stretch of air: from the eye (from space: where it enters the atmosphere) to the
// ground or the top. `length_m` < 0 when it misses the atmosphere.
struct SkyRay {
  vec3 origin;
  float length_m;
  bool hits_ground;
};

SkyRay sky_ray(Atmosphere a, vec3 eye, vec3 dir) {
  SkyRay ray;
  vec2 top = ray_sphere(eye, dir, a.top_radius_m);
  float t_start = max(top.x, 0.0f);
  vec2 ground = ray_sphere(eye, dir, a.planet_radius_m);
  ray.hits_ground = ground.x > 0.0f;
  ray.length_m = top.y <= 0.0f ? -1.0f : (ray.hits_ground ? ground.x : top.y) - t_start;
  ray.origin = eye + dir * t_start;
  return ray;
}

// Step i of n along a ray of `length_m`: its ends, spaced t = length (i / n)^2 (dense near the
// eye, Hillaire's distribution).
vec2 sky_step(float length_m, int i, int n) {
  float u0 = float(i) / float(n);
  float u1 = float(i + 1) / float(n);
  return vec2(length_m * u0 * u0, length_m * u1 * u1);
}

// In-scattering per metre at a point: single scattering (Rayleigh and Cornette-Shanks phases,
// the sun's transmittance `t_sun`) plus multiple scattering `ms`.
vec3 sky_source(AtmosphereMedium m, float phase_r, float phase_m, vec3 t_sun, MsScattering ms) {
  return (m.scattering_r * phase_r + vec3(m.scattering_m * phase_m)) * t_sun +
         m.scattering_r * ms.rayleigh + m.scattering_m * ms.mie;
}


// The ground seen at the end of a ray with transmittance `throughput` (sets ground_sun and adds
// the sky-lit part to radiance; see sky_hillaire).
SkySample sky_add_ground(Atmosphere a, sampler2D t_lut, bool exact, SkySample result, vec3 ground_m,
                         vec3 sun, float ground_albedo, vec3 sky_ambient) {
  // The ground point, lifted 1 m so its own sphere does not shadow it through rounding.
  vec3 nrm = normalize(ground_m);
  vec3 t_sun = transmittance_to_light(a, t_lut, exact, nrm * (a.planet_radius_m + 1.0f), sun);
  result.ground_sun = result.transmittance * ground_albedo / PI * t_sun * max(dot(nrm, sun), 0.0f);
  result.radiance += result.transmittance * ground_albedo * sky_ambient;
  result.ground_air_t = dot(result.transmittance, vec3(1.0f / 3.0f));
  result.transmittance = vec3(0.0f);
  return result;
}

// The sky along unit `dir` from `eye` (SkySample of atmosphere_inc.glsl): single and multiple
// scattering over `samples` steps (sky_step), integrated with the energy-conserving step, and a
// Lambertian ground of albedo `ground_albedo` lit by the sun (ground_sun, for the caller to
// shadow) and by sky radiance `sky_ambient` (per unit illuminance). Multiple scattering by
// `ms_mode` (MS_ISOTROPIC reads only ms_lut, MS_ANGULAR only ms_field).
SkySample sky_hillaire(Atmosphere a, sampler2D t_lut, sampler2D ms_lut, sampler2D ms_field,
                       int ms_mode, bool exact, vec3 eye, vec3 dir, vec3 sun, int samples,
                       float ground_albedo, vec3 sky_ambient) {
  SkySample result = sky_sample_start();
  SkyRay ray = sky_ray(a, eye, dir);
  if (ray.length_m < 0.0f) return result;  // looking away from the atmosphere, from space
  float mu = dot(dir, sun);
  float phase_r = rayleigh_phase(mu);
  float phase_m = cornette_shanks_phase(a.mie_g, mu);
  for (int i = 0; i < samples; ++i) {
    vec2 t = sky_step(ray.length_m, i, samples);
    vec3 x = ray.origin + dir * (0.5f * (t.x + t.y));
    AtmosphereMedium m = atmosphere_medium(a, length(x) - a.planet_radius_m);
    vec3 t_sun = transmittance_to_light(a, t_lut, exact, x, sun);
    MsScattering ms = multiple_scattering_towards(a, t_lut, ms_lut, ms_field, ms_mode, exact, x,
                                                  sun, dir, ground_albedo);
    result = sky_accumulate(result, m.extinction, t.y - t.x,
                            sky_source(m, phase_r, phase_m, t_sun, ms));
  }
  if (ray.hits_ground)
    result = sky_add_ground(a, t_lut, exact, result, ray.origin + dir * ray.length_m, sun,
                            ground_albedo, sky_ambient);
  return result;
}

// One texel (uv in [0, 1]^2 over a half of MS_FIELD_W x MS_FIELD_H) of the multiple-
// scattering light field, iteration `iteration` of MS_FIELD_ITERATIONS: the sky seen from the
// texel's altitude with the sun at its zenith angle, over MS_FIELD_THETA x 2 MS_FIELD_PHI
// directions stratified uniformly on the sphere (half of them by the y symmetry), projected on
// sh_basis. Iteration 0 sees the sky of sky_hillaire with Psi_ms (all orders but the direct
// sun) and a ground lit by the sun alone; each later one the sky scattering the field of the
// iteration before (read from half (iteration - 1) mod 2 of `field`; it writes half
// iteration mod 2) and a ground lit by that field's sky light too: each iteration puts one
// more order of scattering, and the sky light on the ground, where they belong (3 change the
// zenith by less than 1%). Returns the 6 coefficient blocks as stored (ms_field_read).
MsFieldCoefficients ms_field_texel(Atmosphere a, sampler2D t_lut, sampler2D ms_lut,
                                   sampler2D field, int iteration, vec2 uv,
                                   float ground_albedo) {
  vec2 unit = vec2(saturate(texcoord_to_unit(uv.x, float(MS_FIELD_W))),
                   saturate(texcoord_to_unit(uv.y, float(MS_FIELD_H))));
  float cos_sun = 2.0f * unit.x - 1.0f;
  float altitude_m = unit.y * unit.y * (a.top_radius_m - a.planet_radius_m);
  vec3 pos = vec3(0.0f, 0.0f, a.planet_radius_m + max(altitude_m, 1.0f));
  vec3 sun = vec3(sqrt(max(1.0f - cos_sun * cos_sun, 0.0f)), 0.0f, cos_sun);
  int previous = (iteration + 1) % 2;
  int ms_mode = iteration == 0 ? MS_ISOTROPIC : MS_ANGULAR + previous;
  vec3 ground_sky =
      iteration == 0 ? vec3(0.0f) : ms_field_ground_sky(field, previous, cos_sun);
  vec3 c[MS_FIELD_COEFFS];
  for (int k = 0; k < MS_FIELD_COEFFS; ++k) c[k] = vec3(0.0f);
  // Solid angle per direction: 4 pi over THETA x 2 PHI (each of the PHI counts twice).
  float d_omega = 4.0f * PI / float(MS_FIELD_THETA * 2 * MS_FIELD_PHI);
  for (int i = 0; i < MS_FIELD_THETA; ++i) {
    float cos_t = 1.0f - 2.0f * (float(i) + 0.5f) / float(MS_FIELD_THETA);
    float sin_t = sqrt(max(1.0f - cos_t * cos_t, 0.0f));
    for (int j = 0; j < MS_FIELD_PHI; ++j) {
      float phi = PI * (float(j) + 0.5f) / float(MS_FIELD_PHI);
      vec3 dir = vec3(sin_t * cos(phi), sin_t * sin(phi), cos_t);
      SkySample s = sky_hillaire(a, t_lut, ms_lut, field, ms_mode, false, pos, dir, sun,
                                 MS_FIELD_SAMPLES, ground_albedo, ground_sky);
      // Both y and -y: the functions odd in y cancel, the even ones count twice.
      vec3 w = 2.0f * d_omega * (s.radiance + s.ground_sun);
      ShBasis y = sh_basis(dir);
      c[0] += w * y.low.x;
      c[1] += w * y.low.y;
      c[2] += w * y.low.z;
      c[3] += w * y.high.x;
      c[4] += w * y.high.y;
      c[5] += w * y.high.z;
    }
  }
  MsFieldCoefficients stored;
  stored.c[0] = log(c[0] * 0.2820948f + vec3(MS_LUT_FLOOR));
  for (int k = 1; k < MS_FIELD_COEFFS; ++k) stored.c[k] = c[k] / max(c[0], vec3(1e-30f));
  return stored;
}

#endif

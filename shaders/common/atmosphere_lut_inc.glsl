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

const int TRANSMITTANCE_LUT_W = 256;  // mu
const int TRANSMITTANCE_LUT_H = 64;   // r
const int MS_LUT_W = 64;              // sun zenith cosine (log Psi_ms bends most along it)
const int MS_LUT_H = 32;              // altitude
const int MS_DIRECTIONS_SQRT = 8;     // 64 directions per Psi_ms (Hillaire's count)
const int MS_SAMPLES = 20;            // samples along each of them
const int TRANSMITTANCE_SAMPLES = 64;  // samples per transmittance LUT texel
const float MS_LUT_FLOOR = 1e-20f;      // Psi_ms stored as log(Psi_ms + floor)
const int EXACT_SUN_SAMPLES = 16;      // sun transmittance integrated in place (reference)

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
// the sun's transmittance `t_sun`) plus multiple scattering (Psi_ms `psi`, isotropic).
vec3 sky_source(AtmosphereMedium m, float phase_r, float phase_m, vec3 t_sun, vec3 psi) {
  return (m.scattering_r * phase_r + vec3(m.scattering_m * phase_m)) * t_sun +
         (m.scattering_r + vec3(m.scattering_m)) * psi;
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
// shadow) and by sky radiance `sky_ambient` (per unit illuminance).
SkySample sky_hillaire(Atmosphere a, sampler2D t_lut, sampler2D ms_lut, bool exact, vec3 eye,
                       vec3 dir, vec3 sun, int samples, float ground_albedo, vec3 sky_ambient) {
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
    vec3 psi = multiple_scattering_at(a, t_lut, ms_lut, exact, x, sun, ground_albedo);
    result = sky_accumulate(result, m.extinction, t.y - t.x,
                            sky_source(m, phase_r, phase_m, t_sun, psi));
  }
  if (ray.hits_ground)
    result = sky_add_ground(a, t_lut, exact, result, ray.origin + dir * ray.length_m, sun,
                            ground_albedo, sky_ambient);
  return result;
}

#endif

// The atmosphere's medium (Rayleigh, Mie with absorption, ozone) and its optical depth, and the
// single-scattering sky (seed 000, section 1.5, formulas 1.11-1.13), integrated numerically
// along the view ray as Nishita et al. (1993) do: at each sample x the sun's light, attenuated
// by exp(-tau(x -> sun)), is scattered towards the eye by Rayleigh and Mie particles whose
// densities fall off exponentially with height (scale heights H_R, H_M), then attenuated by
// exp(-tau(eye -> x)). Radiances are relative to the solar illuminance given by the caller.
// Pure functions, also compiled as C++ (src/render/glsl.h) for tests and CPU-side lighting.
#ifndef NEPHELE_ATMOSPHERE_INC
#define NEPHELE_ATMOSPHERE_INC

struct Atmosphere {
  float planet_radius_m;
  float top_radius_m;
  vec3 rayleigh_sigma_s;  // 1/m at sea level
  float rayleigh_height_m;
  float mie_sigma_s;      // 1/m at sea level
  float mie_sigma_t;      // 1/m at sea level
  float mie_height_m;
  float mie_g;
  // Ozone (Hillaire 2020, table 1): absorbs only, in a tent-shaped layer peaking at
  // ozone_center_m and falling to zero ozone_half_width_m above and below. Zero = no ozone.
  vec3 ozone_sigma_a;  // 1/m at the peak
  float ozone_center_m;
  float ozone_half_width_m;
};

// Scattering and extinction coefficients (1/m) at one altitude.
struct AtmosphereMedium {
  vec3 scattering_r;   // Rayleigh sigma_s
  float scattering_m;  // Mie sigma_s
  vec3 extinction;     // Rayleigh + Mie (absorption included) + ozone absorption
};

AtmosphereMedium atmosphere_medium(Atmosphere a, float altitude_m) {
  float h = max(altitude_m, 0.0f);
  float density_r = exp(-h / a.rayleigh_height_m);
  float density_m = exp(-h / a.mie_height_m);
  float density_o = a.ozone_half_width_m > 0.0f
                        ? max(1.0f - abs(h - a.ozone_center_m) / a.ozone_half_width_m, 0.0f)
                        : 0.0f;
  AtmosphereMedium m;
  m.scattering_r = a.rayleigh_sigma_s * density_r;
  m.scattering_m = a.mie_sigma_s * density_m;
  m.extinction = m.scattering_r + vec3(a.mie_sigma_t * density_m) + a.ozone_sigma_a * density_o;
  return m;
}

// Extinction coefficient (1/m) at altitude h (m) above the ground.
vec3 atmosphere_sigma_t(Atmosphere a, float altitude_m) {
  return atmosphere_medium(a, altitude_m).extinction;
}

// Optical depth from `pos` along unit `dir` over [0, length_m]: `samples` steps with ends at
// t = length (i / n)^2, denser near `pos` (Hillaire's squared distribution), where a ray
// leaving the ground sees the densest air.
vec3 atmosphere_optical_depth(Atmosphere a, vec3 pos, vec3 dir, float length_m, int samples) {
  vec3 tau = vec3(0.0f);
  float n = float(samples);
  for (int i = 0; i < samples; ++i) {
    float t0 = length_m * (float(i) / n) * (float(i) / n);
    float t1 = length_m * (float(i + 1) / n) * (float(i + 1) / n);
    vec3 x = pos + dir * (0.5f * (t0 + t1));
    tau += atmosphere_sigma_t(a, length(x) - a.planet_radius_m) * (t1 - t0);
  }
  return tau;
}

// Optical depth from `pos` (inside the atmosphere) to the top along unit `dir`, through the
// planet if the ray meets it. A ray that dips (dir below the local horizontal) is split at its
// lowest point, so each half starts where its air is densest.
vec3 atmosphere_optical_depth_to_top(Atmosphere a, vec3 pos, vec3 dir, int samples) {
  vec2 top = ray_sphere(pos, dir, a.top_radius_m);
  float length_m = max(top.y, 0.0f);
  float t_low = clamp(-dot(pos, dir), 0.0f, length_m);
  int first = t_low > 0.0f ? max(samples / 2, 1) : 0;
  vec3 tau = atmosphere_optical_depth(a, pos + dir * t_low, -dir, t_low, first);
  return tau + atmosphere_optical_depth(a, pos + dir * t_low, dir, length_m - t_low,
                                        max(samples - first, 1));
}

// Transmittance from `pos` to the top of the atmosphere along unit `dir`; zero when the ray
// hits the planet. `samples` midpoint samples.
vec3 atmosphere_transmittance_to_top(Atmosphere a, vec3 pos, vec3 dir, int samples) {
  vec2 ground = ray_sphere(pos, dir, a.planet_radius_m);
  if (ground.x > 0.0f) return vec3(0.0f);
  return exp(-atmosphere_optical_depth_to_top(a, pos, dir, samples));
}

struct SkySample {
  vec3 radiance;       // in-scattered radiance per unit solar illuminance (1/sr), plus the
                       // ground's sky-lit part
  vec3 ground_sun;     // the ground's sun-lit radiance as seen (the caller may shadow it)
  vec3 transmittance;  // from the eye to the end of the ray (0 if the ground was hit)
  float ground_air_t;  // the air's mean transmittance from the eye to the ground (0 if missed),
                       // for a caller that shadows the ground's sky-lit part
};

// Nothing gathered yet: no radiance, full transmittance.
SkySample sky_sample_start() {
  SkySample s;
  s.radiance = vec3(0.0f);
  s.ground_sun = vec3(0.0f);
  s.transmittance = vec3(1.0f);
  s.ground_air_t = 0.0f;
  return s;
}

// Adds one step of `dt_m` through air of extinction `extinction` (1/m) that in-scatters
// `source` (radiance per metre) to `s`, integrated over the step with the energy-conserving
// formula (Hillaire 2015; 2020, section 5.6.3).
SkySample sky_accumulate(SkySample s, vec3 extinction, float dt_m, vec3 source) {
  vec3 step_t = exp(-extinction * dt_m);
  s.radiance += s.transmittance * source * (vec3(1.0f) - step_t) / max(extinction, vec3(1e-12f));
  s.transmittance *= step_t;
  return s;
}

// Radiance seen from `eye` along unit `dir`, per unit solar illuminance, for the sun in unit
// direction `sun`. A ray that hits the ground ends there and adds the ground (Lambertian,
// albedo `ground_albedo`, lit by the attenuated sun and by sky radiance `sky_ambient`).
SkySample sky_single_scattering(Atmosphere a, vec3 eye, vec3 dir, vec3 sun, int view_samples,
                                int light_samples, float ground_albedo, vec3 sky_ambient) {
  SkySample result = sky_sample_start();
  float r_eye = length(eye);
  vec2 top = ray_sphere(eye, dir, a.top_radius_m);
  if (top.y <= 0.0f) return result;  // looking away from the atmosphere, from space
  float t_start = r_eye > a.top_radius_m ? max(top.x, 0.0f) : 0.0f;
  float t_end = top.y;
  vec2 ground = ray_sphere(eye, dir, a.planet_radius_m);
  bool hits_ground = ground.x > 0.0f;
  if (hits_ground) t_end = ground.x;

  float mu = dot(dir, sun);
  float phase_r = rayleigh_phase(mu);
  float phase_m = cornette_shanks_phase(a.mie_g, mu);
  float dt = (t_end - t_start) / float(view_samples);
  vec3 tau_view = vec3(0.0f);
  vec3 inscatter = vec3(0.0f);
  for (int i = 0; i < view_samples; ++i) {
    vec3 x = eye + dir * (t_start + (float(i) + 0.5f) * dt);
    AtmosphereMedium m = atmosphere_medium(a, length(x) - a.planet_radius_m);
    vec3 sigma_t = m.extinction;
    // Transmittance from the eye to the middle of this segment.
    vec3 t_eye = exp(-(tau_view + sigma_t * (0.5f * dt)));
    vec3 t_sun = atmosphere_transmittance_to_top(a, x, sun, light_samples);
    vec3 scattering = m.scattering_r * phase_r + vec3(m.scattering_m * phase_m);
    inscatter += t_eye * t_sun * scattering * dt;
    tau_view += sigma_t * dt;
  }
  result.transmittance = exp(-tau_view);
  result.radiance = inscatter;
  if (hits_ground) {
    // The ground point, lifted 1 m so its own sphere does not shadow it through rounding.
    vec3 n = normalize(eye + dir * t_end);
    vec3 p = n * (a.planet_radius_m + 1.0f);
    vec3 t_sun = atmosphere_transmittance_to_top(a, p, sun, light_samples);
    result.ground_sun = result.transmittance * ground_albedo / PI * t_sun * max(dot(n, sun), 0.0f);
    result.radiance += result.transmittance * ground_albedo * sky_ambient;
    result.ground_air_t = dot(result.transmittance, vec3(1.0f / 3.0f));
    result.transmittance = vec3(0.0f);
  }
  return result;
}

#endif

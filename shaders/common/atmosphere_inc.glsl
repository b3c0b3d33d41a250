// Single-scattering sky (seed 000, section 1.5, formulas 1.11-1.13), integrated numerically
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
};

// Extinction coefficient (1/m) at altitude h (m) above the ground.
vec3 atmosphere_sigma_t(Atmosphere a, float altitude_m) {
  float h = max(altitude_m, 0.0f);
  return a.rayleigh_sigma_s * exp(-h / a.rayleigh_height_m) +
         vec3(a.mie_sigma_t * exp(-h / a.mie_height_m));
}

// Transmittance from `pos` to the top of the atmosphere along unit `dir`; zero when the ray
// hits the planet. `samples` midpoint samples.
vec3 atmosphere_transmittance_to_top(Atmosphere a, vec3 pos, vec3 dir, int samples) {
  vec2 ground = ray_sphere(pos, dir, a.planet_radius_m);
  if (ground.x > 0.0f) return vec3(0.0f);
  vec2 top = ray_sphere(pos, dir, a.top_radius_m);
  float length_m = max(top.y, 0.0f);
  float dt = length_m / float(samples);
  vec3 tau = vec3(0.0f);
  for (int i = 0; i < samples; ++i) {
    vec3 x = pos + dir * ((float(i) + 0.5f) * dt);
    tau += atmosphere_sigma_t(a, length(x) - a.planet_radius_m) * dt;
  }
  return exp(-tau);
}

struct SkySample {
  vec3 radiance;       // in-scattered radiance per unit solar illuminance (1/sr), plus the
                       // ground's sky-lit part
  vec3 ground_sun;     // the ground's sun-lit radiance as seen (the caller may shadow it)
  vec3 transmittance;  // from the eye to the end of the ray (0 if the ground was hit)
};

// Radiance seen from `eye` along unit `dir`, per unit solar illuminance, for the sun in unit
// direction `sun`. A ray that hits the ground ends there and adds the ground (Lambertian,
// albedo `ground_albedo`, lit by the attenuated sun and by sky radiance `sky_ambient`).
SkySample sky_single_scattering(Atmosphere a, vec3 eye, vec3 dir, vec3 sun, int view_samples,
                                int light_samples, float ground_albedo, vec3 sky_ambient) {
  SkySample result;
  result.radiance = vec3(0.0f);
  result.ground_sun = vec3(0.0f);
  result.transmittance = vec3(1.0f);
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
    float h = length(x) - a.planet_radius_m;
    float density_r = exp(-max(h, 0.0f) / a.rayleigh_height_m);
    float density_m = exp(-max(h, 0.0f) / a.mie_height_m);
    vec3 sigma_t = a.rayleigh_sigma_s * density_r + vec3(a.mie_sigma_t * density_m);
    // Transmittance from the eye to the middle of this segment.
    vec3 t_eye = exp(-(tau_view + sigma_t * (0.5f * dt)));
    vec3 t_sun = atmosphere_transmittance_to_top(a, x, sun, light_samples);
    vec3 scattering = a.rayleigh_sigma_s * (density_r * phase_r) +
                      vec3(a.mie_sigma_s * density_m * phase_m);
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
    result.transmittance = vec3(0.0f);
  }
  return result;
}

#endif

#version 450
// Pass 3: clouds. Per pixel, march the view ray through the cloud shell between two spheres
// (seed 000, 2.2) compositing front to back (formulas 1.5, 1.6) with Beer-Lambert attenuation,
// a light march towards the sun, dual-lobe Henyey-Greenstein phase, the powder term and ambient
// light (1.4, listings B.1-B.3). Writes two vec4 per pixel: (rgb in-scattered radiance
// attenuated by the air between the eye and each sample, a = cloud transmittance) and
// (x = haze weight: the share of the cloud's light replaced by the air's in-scattering, yzw 0).
//
// MARCH_MODE (specialization constant) selects the variant:
//   0 default:  distance-adaptive steps with per-pixel jitter, detail noise only where the
//               base shape is non-zero, longer light march, multiple-scattering octaves,
//               early exit at T < 0.01.
//   1 baseline: the seed's algorithm as written: fixed step (layer thickness / 64), at most 128
//               steps, 4-sample light march (3 short steps and one 6x), colour extinction
//               (0.8, 0.8, 1.0), no jitter, no skipping.
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/phase_inc.glsl"
#include "common/clouds_inc.glsl"

layout(constant_id = 0) const int MARCH_MODE = 0;
layout(local_size_x = 8, local_size_y = 8) in;

const vec3 SEED_EXTINCTION_MULT = vec3(0.8f, 0.8f, 1.0f);  // listing B.3

float altitude_fraction(vec3 pos) {
  return cloud_height_fraction(length(pos), frame.radii_m.z, frame.radii_m.w);
}

// Cloud density field (dimensionless, listing B.1); sigma_t = field * cloud_shape.z.
float cloud_density(vec3 pos, bool with_detail) {
  float h = altitude_fraction(pos);
  if (h <= 0.0f || h >= 1.0f) return 0.0f;
  vec2 ground_xy = pos.xy - frame.wind_offset_m.xy;  // clouds drift with the wind
  vec4 weather = textureLod(weather_map, ground_xy * frame.cloud_noise.z + 0.5f, 0.0f);
  float coverage = cloud_local_coverage(weather.r, weather.g, frame.cloud_shape.x);
  if (coverage <= 0.0f) return 0.0f;
  float shape_gradient = cloud_shape_gradient(h, weather.b);
  if (shape_gradient <= 0.0f) return 0.0f;
  float density_gradient =
      cloud_density_gradient(h) * weather.a * 2.0f * frame.cloud_shape.y;

  float altitude_m = length(pos) - frame.radii_m.x;
  vec3 uvw = vec3(ground_xy, altitude_m) * frame.cloud_noise.x;
  vec4 base = textureLod(base_noise, uvw, 0.0f);
  if (MARCH_MODE == 1) {
    // Seed: low-frequency noise 85% plus detail noise 15%, then coverage and height shape.
    float detail = textureLod(detail_noise, vec3(ground_xy, altitude_m) * frame.cloud_noise.y, 0.0f).r;
    float noise = base.r * 0.85f + detail * 0.15f;
    return cloud_apply_coverage(noise * shape_gradient, coverage) * density_gradient;
  }
  // Schneider: Worley fBm (GBA) carves the Perlin-Worley (R), coverage cuts, detail erodes.
  float worley = base.g * 0.625f + base.b * 0.25f + base.a * 0.125f;
  float shape = saturate(remap(base.r, worley - 1.0f, 1.0f, 0.0f, 1.0f));
  shape = cloud_apply_coverage(shape * shape_gradient, coverage);
  if (shape <= 0.0f) return 0.0f;
  if (with_detail) {
    vec3 d = textureLod(detail_noise, vec3(ground_xy, altitude_m) * frame.cloud_noise.y, 0.0f).rgb;
    shape = cloud_erode(shape, d.r * 0.625f + d.g * 0.25f + d.b * 0.125f, h,
                        frame.cloud_noise.w);
  }
  return shape * density_gradient;
}

// Optical depth towards the sun from pos (without the view-independent extinction scale).
float light_optical_depth(vec3 pos, vec3 sun) {
  float thickness = frame.radii_m.w - frame.radii_m.z;
  float depth = 0.0f;
  if (MARCH_MODE == 1) {
    // Listing B.2: three steps of 1% of the layer thickness, the fourth six times longer.
    float step_m = thickness * 0.01f;
    for (int i = 0; i < 4; ++i) {
      float s = i == 3 ? step_m * 6.0f : step_m;
      pos += sun * s;
      depth += cloud_density(pos, true) * s;
    }
    return depth;
  }
  // Steps growing linearly up to the top of the layer along the sun (at most two layer
  // thicknesses, for a low sun), so a sample near the base sees the dense tops above it.
  int n = frame.steps.y;
  float to_top = ray_sphere(pos, sun, frame.radii_m.w).y;
  float unit = min(to_top, 2.0f * thickness) / float(n * (n + 1) / 2);
  float t = 0.0f;
  for (int i = 1; i <= n; ++i) {
    float s = unit * float(i);
    depth += cloud_density(pos + sun * (t + 0.5f * s), i <= 2) * s;
    t += s;
  }
  return depth;
}

// Transmittance of the air over `dist_m` from the eye to a cloud sample at altitude
// `sample_alt_m`, with the extinction taken at the mean altitude (a simple aerial perspective;
// distant clouds fade into the haze of the sky behind them).
vec3 air_transmittance(float eye_alt_m, float sample_alt_m, float dist_m) {
  float h = max(0.5f * (eye_alt_m + sample_alt_m), 0.0f);
  vec3 sigma_t = frame.rayleigh.rgb * exp(-h / frame.rayleigh.w) + frame.mie.y * exp(-h / frame.mie.z);
  return exp(-sigma_t * dist_m);
}

// Cloud shadow on the ground: transmittance from the ground point this ray hits towards the
// sun through the cloud layer (16 samples of the full density: coarser sampling turns thin
// wisps into deep shadow), 1 when the ray misses the ground.
float ground_shadow(vec3 eye, vec3 dir, vec3 sun) {
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  if (ground.x <= 0.0f) return 1.0f;
  vec3 p = normalize(eye + dir * ground.x) * (frame.radii_m.x + 1.0f);
  vec2 inner = ray_sphere(p, sun, frame.radii_m.z);
  vec2 outer = ray_sphere(p, sun, frame.radii_m.w);
  if (inner.y <= 0.0f || outer.y <= inner.y) return 1.0f;
  const int n = 16;
  float ds = (outer.y - inner.y) / float(n);
  float depth = 0.0f;
  for (int i = 0; i < n; ++i) depth += cloud_density(p + sun * (inner.y + (float(i) + 0.5f) * ds), true);
  return exp(-depth * ds * frame.cloud_shape.z * frame.cloud_light.y);
}

// Multiple-scattering approximation (Wrenninge et al. 2013, "Oz: the great and volumetric"):
// octave i scatters with contribution a^i, extinction b^i and eccentricity c^i. b < 1 lets
// light reach deep into the cloud as repeated forward scattering does, so thick clouds keep
// their brightness instead of turning grey. a = 0.6, b = 0.4, c = 0.5, four octaves.
float multiple_scattering(float tau_light, float mu, float powder) {
  float energy = 0.0f;
  float a = 1.0f, b = 1.0f, c = 1.0f;
  for (int i = 0; i < 4; ++i) {
    float phase = dual_lobe_hg(frame.cloud_phase.x * c, frame.cloud_phase.y * c, frame.cloud_phase.z, mu);
    energy += a * cloud_beer_powder(b * tau_light, mu, powder) * phase;
    a *= 0.6f;
    b *= 0.4f;
    c *= 0.5f;
  }
  return energy;
}

// The part of the view ray inside the cloud shell: (t_enter, t_exit), empty if exit <= enter.
vec2 shell_segment(vec3 eye, vec3 dir) {
  float r = length(eye);
  vec2 inner = ray_sphere(eye, dir, frame.radii_m.z);
  vec2 outer = ray_sphere(eye, dir, frame.radii_m.w);
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  if (outer.y <= 0.0f) return vec2(0.0f);  // the shell is behind
  float t_enter;
  float t_exit;
  if (r < frame.radii_m.z) {  // below the layer: from leaving the inner sphere to the outer
    if (ground.x > 0.0f) return vec2(0.0f);  // looking at the ground
    t_enter = inner.y;
    t_exit = outer.y;
  } else if (r <= frame.radii_m.w) {  // inside the layer
    t_enter = 0.0f;
    t_exit = inner.x > 0.0f ? inner.x : outer.y;
  } else {  // above: from entering the outer sphere to the inner sphere or out again
    t_enter = max(outer.x, 0.0f);
    t_exit = inner.x > 0.0f ? inner.x : outer.y;
  }
  return vec2(t_enter, t_exit);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  int width = frame.size.x;
  int height = frame.size.y;
  if (pixel.x >= width || pixel.y >= height) return;
  int index = pixel.y * width + pixel.x;

  vec3 eye = frame.camera_pos_m.xyz;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x),
                        float(pixel.y), float(width), float(height));
  vec3 sun = frame.sun_dir.xyz;
  float mu = dot(dir, sun);
  vec2 segment = shell_segment(eye, dir);
  float shadow = ground_shadow(eye, dir, sun);
  if (segment.y <= segment.x) {
    cloud_out[2 * index] = vec4(0.0f, 0.0f, 0.0f, 1.0f);
    cloud_out[2 * index + 1] = vec4(0.0f, shadow, 0.0f, 0.0f);
    return;
  }
  float eye_alt_m = length(eye) - frame.radii_m.x;
  float haze = 0.0f;

  float sigma_scale = frame.cloud_shape.z;  // sigma_t (1/m) at density field 1
  float view_atten = frame.cloud_light.x;
  float light_atten = frame.cloud_light.y;
  float powder = frame.cloud_light.z;
  float albedo = frame.cloud_shape.w;
  vec3 sun_light = frame.sun_at_clouds.rgb;
  vec3 ambient = frame.ambient_at_clouds.rgb * frame.cloud_light.w;
  float g_f = frame.cloud_phase.x;
  float g_b = frame.cloud_phase.y;
  float lobe = frame.cloud_phase.z;
  float thickness = frame.radii_m.w - frame.radii_m.z;

  vec3 scattered = vec3(0.0f);
  vec3 transmittance = vec3(1.0f);

  if (MARCH_MODE == 1) {
    // Seed listing B.3: fixed steps from the entry point, stop on leaving the layer.
    float step_m = thickness / 64.0f;
    float phase = dual_lobe_hg(g_f, g_b, lobe, mu);
    for (int i = 0; i < 128; ++i) {
      float t = segment.x + float(i) * step_m;
      if (t > segment.y) break;
      vec3 pos = eye + dir * t;
      float density = cloud_density(pos, true);
      if (density > 0.01f) {
        vec3 tau_light = light_optical_depth(pos, sun) * sigma_scale * light_atten *
                         SEED_EXTINCTION_MULT;
        vec3 beer = exp(-tau_light) * phase;
        vec3 powder_term = 1.0f - exp(-2.0f * tau_light);
        vec3 energy = beer * mix(2.0f * powder_term, vec3(1.0f), remap(mu, -1.0f, 1.0f, 0.0f, 1.0f));
        energy = mix(exp(-tau_light) * phase, energy, powder);
        vec3 luminance = albedo * (ambient + sun_light * energy);
        vec3 step_t = exp(-density * step_m * sigma_scale * view_atten * SEED_EXTINCTION_MULT);
        vec3 air = air_transmittance(eye_alt_m, length(pos) - frame.radii_m.x, t);
        scattered += transmittance * air * luminance * (1.0f - step_t);
        haze += transmittance.g * (1.0f - air.g) * (1.0f - step_t.g);
        transmittance *= step_t;
        if (length(transmittance) <= 0.01f) {
          transmittance = vec3(0.0f);
          break;
        }
      }
    }
  } else {
    // Coarse steps of at least thickness / primary_steps, growing with distance (1% of t) so
    // far rays stay affordable, jittered per pixel so the step pattern becomes fine noise. On
    // the first hit the march steps back one coarse step and goes on in fine steps of about
    // half a mean free path, so lighting is sampled where the cloud's surface really is
    // (a coarse sample lands up to a step deep, where the sun is already attenuated); after
    // four empty fine samples past that hit it returns to coarse steps.
    float base_step = thickness / float(frame.steps.x);
    float jitter = interleaved_gradient_noise(float(pixel.x), float(pixel.y));
    float t = segment.x + max(base_step, 0.01f * segment.x) * jitter;
    int max_steps = 4 * frame.steps.x;
    bool fine = false;
    int misses = 0;
    float fine_until = 0.0f;  // stay fine at least past the coarse sample that hit
    float fine_step = base_step;
    for (int i = 0; i < max_steps && t < segment.y; ++i) {
      float coarse_step = max(base_step, 0.01f * t);
      vec3 pos = eye + dir * t;
      float density = cloud_density(pos, true);
      if (density <= 0.0f) {
        if (fine && ++misses >= 4 && t > fine_until) fine = false;
        t += fine ? fine_step : coarse_step;
        continue;
      }
      float sigma_t = density * sigma_scale * view_atten;
      if (!fine) {
        fine = true;
        fine_until = t;
        if (i > 0) {  // step back to where the previous (empty) coarse sample was
          t = max(t - coarse_step, segment.x);
          fine_step = clamp(0.5f / sigma_t, 2.0f, coarse_step);
          continue;
        }
      }
      misses = 0;
      float step_m = clamp(0.5f / sigma_t, 2.0f, coarse_step);
      fine_step = step_m;
      float tau_light = light_optical_depth(pos, sun) * sigma_scale * light_atten;
      float energy = multiple_scattering(tau_light, mu, powder);
      float h = altitude_fraction(pos);
      vec3 luminance = albedo * (sun_light * energy + ambient * mix(0.5f, 1.0f, h));
      float step_t = exp(-sigma_t * step_m);
      vec3 air = air_transmittance(eye_alt_m, length(pos) - frame.radii_m.x, t);
      // Energy-conserving integration over the step (Hillaire 2016).
      scattered += transmittance * air * luminance * (1.0f - step_t);
      haze += transmittance.x * (1.0f - air.g) * (1.0f - step_t);
      transmittance *= step_t;
      if (transmittance.x < 0.01f) {
        transmittance = vec3(0.0f);
        break;
      }
      t += step_m;
    }
  }
  float t_mean = (transmittance.r + transmittance.g + transmittance.b) / 3.0f;
  cloud_out[2 * index] = vec4(scattered, t_mean);
  cloud_out[2 * index + 1] = vec4(haze, shadow, 0.0f, 0.0f);
}

#version 450
// Pass: the classical cloud models of seed 004 (issue 23, render/modules/classic_clouds/classic_clouds.h),
// drawn in place of nephele's march into this frame's cloud buffer (clouds_a_out,
// clouds_b_out: what resolve.comp writes), so that compose.comp puts them in the sky as it
// does nephele's clouds. MODEL (specialization constant) selects the model:
//   CLASSIC_BLINN: Blinn 1982, the [clouds] layer as a uniform slab of small particles, lit by
//     the key light with low-albedo single scattering (common/classic_inc.glsl): the light
//     scattered once towards the eye and the transparency of the slab along the view.
//   CLASSIC_GARDNER: Gardner 1985, on a flat earth as he had it: cumulus as ellipsoids standing
//     on the layer's bottom, one in a share `coverage` of the cells of a grid (visited along the
//     ray in order, front to back), or stratus as a sky plane at the layer's bottom; both
//     textured by his T(x, y, z), translucent where T falls below the threshold that goes from
//     T1 at an ellipsoid's centre to T2 at its limb, shaded by his I = (1 - f){(1 - t)
//     [(1 - s) I_d + s I_s] + t T} + f, its ambient term f lit by the sky and the rest by the
//     sun, each as a white diffuser (E / pi). No shadows on the ground: his model has none.
//   CLASSIC_GARDNER_QUADRICS: Gardner's impressionistic scenes: in the same cells, clouds of
//     convex objects, each a quadric cut by planes (classic_inc.glsl, gardner_cell_object),
//     found by casting the ray against each and textured and shaded as above.
//   A third form of his plane is cirrus: the plane at the cirrus's altitude, its texture
//     stretched along x into streaks, thin.
//   CLASSIC_KAJIYA: Kajiya and Von Herzen 1984's two passes on nephele's own density field
//     (kajiya() below).
//   CLASSIC_NISHITA: Nishita and Nakamae 1996's metaball clouds on their voxel grid, lit by
//     nishita_light.comp and nishita_scatter.comp (nishita() below).
#extension GL_GOOGLE_include_directive : require
#include "common/bindings_inc.glsl"
#include "common/math_inc.glsl"
#include "common/noise_inc.glsl"
#include "common/classic_inc.glsl"
#include "air_inc.glsl"
#include "common/phase_inc.glsl"
#include "nishita_volume_inc.glsl"

const int MARCH_MODE = 0;  // cloud_field_inc.glsl's density and light lookups, nephele's own
#include "cloud_field_inc.glsl"

layout(constant_id = 0) const int MODEL = CLASSIC_BLINN;
layout(local_size_x = 8, local_size_y = 8) in;

void write_cloud(ivec2 pixel, vec3 radiance, float transmittance, float haze, float shadow,
                 float distance_m) {
  imageStore(clouds_a_out, pixel, vec4(radiance, transmittance));
  imageStore(clouds_b_out, pixel, vec4(haze, shadow, distance_m * 1e-3f, 1.0f));
}

// The slab between the spheres of radii frame.radii_m.z and .w crossed by the ray from `eye`
// along `dir`: (t_enter, t_exit), empty when exit <= enter; the ground stops it.
vec2 slab_segment(vec3 eye, vec3 dir) {
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  vec2 inner = ray_sphere(eye, dir, frame.radii_m.z);
  vec2 outer = ray_sphere(eye, dir, frame.radii_m.w);
  float r = length(eye);
  float t0, t1;
  if (r < frame.radii_m.z) {
    if (ground.x > 0.0f) return vec2(0.0f);
    t0 = inner.y;
    t1 = outer.y;
  } else if (r <= frame.radii_m.w) {
    t0 = 0.0f;
    t1 = inner.x > 0.0f ? inner.x : outer.y;
  } else {
    t0 = max(outer.x, 0.0f);
    t1 = inner.x > 0.0f ? inner.x : outer.y;
  }
  return outer.y <= 0.0f ? vec2(0.0f) : vec2(t0, t1);
}

// Blinn's slab. tau is its optical depth along the vertical: along the ray the slab's path
// (t1 - t0) is tau / mu with mu = thickness / path, which holds on the sphere too; mu0 is the
// light's cosine to the vertical where the ray crosses the slab's middle.
void blinn(ivec2 pixel, vec3 eye, vec3 dir, vec3 light) {
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  vec2 seg = slab_segment(eye, dir);
  float thickness_m = frame.radii_m.w - frame.radii_m.z;
  float tau = frame.classic_blinn.x;
  bool seed_form = frame.classic_options.x > 0.5f;
  // The ground's shadow: the light through the slab above the ground point.
  float shadow = 1.0f;
  if (ground.x > 0.0f) {
    vec3 up = normalize(eye + dir * ground.x);
    float mu0 = dot(up, light);
    shadow = mu0 > 0.0f ? exp(-tau / max(mu0, 1e-3f)) : 1.0f;
  }
  if (seg.y <= seg.x || tau <= 0.0f) {
    write_cloud(pixel, vec3(0.0f), 1.0f, 0.0f, shadow, ground.x > 0.0f ? ground.x : FAR_M);
    return;
  }
  float t_mid = 0.5f * (seg.x + seg.y);
  vec3 mid = eye + dir * t_mid;
  vec3 up = normalize(mid);
  float mu = clamp(thickness_m / (seg.y - seg.x), 1e-4f, 1.0f);
  // Within the slab only the part ahead counts: a thinner slab (its depth ahead).
  float tau_seen = tau;
  float eye_r = length(eye);
  if (eye_r > frame.radii_m.z && eye_r < frame.radii_m.w) tau_seen = tau * (seg.y - seg.x) * mu / thickness_m;
  // Where the eye looks from: below the slab it looks up (the light on the far side when above
  // the horizon); above it looks down (the light on its side).
  bool from_below = dot(dir, up) > 0.0f;
  float mu0 = dot(up, light);
  float cos_alpha = -dot(dir, light);
  int kind = int(frame.classic_blinn.w);
  float x = frame.classic_blinn.z, omega = frame.classic_blinn.y;
  float phi = blinn_phase(kind, x, cos_alpha, seed_form);
  float phi_pi = blinn_phase(kind, x, -1.0f, seed_form);
  bool lit_from_front = from_below ? mu0 < 0.0f : mu0 > 0.0f;
  vec2 b_tr = blinn_layer(tau_seen, mu, max(abs(mu0), 1e-4f), lit_from_front, omega, phi, phi_pi,
                          seed_form);
  // A light below the horizon of the slab lights nothing the slab can scatter (it would come
  // through the planet for an eye below).
  float lit = mu0 > 0.0f ? 1.0f : 0.0f;
  // Blinn's B is radiance over the beam's irradiance / 4 pi.
  vec3 radiance = frame.sun_at_clouds.rgb * (lit * b_tr.x / (4.0f * PI));
  float transmittance = clamp(b_tr.y, 0.0f, 1.0f);
  float eye_alt_m = eye_r - frame.radii_m.x;
  vec3 air = air_transmittance(eye_alt_m, length(mid) - frame.radii_m.x, t_mid);
  float haze = (1.0f - air.g) * (1.0f - transmittance);
  write_cloud(pixel, air * radiance, transmittance, haze, shadow, t_mid);
}

// Gardner's texture at a point (ENU, m) and the translucency (opacity) there for limb curve g;
// `stretch` divides the texture's x frequencies (cirrus's streaks along x).
vec2 gardner_surface(vec3 p, float g, float stretch) {
  bool seed_form = frame.classic_options.x > 0.5f;
  int terms = int(frame.classic_options.z);
  // k and T0 keep the original's T in [0, 1]: each factor's sum lies within +-S, S = sum C_i.
  float s = 0.0f, c = 1.0f;
  for (int i = 0; i < GARDNER_TERMS_MAX; ++i) {
    if (i >= terms) break;
    s += c;
    c *= 0.707f;
  }
  float f1 = frame.classic_gardner.x;
  float t = gardner_texture(p, vec2(f1 / stretch, f1), s, 1.0f / (4.0f * s * s), terms, seed_form);
  if (seed_form) t = fract(t);  // the seed's printing grows without bound: seen modulo 1
  return vec2(t, gardner_translucency(t, frame.classic_gardner.y, frame.classic_gardner.z,
                                      frame.classic_gardner.w, g));
}

// Gardner's intensity at a surface point with normal n facing the eye, as radiance: his
// I = (1 - f){...} + f with the ambient term f lit by the sky (a white diffuser facing up at
// the layer: the sky's light, blue by day, dark at night) and the rest by the key light.
vec3 gardner_shade(vec3 n, vec3 to_eye, vec3 light, float texture_value) {
  vec4 k = frame.classic_gardner_shading;
  float i_d = max(dot(n, light), 0.0f);
  float i_s = pow(max(dot(n, normalize(light + to_eye)), 0.0f), 16.0f);
  float intensity = gardner_intensity(i_d, i_s, texture_value, k.x, k.y, k.z);
  vec3 sunlight = frame.sun_at_clouds.rgb / PI * (light.z > 0.0f ? 1.0f : 0.0f);
  return sunlight * (intensity - k.x) + frame.ambient_at_clouds.rgb * k.x;
}

void gardner(ivec2 pixel, vec3 eye_planet, vec3 dir, vec3 light, bool quadrics) {
  float radius_m = frame.radii_m.x;
  vec3 eye = vec3(eye_planet.xy, length(eye_planet) - radius_m);  // ENU on a flat earth
  float bottom_m = frame.radii_m.z - radius_m, top_m = frame.radii_m.w - radius_m;
  float t_ground = dir.z < 0.0f ? -eye.z / dir.z : FAR_M;
  vec3 radiance = vec3(0.0f);
  float transmittance = 1.0f, haze = 0.0f, weighted_t = 0.0f;
  // One surface: composited front to back with the air in front of it.
  #define GARDNER_HIT(t_hit, opacity, shade)                                              \
    {                                                                                      \
      vec3 air = air_transmittance(eye.z, eye.z + dir.z * (t_hit), (t_hit));              \
      radiance += transmittance * (opacity) * air * (shade);                               \
      haze += transmittance * (opacity) * (1.0f - air.g);                                  \
      weighted_t += (t_hit) * transmittance * (opacity);                                   \
      transmittance *= 1.0f - (opacity);                                                   \
    }
  if (!quadrics && frame.classic_options.y > 0.5f) {  // stratus or cirrus: the sky plane
    vec4 plane = frame.classic_gardner_plane;
    float t = abs(dir.z) > 1e-6f ? (plane.x - eye.z) / dir.z : -1.0f;
    if (t > 0.0f && t < t_ground) {
      vec3 n = vec3(0.0f, 0.0f, dir.z > 0.0f ? -1.0f : 1.0f);
      vec2 surface = gardner_surface(eye + dir * t, 1.0f, plane.y);
      GARDNER_HIT(t, plane.z * surface.y, gardner_shade(n, -dir, light, surface.x));
    }
  } else {  // cumulus: the cells the ray crosses within the layer, in order
    float spacing = frame.classic_gardner_shading.w;
    float t0 = 0.0f, t1 = FAR_M;
    if (abs(dir.z) > 1e-6f) {
      float tb = (bottom_m - eye.z) / dir.z, tt = (top_m - eye.z) / dir.z;
      t0 = max(min(tb, tt), 0.0f);
      t1 = max(tb, tt);
    } else if (eye.z < bottom_m || eye.z > top_m) {
      t1 = -1.0f;
    }
    t1 = min(t1, min(t_ground, t0 + 80000.0f));  // at most 80 km of the layer
    if (t1 > t0) {
      vec2 p = (eye.xy + dir.xy * t0) / spacing;
      ivec2 cell = ivec2(floor(p));
      vec2 d = dir.xy;
      ivec2 step_dir = ivec2(d.x >= 0.0f ? 1 : -1, d.y >= 0.0f ? 1 : -1);
      vec2 inv = vec2(abs(d.x) > 1e-9f ? 1.0f / abs(d.x) : 1e30f, abs(d.y) > 1e-9f ? 1.0f / abs(d.y) : 1e30f);
      // The ray's t at the next cell border in x and y (Amanatides and Woo).
      vec2 border = vec2(d.x >= 0.0f ? float(cell.x + 1) - p.x : p.x - float(cell.x),
                         d.y >= 0.0f ? float(cell.y + 1) - p.y : p.y - float(cell.y));
      vec2 t_next = vec2(t0) + border * spacing * inv;
      vec2 t_delta = spacing * inv;
      uint seed = uint(frame.size.w);
      for (int i = 0; i < 160 && transmittance > 0.01f; ++i) {
        GardnerEllipsoid e = gardner_cell_ellipsoid(cell, spacing, bottom_m, top_m,
                                                    frame.classic_options.w, seed);
        vec3 axis = quadrics ? gardner_cell_axis(cell, spacing, seed) : vec3(0.0f);
        vec2 to_axis = axis.xy - eye.xy;
        float along = dot(to_axis, d) / max(dot(d, d), 1e-12f);  // the closest approach in xy
        bool near_axis = length(to_axis - d * along) <= axis.z;
        if (e.present && quadrics && near_axis) {
          // The impressionistic cloud's objects the ray enters, nearest first.
          vec4 hits[GARDNER_CELL_OBJECTS];
          vec3 normals[GARDNER_CELL_OBJECTS];
          int count = 0;
          for (int k = 0; k < GARDNER_CELL_OBJECTS; ++k) {
            ConvexObject object = gardner_cell_object(cell, k, spacing, bottom_m, top_m, seed);
            vec4 hit = ray_convex_object(object, eye, dir);
            if (hit.x >= hit.y || hit.x <= 0.0f || hit.x >= t_ground) continue;
            vec3 n = hit.z < 0.0f ? quadric_gradient(object.shape, eye + dir * hit.x)
                                  : object.planes[int(hit.z)].xyz;
            int j = count++;
            for (; j > 0 && hits[j - 1].x > hit.x; --j) {
              hits[j] = hits[j - 1];
              normals[j] = normals[j - 1];
            }
            hits[j] = hit;
            normals[j] = normalize(n);
          }
          for (int j = 0; j < count; ++j) {
            vec2 surface = gardner_surface(eye + dir * hits[j].x, hits[j].w, 1.0f);
            GARDNER_HIT(hits[j].x, surface.y, gardner_shade(normals[j], -dir, light, surface.x));
          }
        } else if (e.present && !quadrics) {
          vec2 hit = ray_ellipsoid(eye, dir, e.centre, e.radii);
          if (hit.x > 0.0f && hit.x < t_ground) {
            vec3 q = eye + dir * hit.x;
            vec3 n = normalize((q - e.centre) / (e.radii * e.radii));
            vec2 surface = gardner_surface(q, hit.y, 1.0f);
            GARDNER_HIT(hit.x, surface.y, gardner_shade(n, -dir, light, surface.x));
          }
        }
        float t_here = min(t_next.x, t_next.y);
        if (t_here > t1) break;
        if (t_next.x < t_next.y) {
          t_next.x += t_delta.x;
          cell.x += step_dir.x;
        } else {
          t_next.y += t_delta.y;
          cell.y += step_dir.y;
        }
      }
    }
  }
  float opacity = 1.0f - transmittance;
  float distance_m = opacity > 1e-6f ? weighted_t / opacity : (t_ground < FAR_M ? t_ground : FAR_M);
  write_cloud(pixel, radiance, transmittance, haze, 1.0f, distance_m);
}

// Kajiya and Von Herzen 1984 on nephele's density field. Pass 1, the array I(x, y, z) of the
// key light's attenuation over the volume, is nephele's light volume (light_volume.comp: the
// optical depth towards the light on a grid about the camera; beyond it, a march towards the
// light). Pass 2 integrates each eye ray through the layer, B = integral of A C rho dt with
// A = exp(-kappa integral rho) and C = I p(cos theta) (single scattering, nephele's phase),
// by Romberg's method: trapezoid sums on 2^k + 1 samples, k = 0 ... levels, each with its own
// A from the cumulative trapezoid of rho on the same samples, extrapolated by Richardson (the
// sums of every level gathered in one pass over the finest samples).
// `reference`: instead, a brute-force march of the same integral (1024 midpoint samples, the
// light marched at each), to check the method against.
void kajiya(ivec2 pixel, vec3 eye, vec3 dir, vec3 light, bool reference) {
  vec2 seg = slab_segment(eye, dir);
  vec2 ground = ray_sphere(eye, dir, frame.radii_m.x);
  float far_m = ground.x > 0.0f ? ground.x : FAR_M;
  seg.y = min(seg.y, seg.x + 60000.0f);
  if (seg.y <= seg.x) {
    write_cloud(pixel, vec3(0.0f), 1.0f, 0.0f, 1.0f, far_m);
    return;
  }
  float kappa = max(frame.cloud_shape.z * frame.cloud_light.x, 1e-9f);  // view rays
  float kappa_light = frame.cloud_shape.z * frame.cloud_light.y;  // light rays
  float phase = dual_lobe_hg(frame.cloud_phase.x, frame.cloud_phase.y, frame.cloud_phase.z,
                             dot(dir, light));
  float lit = dot(normalize(eye + dir * seg.x), light) > -0.2f ? 1.0f : 0.0f;
  float length_m = seg.y - seg.x;
  float integral = 0.0f, depth = 0.0f, weighted_t = 0.0f;
  if (reference) {
    const int n = 1024;
    float dt = length_m / float(n);
    float a = 1.0f;
    for (int i = 0; i < n; ++i) {
      float t = seg.x + (float(i) + 0.5f) * dt;
      vec3 p = eye + dir * t;
      float rho = cloud_density(p, true);
      if (rho <= 0.0f) continue;
      float step_a = exp(-kappa * rho * dt);
      float i_light = exp(-kappa_light * march_light(p, light, 0.0f, light_ray_length(p, light), 32));
      // The exact integral over the step of A rho at constant rho: A (1 - e^(-kappa rho dt)) / kappa.
      integral += a * (1.0f - step_a) / kappa * i_light;
      weighted_t += t * a * (1.0f - step_a);
      a *= step_a;
    }
    depth = -log(max(a, 1e-30f)) / kappa;
  } else {
    int levels = int(frame.classic_kajiya.x);
    int n = 1 << levels;
    // One pass over the finest level's 2^levels + 1 samples: sample i belongs to level k when
    // i is a multiple of 2^(levels - k); each level keeps its own trapezoid sums of rho (the
    // optical depth) and of A C rho, A from the cumulative trapezoid of rho on its samples.
    float sum_b[KAJIYA_LEVELS_MAX + 1], cumulative[KAJIYA_LEVELS_MAX + 1];
    float previous_rho[KAJIYA_LEVELS_MAX + 1], wt[KAJIYA_LEVELS_MAX + 1];
    for (int k = 0; k <= levels; ++k) {
      sum_b[k] = 0.0f;
      cumulative[k] = 0.0f;
      previous_rho[k] = 0.0f;
      wt[k] = 0.0f;
    }
    for (int i = 0; i <= n; ++i) {
      float t = seg.x + length_m * float(i) / float(n);
      vec3 p = eye + dir * t;
      float rho = cloud_density(p, true);
      float c = 0.0f;
      if (rho > 0.0f) {
        // The array's trilinear lookup smooths the depth over a voxel, where the light changes
        // fastest: as nephele's march does, the first voxel towards the light is marched.
        float near_m = light_volume_voxel_at(p);
        float d = light_volume_covers(p + light * near_m)
                      ? march_light(p, light, 0.0f, near_m, 4) + light_volume_lookup(p + light * near_m)
                      : march_light(p, light, 0.0f, light_ray_length(p, light), 16);
        c = exp(-kappa_light * d);
      }
      for (int k = 0; k <= levels; ++k) {
        int stride = 1 << (levels - k);
        if (i % stride != 0) continue;
        float h = length_m / float(1 << k);
        if (i > 0) cumulative[k] += 0.5f * h * (previous_rho[k] + rho);
        previous_rho[k] = rho;
        float weight = (i == 0 || i == n) ? 0.5f * h : h;
        float a = exp(-kappa * cumulative[k]);
        sum_b[k] += weight * a * c * rho;
        wt[k] += weight * a * rho * t;
      }
    }
    weighted_t = wt[levels] * kappa;
    // Richardson: R(k, j) = R(k, j - 1) + (R(k, j - 1) - R(k - 1, j - 1)) / (4^j - 1).
    float r_b[KAJIYA_LEVELS_MAX + 1], r_d[KAJIYA_LEVELS_MAX + 1];
    for (int k = 0; k <= levels; ++k) {
      r_b[k] = sum_b[k];
      r_d[k] = cumulative[k];
    }
    float scale = 1.0f;
    for (int j = 1; j <= levels; ++j) {
      scale *= 4.0f;
      for (int k = levels; k >= j; --k) {
        r_b[k] = r_b[k] + (r_b[k] - r_b[k - 1]) / (scale - 1.0f);
        r_d[k] = r_d[k] + (r_d[k] - r_d[k - 1]) / (scale - 1.0f);
      }
    }
    integral = max(r_b[levels], 0.0f);
    depth = max(r_d[levels], 0.0f);
  }
  float transmittance = exp(-kappa * depth);
  float opacity = 1.0f - transmittance;
  float distance_m = opacity > 1e-6f ? clamp(weighted_t / opacity, seg.x, seg.y) : far_m;
  vec3 mid = eye + dir * distance_m;
  vec3 air = air_transmittance(length(eye) - frame.radii_m.x, length(mid) - frame.radii_m.x, distance_m);
  // Scattered light: albedo sigma_s per unit rho times the light and the phase.
  vec3 radiance = air * frame.sun_at_clouds.rgb * (lit * frame.cloud_shape.w * kappa * phase * integral);
  write_cloud(pixel, radiance, transmittance, (1.0f - air.g) * opacity, 1.0f, distance_m);
}

// Nishita and Nakamae 1996: the eye ray through their grid (on a flat earth, as Gardner's),
// L = integral of T sigma_s rho (E (T_sun p(theta) + J_2) + J_sky) dt with each step's
// extinction integrated exactly at its density: the first order from the sun's transmittance,
// the second from the gathered sums (nishita_second_order, the phase's mean cosine), the sky's
// isotropic. The ground's shadow: the sun's transmittance through the grid from the ground.
void nishita(ivec2 pixel, vec3 eye_planet, vec3 dir, vec3 light) {
  float radius_m = frame.radii_m.x;
  vec3 eye = vec3(eye_planet.xy, length(eye_planet) - radius_m);
  float t_ground = dir.z < 0.0f ? -eye.z / dir.z : FAR_M;
  float shadow = 1.0f;
  if (t_ground < FAR_M) shadow = exp(-nishita_optical_depth(eye + dir * t_ground, light, nishita_voxel_m()));
  vec2 box = nishita_box(eye, dir);
  box.x = max(box.x, 0.0f);
  box.y = min(box.y, t_ground);
  if (box.y <= box.x) {
    write_cloud(pixel, vec3(0.0f), 1.0f, 0.0f, shadow, t_ground);
    return;
  }
  float sigma_t = frame.classic_nishita_light.x, albedo = frame.classic_nishita_light.y;
  bool second = frame.classic_nishita_light.z > 1.5f;
  vec3 e_sun = frame.sun_at_clouds.rgb;
  vec3 e_key = frame.sun_illuminance.rgb;  // the sky light's unit
  float phase = dual_lobe_hg(frame.cloud_phase.x, frame.cloud_phase.y, frame.cloud_phase.z, dot(dir, light));
  float g_mean = mix(frame.cloud_phase.y, frame.cloud_phase.x, frame.cloud_phase.z);
  float step_m = 0.75f * nishita_voxel_m();
  int steps = min(int(ceil((box.y - box.x) / step_m)), 512);
  float dt = (box.y - box.x) / float(max(steps, 1));
  // Start each pixel's steps at its own offset (interleaved gradient noise): banding becomes
  // fine grain.
  float jitter = fract(52.9829189f * fract(0.06711056f * float(pixel.x) + 0.00583715f * float(pixel.y)));
  vec3 radiance = vec3(0.0f);
  float transmittance = 1.0f, weighted_t = 0.0f;
  for (int i = 0; i < steps && transmittance > 1e-3f; ++i) {
    float t = box.x + (float(i) + jitter) * dt;
    vec3 p = eye + dir * t;
    float rho = nishita_sample(0, p).r;
    if (rho <= 0.0f) continue;
    vec4 first = nishita_sample(1, p);
    float j = first.r * phase;
    if (second) {
      vec4 gathered = nishita_sample(2, p);
      j += nishita_second_order(gathered.x, gathered.yzw, g_mean, -dir);
    }
    float step_t = exp(-sigma_t * rho * dt);
    float absorbed = transmittance * (1.0f - step_t);
    radiance += absorbed * albedo * (e_sun * j + e_key * first.gba);
    weighted_t += absorbed * t;
    transmittance *= step_t;
  }
  float opacity = 1.0f - transmittance;
  float distance_m = opacity > 1e-6f ? weighted_t / opacity : t_ground;
  vec3 air = air_transmittance(eye.z, eye.z + dir.z * distance_m, distance_m);
  write_cloud(pixel, air * radiance, transmittance, (1.0f - air.g) * opacity, shadow, distance_m);
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  int width = frame.cloud_grid.x, height = frame.cloud_grid.y;
  if (pixel.x >= width || pixel.y >= height) return;
  vec3 eye = frame.camera_pos_m.xyz;
  vec3 dir = camera_ray(frame.camera_forward.xyz, frame.camera_right.xyz, frame.camera_up.xyz,
                        frame.camera_pos_m.w, frame.camera_forward.w, float(pixel.x),
                        float(pixel.y), float(width), float(height),
                        vec2(frame.camera_right.w, frame.camera_up.w));
  if (MODEL == CLASSIC_BLINN) blinn(pixel, eye, dir, frame.sun_dir.xyz);
  if (MODEL == CLASSIC_GARDNER) gardner(pixel, eye, dir, frame.sun_dir.xyz, false);
  if (MODEL == CLASSIC_GARDNER_QUADRICS) gardner(pixel, eye, dir, frame.sun_dir.xyz, true);
  if (MODEL == CLASSIC_NISHITA) nishita(pixel, eye, dir, frame.sun_dir.xyz);
  if (MODEL == CLASSIC_KAJIYA) kajiya(pixel, eye, dir, frame.sun_dir.xyz, frame.classic_kajiya.y > 0.5f);
}

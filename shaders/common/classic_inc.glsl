// The classical cloud models of seed 004 (issue 23): their pure functions, shared by
// classic_clouds.comp and the C++ tests (render/glsl.h).
//
// Angles follow Blinn (1982): the phase angle alpha is the angle at the particle between the
// directions towards the light and towards the eye, so alpha = 0 is light from behind the eye
// (back scattering, "full phase") and alpha = pi light straight through the cloud towards the
// eye (forward scattering). With nephele's mu = dot(view ray, towards light), cos alpha = -mu.
// Blinn's phase functions are normalised to a mean of 1 over the sphere: phi / (4 pi) is a
// phase function in nephele's sense (1/sr, integrating to 1).
#ifndef NEPHELE_CLASSIC_INC
#define NEPHELE_CLASSIC_INC

// The models of classic_clouds.comp (its MODEL specialization constant).
const int CLASSIC_BLINN = 1;
const int CLASSIC_GARDNER = 2;
const int CLASSIC_KAJIYA = 3;
const int CLASSIC_NISHITA = 4;
const int CLASSIC_GARDNER_QUADRICS = 5;
const int KAJIYA_LEVELS_MAX = 10;  // Romberg's finest trapezoid: 2^10 + 1 = 1025 samples

// --- Blinn 1982: phase functions -------------------------------------------------------------
const int BLINN_PHASE_CONSTANT = 0;     // 1
const int BLINN_PHASE_ANISOTROPIC = 1;  // 1 + x cos alpha
const int BLINN_PHASE_LAMBERT = 2;      // 8 / (3 pi) (sin alpha + (pi - alpha) cos alpha)
const int BLINN_PHASE_RAYLEIGH = 3;     // 3/4 (1 + cos^2 alpha)
const int BLINN_PHASE_HG = 4;           // (1 - g^2) / (1 + g^2 - 2 g cos alpha)^(3/2)

// phi(alpha) of `kind`; `x` is the anisotropic function's x or Henyey-Greenstein's g.
// `seed_lambert`: the seed's (8/3) pi for the Lambert sphere's factor instead of the original
// 8 / (3 pi), which has a mean of 1 (the seed's is pi^2 = 9.87 times larger).
float blinn_phase(int kind, float x, float cos_alpha, bool seed_lambert) {
  float c = clamp(cos_alpha, -1.0f, 1.0f);
  if (kind == BLINN_PHASE_ANISOTROPIC) return 1.0f + x * c;
  if (kind == BLINN_PHASE_LAMBERT) {
    float alpha = acos(c);
    float factor = seed_lambert ? (8.0f / 3.0f) * PI : 8.0f / (3.0f * PI);
    return factor * (sqrt(max(1.0f - c * c, 0.0f)) + (PI - alpha) * c);
  }
  if (kind == BLINN_PHASE_RAYLEIGH) return 0.75f * (1.0f + c * c);
  if (kind == BLINN_PHASE_HG) {
    float gg = x * x;
    return (1.0f - gg) / pow(max(1.0f + gg - 2.0f * x * c, 1e-6f), 1.5f);
  }
  return 1.0f;
}

// --- Blinn 1982: a layer of particles, low albedo ---------------------------------------------
// A layer of thickness T holding n spheres of radius r per unit volume has the optical depth
// tau = n pi r^2 T along its normal. Seen along a direction at cosine mu to the normal, lit by a
// parallel beam at cosine mu0 (both > 0, measured on the side each comes from), single
// scattering gives Blinn's brightness (radiance over the beam's irradiance / 4 pi):
//   lit and seen from the same side: B = omega phi mu0 / (mu + mu0) (1 - e^(-tau (1/mu + 1/mu0)))
//   lit from the far side:           B = omega phi mu0 / (mu - mu0) (e^(-tau/mu) - e^(-tau/mu0))
// (mu = mu0: omega phi (tau/mu) e^(-tau/mu), the seed's s), and the layer lets through
// Tr = e^(-tau/mu) of the light behind it.
float blinn_optical_depth(float n_per_m3, float radius_m, float thickness_m) {
  return n_per_m3 * PI * radius_m * radius_m * thickness_m;
}

// The scattering probability per unit omega phi of the two cases above.
float blinn_reflection(float tau, float mu, float mu0) {
  return mu0 / (mu + mu0) * (1.0f - exp(-tau * (1.0f / mu + 1.0f / mu0)));
}

float blinn_transmission(float tau, float mu, float mu0) {
  // With a = tau/mu, b = tau/mu0 and d = |a - b|: e^(-min(a, b)) a (1 - e^(-d)) / d, which
  // neither overflows nor loses its digits near mu = mu0 (there (1 - e^(-d)) / d comes from
  // its series).
  float a = tau / mu, b = tau / mu0;
  float d = abs(a - b);
  float ratio = d < 1e-3f ? 1.0f - d * (0.5f - d / 6.0f) : (1.0f - exp(-d)) / d;
  return exp(-min(a, b)) * a * ratio;
}

// Blinn's brightness of the layer and its transparency: x = B (per unit beam irradiance / 4 pi),
// y = Tr. `lit_from_front`: the light on the eye's side of the layer. `seed_form`: the seed's
// printing, B = (omega / mu) phi s with s = (tau/mu) e^(-tau/mu) whatever the light's angle,
// and Tr = e^(-tau/mu) + omega phi(pi), kept for comparison.
vec2 blinn_layer(float tau, float mu, float mu0, bool lit_from_front, float omega, float phi,
                 float phi_at_pi, bool seed_form) {
  float tr = exp(-tau / mu);
  if (seed_form) {
    float s = tau / mu * exp(-tau / mu);
    return vec2(omega / mu * phi * s, tr + omega * phi_at_pi);
  }
  float p = lit_from_front ? blinn_reflection(tau, mu, mu0) : blinn_transmission(tau, mu, mu0);
  return vec2(omega * phi * p, tr);
}

// --- Gardner 1985: the texture function -------------------------------------------------------
// T(x, y, z) = k [sum_i C_i sin(FX_i x + PX_i) + T0] [sum_i C_i sin(FY_i y + PY_i) + T0],
// FX_(i+1) = 2 FX_i, FY_(i+1) = 2 FY_i, C_(i+1) = 0.707 C_i, with the phase shifts
// PX_i = pi/2 sin(FY_(i-1) y) + pi sin(FX_i z / 2), PY_i = pi/2 sin(FX_(i-1) x) + pi sin(FY_i z / 2)
// (for i = 1, FX_0 = FX_1 / 2). That is Gardner's paper; the seed prints a sum instead of the
// product, the terms without their sines (C_i (FX_i x + PY_i): PX_i does not appear) and FX_i
// in PY_i's second term: `seed_form` keeps its printing, for comparison. The caller chooses k
// and T0 so that T stays in [0, 1].
const int GARDNER_TERMS_MAX = 8;

// The x factor's sum, sum_i C_i sin(FX_i x + PX_i) with C_1 = 1: along x a sum of sines at
// FX_1, 2 FX_1, 4 FX_1, ... (PX_i depends on y and z only). `seed_form`: C_i (FX_i x + PY_i).
float gardner_sum_x(vec3 p, vec2 f1, int terms, bool seed_form) {
  float sum = 0.0f, c = 1.0f;
  vec2 f = f1, f_prev = 0.5f * f1;
  for (int i = 0; i < GARDNER_TERMS_MAX; ++i) {
    if (i >= terms) break;
    float px = 0.5f * PI * sin(f_prev.y * p.y) + PI * sin(0.5f * f.x * p.z);
    float py = 0.5f * PI * sin(f_prev.x * p.x) + PI * sin(0.5f * f.x * p.z);
    sum += c * (seed_form ? f.x * p.x + py : sin(f.x * p.x + px));
    f_prev = f;
    f *= 2.0f;
    c *= 0.707f;
  }
  return sum;
}

// The y factor's sum, sum_i C_i sin(FY_i y + PY_i). `seed_form`: C_i (FY_i y + PY_i), with the
// seed's FX_i in PY_i's second term.
float gardner_sum_y(vec3 p, vec2 f1, int terms, bool seed_form) {
  float sum = 0.0f, c = 1.0f;
  vec2 f = f1, f_prev = 0.5f * f1;
  for (int i = 0; i < GARDNER_TERMS_MAX; ++i) {
    if (i >= terms) break;
    float py = 0.5f * PI * sin(f_prev.x * p.x) + PI * sin(0.5f * (seed_form ? f.x : f.y) * p.z);
    sum += c * (seed_form ? f.y * p.y + py : sin(f.y * p.y + py));
    f_prev = f;
    f *= 2.0f;
    c *= 0.707f;
  }
  return sum;
}

// T(x, y, z) = k [sum_x + T0] [sum_y + T0]; the seed's printing: k sum_x + T0 + sum_y + T0.
float gardner_texture(vec3 p, vec2 f1, float t0, float k, int terms, bool seed_form) {
  float sx = gardner_sum_x(p, f1, terms, seed_form), sy = gardner_sum_y(p, f1, terms, seed_form);
  return seed_form ? k * sx + t0 + sy + t0 : k * (sx + t0) * (sy + t0);
}

// Gardner's shading: I = (1 - f) {(1 - t) [(1 - s) I_d + s I_s] + t I_t} + f.
float gardner_intensity(float i_d, float i_s, float i_t, float f, float t, float s) {
  return (1.0f - f) * ((1.0f - t) * ((1.0f - s) * i_d + s * i_s) + t * i_t) + f;
}

// Gardner's translucency: TR = (I_t - T1 - (T2 - T1)(1 - g)) / D, g the normalised limb
// curve (1 at the ellipsoid's centre as seen, 0 at its silhouette), clamped to [0, 1] as an
// opacity: T1 the texture's threshold at the centre, T2 at the edge, D the texture's range
// over which the cloud goes from clear to opaque.
float gardner_translucency(float i_t, float t1, float t2, float d, float g) {
  return clamp((i_t - t1 - (t2 - t1) * (1.0f - g)) / d, 0.0f, 1.0f);
}

// --- Gardner 1985: the cumulus field and its ellipsoids -------------------------------------
// One ellipsoid per square cell of `spacing_m`, where the cell's hash is below `coverage`: a
// horizontal semi-axis of 0.3-0.45 spacing, a vertical one of 0.6-1 of half the layer's
// thickness, standing on the layer's bottom, its centre jittered as far as keeps it inside its
// cell (a ray visiting the cells in order meets the ellipsoids in order).
struct GardnerEllipsoid {
  vec3 centre;  // ENU (m)
  vec3 radii;   // semi-axes (m)
  bool present;
};

GardnerEllipsoid gardner_cell_ellipsoid(ivec2 cell, float spacing_m, float bottom_m, float top_m,
                                        float coverage, uint seed) {
  vec3 h = hash_cell(ivec3(cell, 7), seed);
  vec3 k = hash_cell(ivec3(cell, 11), seed);
  float a = spacing_m * (0.3f + 0.15f * k.x);
  float c = 0.5f * (top_m - bottom_m) * (0.6f + 0.4f * k.y);
  vec2 slack = vec2(0.5f * spacing_m - a);
  vec2 centre = (vec2(cell) + 0.5f) * spacing_m + (vec2(h.y, h.z) * 2.0f - 1.0f) * slack;
  GardnerEllipsoid e;
  e.centre = vec3(centre, bottom_m + c);
  e.radii = vec3(a, a, c);
  e.present = h.x < coverage;
  return e;
}

// The ray o + t d (d unit) against the ellipsoid (centre, radii): x the entering t (< 0: none
// ahead, or the ray misses), y Gardner's normalised limb curve there, sqrt(1 - q^2) with q the
// ray's closest approach to the centre in the ellipsoid's unit-sphere space (1 through the
// centre, 0 grazing the silhouette).
vec2 ray_ellipsoid(vec3 o, vec3 d, vec3 centre, vec3 radii) {
  vec3 o1 = (o - centre) / radii, d1 = d / radii;
  float a = dot(d1, d1), b = dot(o1, d1), c = dot(o1, o1) - 1.0f;
  float disc = b * b - a * c;
  if (disc <= 0.0f) return vec2(-1.0f, 0.0f);
  float t = (-b - sqrt(disc)) / a;
  float q2 = c + 1.0f - b * b / a;
  return vec2(t, sqrt(max(1.0f - q2, 0.0f)));
}

// --- Gardner's impressionistic scenes: convex objects of a quadric and planes -------------------
// A quadric in the seed's coefficients, Q(x, y, z) = Q1 x^2 + Q2 y^2 + Q3 z^2 + Q4 xy + Q5 yz +
// Q6 xz + Q7 x + Q8 y + Q9 z + Q10, q[0] = Q1 ... q[9] = Q10; its inside is Q <= 0.
struct Quadric {
  float q[10];
};

float quadric_value(Quadric s, vec3 p) {
  return s.q[0] * p.x * p.x + s.q[1] * p.y * p.y + s.q[2] * p.z * p.z + s.q[3] * p.x * p.y +
         s.q[4] * p.y * p.z + s.q[5] * p.x * p.z + s.q[6] * p.x + s.q[7] * p.y + s.q[8] * p.z + s.q[9];
}

vec3 quadric_gradient(Quadric s, vec3 p) {
  return vec3(2.0f * s.q[0] * p.x + s.q[3] * p.y + s.q[5] * p.z + s.q[6],
              2.0f * s.q[1] * p.y + s.q[3] * p.x + s.q[4] * p.z + s.q[7],
              2.0f * s.q[2] * p.z + s.q[4] * p.y + s.q[5] * p.x + s.q[8]);
}

// The ellipsoid (p - c)^T R diag(1/a^2, 1/b^2, 1/c^2) R^T (p - c) <= 1, R the turn by `yaw`
// (rad) about the vertical, in the seed's ten coefficients.
Quadric quadric_ellipsoid(vec3 centre, vec3 radii, float yaw) {
  vec3 inv = 1.0f / (radii * radii);
  float c = cos(yaw), s = sin(yaw);
  // A = R D R^T: the horizontal block turned, the vertical untouched.
  float a00 = c * c * inv.x + s * s * inv.y, a11 = s * s * inv.x + c * c * inv.y;
  float a01 = c * s * (inv.x - inv.y), a22 = inv.z;
  Quadric q;
  q.q[0] = a00;
  q.q[1] = a11;
  q.q[2] = a22;
  q.q[3] = 2.0f * a01;
  q.q[4] = 0.0f;
  q.q[5] = 0.0f;
  vec3 ac = vec3(a00 * centre.x + a01 * centre.y, a01 * centre.x + a11 * centre.y, a22 * centre.z);
  q.q[6] = -2.0f * ac.x;
  q.q[7] = -2.0f * ac.y;
  q.q[8] = -2.0f * ac.z;
  q.q[9] = dot(centre, ac) - 1.0f;
  return q;
}

// A dome: the elliptic paraboloid z <= apex.z - h ((x - apex.x)^2 / a^2 + (y - apex.y)^2 / b^2).
Quadric quadric_dome(vec3 apex, vec2 radii, float h) {
  vec2 k = h / (radii * radii);
  Quadric q;
  q.q[0] = k.x;
  q.q[1] = k.y;
  q.q[2] = 0.0f;
  q.q[3] = 0.0f;
  q.q[4] = 0.0f;
  q.q[5] = 0.0f;
  q.q[6] = -2.0f * k.x * apex.x;
  q.q[7] = -2.0f * k.y * apex.y;
  q.q[8] = 1.0f;
  q.q[9] = k.x * apex.x * apex.x + k.y * apex.y * apex.y - apex.z;
  return q;
}

// A convex object: a quadric whose inside is convex (its quadratic part positive
// semi-definite: ellipsoids, elliptic paraboloids and cylinders) cut by up to two planes,
// each keeping n . p + w <= 0 (plane = (n, w)).
const int QUADRIC_PLANES_MAX = 2;
struct ConvexObject {
  Quadric shape;
  vec4 planes[QUADRIC_PLANES_MAX];
  int plane_count;
};

// The ray o + t d (d unit) through the object: x the entering t, y the leaving t (x >= y: a
// miss), z the surface entered (-1 the quadric, k plane k), w the limb curve there
// (|cos| between the surface's normal and the ray: 1 face on, 0 at the silhouette). What a
// ray cast finds is what Gardner's key-point algorithm outlines: the nearest visible surface.
vec4 ray_convex_object(ConvexObject object, vec3 o, vec3 d) {
  Quadric s = object.shape;
  float a = s.q[0] * d.x * d.x + s.q[1] * d.y * d.y + s.q[2] * d.z * d.z + s.q[3] * d.x * d.y +
            s.q[4] * d.y * d.z + s.q[5] * d.x * d.z;
  float b = dot(d, quadric_gradient(s, o));  // Q(o + t d) = a t^2 + b t + c
  float c = quadric_value(s, o);
  float t0, t1;
  if (a > 1e-20f) {
    float disc = b * b - 4.0f * a * c;
    if (disc <= 0.0f) return vec4(1.0f, 0.0f, -1.0f, 0.0f);
    float root = sqrt(disc);
    // The numerically stable pair of roots.
    float qq = -0.5f * (b + (b >= 0.0f ? root : -root));
    float r0 = qq / a, r1 = abs(qq) > 0.0f ? c / qq : r0;
    t0 = min(r0, r1);
    t1 = max(r0, r1);
  } else if (abs(b) > 1e-20f) {  // linear along this ray (a paraboloid's axis)
    float t = -c / b;
    t0 = b < 0.0f ? t : -1e30f;
    t1 = b < 0.0f ? 1e30f : t;
  } else {
    if (c > 0.0f) return vec4(1.0f, 0.0f, -1.0f, 0.0f);
    t0 = -1e30f;
    t1 = 1e30f;
  }
  float face = -1.0f;
  for (int k = 0; k < QUADRIC_PLANES_MAX; ++k) {
    if (k >= object.plane_count) break;
    vec3 n = vec3(object.planes[k]);
    float dn = dot(n, d), on = dot(n, o) + object.planes[k].w;
    if (abs(dn) < 1e-20f) {
      if (on > 0.0f) return vec4(1.0f, 0.0f, -1.0f, 0.0f);
      continue;
    }
    float t = -on / dn;
    if (dn < 0.0f) {  // entering the half-space
      if (t > t0) {
        t0 = t;
        face = float(k);
      }
    } else {
      t1 = min(t1, t);
    }
  }
  vec3 n = face < 0.0f ? quadric_gradient(s, o + d * t0) : vec3(object.planes[int(face)]);
  float g = abs(dot(normalize(n), d));
  return vec4(t0, t1, face, g);
}

// Gardner's impressionistic cumulus in one cell of the cumulus grid (where
// gardner_cell_ellipsoid stands one): object k of GARDNER_CELL_OBJECTS, all cut flat by the
// layer's bottom: 0 a wide ellipsoid, 1 a smaller one beside it, 2 a dome (a paraboloid)
// rising from them, its top sheared off by a slanting plane. All within the cell's column.
const int GARDNER_CELL_OBJECTS = 3;

// The cloud's vertical axis (xy, m) and how far from it its objects reach (z, m).
vec3 gardner_cell_axis(ivec2 cell, float spacing_m, uint seed) {
  vec3 h = hash_cell(ivec3(cell, 7), seed);
  float a = spacing_m * (0.22f + 0.1f * hash_cell(ivec3(cell, 13), seed).x);
  float reach = 1.1f * a;
  return vec3((vec2(cell) + 0.5f) * spacing_m + (vec2(h.y, h.z) * 2.0f - 1.0f) * (0.5f * spacing_m - reach),
              reach);
}

ConvexObject gardner_cell_object(ivec2 cell, int k, float spacing_m, float bottom_m, float top_m,
                                 uint seed) {
  vec3 r = hash_cell(ivec3(cell, 13), seed);
  vec3 u = hash_cell(ivec3(cell, 17 + k), seed);
  float a = spacing_m * (0.22f + 0.1f * r.x), b = a * (0.6f + 0.4f * r.y);
  float c = 0.5f * (top_m - bottom_m) * (0.5f + 0.4f * r.z);
  vec2 axis = vec2(gardner_cell_axis(cell, spacing_m, seed));
  float yaw = 2.0f * PI * u.x;
  ConvexObject o;
  o.planes[0] = vec4(0.0f, 0.0f, -1.0f, bottom_m);  // z >= bottom
  o.plane_count = 1;
  if (k == 0) {
    o.shape = quadric_ellipsoid(vec3(axis, bottom_m + 0.35f * c), vec3(a, b, c), yaw);
  } else if (k == 1) {
    vec2 side = 0.5f * a * vec2(cos(yaw), sin(yaw));
    o.shape = quadric_ellipsoid(vec3(axis + side, bottom_m + 0.2f * c), 0.6f * vec3(a, b, c), yaw);
  } else {
    float apex_m = min(bottom_m + (0.9f + 0.4f * u.y) * c, top_m);
    vec3 apex = vec3(axis + 0.2f * a * vec2(u.z * 2.0f - 1.0f, u.y * 2.0f - 1.0f), apex_m);
    o.shape = quadric_dome(apex, 0.5f * vec2(a, b), apex_m - bottom_m);
    vec3 n = normalize(vec3(cos(yaw), sin(yaw), 2.5f));
    vec3 through = apex - vec3(0.0f, 0.0f, 0.2f * (apex_m - bottom_m));
    o.planes[1] = vec4(n, -dot(n, through));
    o.plane_count = 2;
  }
  return o;
}

// --- Nishita and Nakamae 1996: metaballs -------------------------------------------------------
// A metaball of radius R and central density q contributes q f(r / R) at distance r from its
// centre, with Wyvill's soft-object polynomial f(u) = 1 - 22/9 u^2 + 17/9 u^4 - 4/9 u^6 for
// u < 1 and 0 beyond: f(0) = 1, f(1) = 0, f'(0) = f'(1) = 0, so the field is smooth where balls
// end.
float metaball_falloff(float u) {
  if (u >= 1.0f) return 0.0f;
  float u2 = u * u;
  return 1.0f + u2 * (-22.0f / 9.0f + u2 * (17.0f / 9.0f - u2 * (4.0f / 9.0f)));
}

// d f / d (u^2): the gradient of q f(|p - c| / R) is q f'(u^2) 2 (p - c) / R^2.
float metaball_falloff_d_u2(float u) {
  if (u >= 1.0f) return 0.0f;
  float u2 = u * u;
  return -22.0f / 9.0f + u2 * (34.0f / 9.0f - u2 * (12.0f / 9.0f));
}

// One ball (centre_radius = (c, R)) at p: x = density, yzw = its gradient.
vec4 metaball(vec3 p, vec4 centre_radius, float q) {
  vec3 d = p - vec3(centre_radius);
  float r2 = centre_radius.w * centre_radius.w;
  float u = sqrt(dot(d, d) / r2);
  return vec4(q * metaball_falloff(u), q * metaball_falloff_d_u2(u) * 2.0f * d / r2);
}

// --- Nishita and Nakamae 1996: the light on their voxel grid -----------------------------------
const int NISHITA_SLABS = 3;           // density; sun transmittance and sky light; second order
const int NISHITA_GATHER_RADIUS = 3;   // the second order gathers from voxels this close (in voxels)
const int NISHITA_SKY_DIRECTIONS = 16; // directions the sky's light is gathered from

// Direction i of n spread evenly over the sphere (a Fibonacci lattice): each stands for a
// solid angle of 4 pi / n.
vec3 nishita_sphere_dir(int i, int n) {
  float z = 1.0f - (2.0f * float(i) + 1.0f) / float(n);
  float r = sqrt(max(1.0f - z * z, 0.0f));
  float phi = float(i) * 2.39996323f;  // the golden angle
  return vec3(r * cos(phi), r * sin(phi), z);
}

// The second order's light scattered into the direction w_out, per unit volume and unit
// sigma_s, from the irradiance reaching a voxel summed over the directions it travels:
// `total` = sum E_k and `flux` = sum E_k s_k (s_k unit, the direction light k travels). The
// Henyey-Greenstein phase with mean cosine g is p(s . w) = sum_l (2l + 1) g^l P_l(s . w) /
// (4 pi); kept to its first two terms (l = 0, 1), the sum over k is
// (total + 3 g flux . w_out) / (4 pi): exact for an isotropic phase, and anisotropic to first
// order (an incident field whose flux is its total times a unit vector gets 1 + 3 g cos).
float nishita_second_order(float total, vec3 flux, float g, vec3 w_out) {
  return max(total + 3.0f * g * dot(flux, w_out), 0.0f) / (4.0f * PI);
}

#endif

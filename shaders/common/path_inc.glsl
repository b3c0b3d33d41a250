// The reference path tracer's pure functions (issue 21): random numbers, Henyey-Greenstein
// sampling, and null-collision tracking through a heterogeneous medium (Woodcock's delta
// tracking to sample collisions, ratio tracking to estimate transmittance; Novák et al. 2014),
// shared by the GPU pass and the CPU tests (tests/unit/path_test.cpp), which check them
// against closed forms.
//
// The includer defines, before including this file, the medium:
//   float pt_sigma_t(vec3 p)            extinction (1/m) at p
//   vec2 pt_bounds(vec3 origin, vec3 d) where a ray enters and leaves the medium (t_in >= 0;
//                                        t_out <= t_in: it misses)
//   vec2 pt_majorant_segment(vec3 origin, vec3 d, float t)
//                                        a majorant grid along the ray: (x) a bound on
//                                        pt_sigma_t over [t, y) (0 where the medium is empty,
//                                        which the tracking crosses in one step), y > t
// No include guard: a CPU test includes it once per medium, each in its own namespace.
// Keeps to the GLSL subset that GLM accepts (see math_inc.glsl): no out parameters.

// The includer may define PT_NOTE_MAJORANT(sigma, majorant), called at every tentative
// collision, to count the points where sigma_t exceeds its majorant (which would bias the
// estimates); by default it does nothing.
#ifndef PT_NOTE_MAJORANT
#define PT_NOTE_MAJORANT(sigma, majorant)
#endif
// And PT_NOTE_CUT(), called where a tracking walk (path_spectral_inc.glsl) ends at
// PT_MAX_COLLISIONS, short of the end of its ray or a collision: its estimate is then biased.
#ifndef PT_NOTE_CUT
#define PT_NOTE_CUT()
#endif

// Pseudo-random numbers without state: a hash of (stream, index). PCG's output permutation as
// a hash (Jarzynski and Olano 2020, "Hash Functions for GPU Rendering").
uint pt_hash(uint v) {
  uint state = v * 747796405u + 2891336453u;
  uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
  return (word >> 22u) ^ word;
}

// A stream of random numbers for one purpose of one sample of one pixel.
uint pt_stream(uint a, uint b, uint c) { return pt_hash(a ^ pt_hash(b ^ pt_hash(c))); }

// The i-th number of a stream, uniform in [0, 1).
float pt_uniform(uint stream, uint i) {
  return float(pt_hash(stream ^ pt_hash(i + 0x9E3779B9u)) >> 8u) * (1.0f / 16777216.0f);
}

// The cosine of a Henyey-Greenstein angle of eccentricity g (the inverse of its cumulative
// distribution, Pharr et al., PBRT 3, 15.2.3).
float pt_sample_hg_cos(float g, float u) {
  if (abs(g) < 1e-3f) return 1.0f - 2.0f * u;
  float s = (1.0f - g * g) / (1.0f - g + 2.0f * g * u);
  return clamp((1.0f + g * g - s * s) / (2.0f * g), -1.0f, 1.0f);
}

// The direction at angle acos(cos_theta) to d, at azimuth 2 pi u around it.
vec3 pt_direction_at(vec3 d, float cos_theta, float u) {
  float sin_theta = sqrt(max(1.0f - cos_theta * cos_theta, 0.0f));
  float phi = 2.0f * PI * u;
  // An orthonormal frame around d (Duff et al. 2017).
  float s = d.z >= 0.0f ? 1.0f : -1.0f;
  float a = -1.0f / (s + d.z);
  float b = d.x * d.y * a;
  vec3 t1 = vec3(1.0f + s * d.x * d.x * a, s * b, -s * d.x);
  vec3 t2 = vec3(b, s + d.y * d.y * a, -d.y);
  return normalize(sin_theta * (cos(phi) * t1 + sin(phi) * t2) + cos_theta * d);
}

// A direction whose angle to d has a Henyey-Greenstein distribution of eccentricity g: the
// scattered direction of a path that travelled along d; its pdf is henyey_greenstein(g,
// dot(d, result)).
vec3 pt_sample_hg(vec3 d, float g, float u1, float u2) {
  return pt_direction_at(d, pt_sample_hg_cos(g, u1), u2);
}

// Candidates pt_sample_draine_cos draws before it gives up on rejection.
const int PT_DRAINE_TRIES = 12;

// A cosine with the density of Draine's phase function of (g, alpha) (droplets_inc.glsl:
// Henyey-Greenstein's of g times (1 + alpha mu^2), normalised), and its weight: rejection from
// Henyey-Greenstein's, a candidate kept with probability (1 + alpha mu^2) / (1 + alpha), so a
// kept one has exactly Draine's density and weight 1. Only if PT_DRAINE_TRIES candidates are
// refused (0.42^12 = 3e-5 of draws for cloud droplets, alpha near 25), a fresh
// Henyey-Greenstein cosine weighted by the ratio of the densities, (1 + alpha mu^2) /
// (1 + alpha (1 + 2 g^2) / 3): unbiased either way. Weighting every draw by that ratio instead
// (which ranges over 0.06-1.7) multiplies hundreds of such weights along a path through a thick
// cloud: their mean stays 1, but their product's logarithm falls by 0.13 a bounce, and a
// path's estimate is then carried by ever rarer paths (stop 58's overcast reference, 10 to
// 70 times too dark and growing with its samples). `stream` supplies the numbers 0 to
// 2 PT_DRAINE_TRIES.
vec2 pt_sample_draine_cos(float g, float alpha, uint stream) {
  for (int k = 0; k < PT_DRAINE_TRIES; ++k) {
    float mu = pt_sample_hg_cos(g, pt_uniform(stream, uint(2 * k)));
    if (pt_uniform(stream, uint(2 * k + 1)) * (1.0f + alpha) < 1.0f + alpha * mu * mu)
      return vec2(mu, 1.0f);
  }
  float mu = pt_sample_hg_cos(g, pt_uniform(stream, uint(2 * PT_DRAINE_TRIES)));
  return vec2(mu, (1.0f + alpha * mu * mu) / (1.0f + alpha * (1.0f + 2.0f * g * g) / 3.0f));
}

// Most tentative collisions a tracking walk takes: a guard against a walk that never ends (a
// majorant of 0 where the medium is not, a NaN), never reached by a real one. The seed's storm
// (sigma_t to 2/m, an anvil tens of kilometres across) passed 65536 on horizontal rays; 2^24
// keeps the count exact in the float that path_trace.comp stores it in.
const int PT_MAX_COLLISIONS = 16777216;

// One draw of a walk from p along d through the majorant grid, from t in `segment`: the next
// tentative collision at the segment's majorant rate, or, where the draw passes the segment's
// end, that end and the next segment (the exponential distribution forgets, so the draw starts
// afresh there, and an empty segment costs one step). Returns (x) the new t, (y) 1 for a
// tentative collision, 0 for a segment's end, (zw) the segment from there on.
vec4 pt_walk(vec3 p, vec3 d, float t, vec2 segment, float u) {
  float step = segment.x > 0.0f ? -log(1.0f - u) / segment.x : 1e30f;
  bool crossing = t + step >= segment.y;
  t = crossing ? segment.y : t + step;
  // The next segment as a loop of one trip or none. A CPU device (lavapipe) runs a branch's
  // both sides for every lane, and such a loop's body once even when no lane enters it.
  for (int k = 0; k < (crossing ? 1 : 0); ++k) segment = pt_majorant_segment(p, d, t);
  return vec4(t, crossing ? 0.0f : 1.0f, segment);
}

// Delta tracking from p along d over [0, t_max]: the distance to a real collision, sampled
// with probability density sigma_t(t) T(t), or a value above t_max when the path leaves the
// medium unscattered (probability T(t_max)). Tentative collisions are real with probability
// sigma_t / majorant, null otherwise.
float pt_delta_tracking(vec3 p, vec3 d, float t_max, uint stream) {
  vec4 walk = vec4(0.0f, 0.0f, pt_majorant_segment(p, d, 0.0f));
  for (int i = 0; i < PT_MAX_COLLISIONS; ++i) {
    float majorant = walk.z;
    walk = pt_walk(p, d, walk.x, vec2(walk.z, walk.w), pt_uniform(stream, uint(2 * i)));
    if (walk.x >= t_max) break;
    if (walk.y == 0.0f) continue;
    float sigma = pt_sigma_t(p + d * walk.x);
    PT_NOTE_MAJORANT(sigma, majorant);
    if (pt_uniform(stream, uint(2 * i + 1)) * majorant < sigma) return walk.x;
  }
  return t_max + 1.0f;
}

// Ratio tracking from p along d over [0, t_max]: an unbiased estimate of the transmittance
// exp(-integral of sigma_t), the product of (1 - sigma_t / majorant) over the tentative
// collisions (drawn as delta tracking draws them), with Russian roulette once it falls under
// 0.1 (each survivor weighs 2).
float pt_ratio_tracking(vec3 p, vec3 d, float t_max, uint stream) {
  float transmittance = 1.0f;
  vec4 walk = vec4(0.0f, 0.0f, pt_majorant_segment(p, d, 0.0f));
  for (int i = 0; i < PT_MAX_COLLISIONS; ++i) {
    float majorant = walk.z;
    walk = pt_walk(p, d, walk.x, vec2(walk.z, walk.w), pt_uniform(stream, uint(2 * i)));
    if (walk.x >= t_max) break;
    if (walk.y == 0.0f) continue;
    float sigma = pt_sigma_t(p + d * walk.x);
    PT_NOTE_MAJORANT(sigma, majorant);
    transmittance *= 1.0f - sigma / majorant;
    if (transmittance < 0.1f) {
      if (pt_uniform(stream, uint(2 * i + 1)) < 0.5f) return 0.0f;
      transmittance *= 2.0f;
    }
  }
  return transmittance;
}

// What the medium lets through towards the light from p (inside it or on its surface).
float pt_transmittance_to(vec3 p, vec3 d, uint stream) {
  vec2 bounds = pt_bounds(p, d);
  if (bounds.y <= bounds.x) return 1.0f;
  return pt_ratio_tracking(p + d * bounds.x, d, bounds.y - bounds.x, stream);
}

// Radiance along the ray (eye, dir) through the medium (single albedo, Henyey-Greenstein phase
// g) lit by a distant light of irradiance E from direction `light` (next-event estimation at
// every collision) and a uniform environment of radiance `environment` (met by paths that
// leave). max_bounces scatterings after the first (0: single scattering only). One path;
// `stream` seeds it. Every path that is not cut by max_bounces leaves the medium, so with
// albedo 1 and no light but the environment it returns the environment exactly (a furnace).
float pt_path_radiance(vec3 eye, vec3 dir, vec3 light, float irradiance, float environment,
                       float albedo, float g, int max_bounces, uint stream) {
  float radiance = 0.0f;
  float weight = 1.0f;
  vec3 x = eye;
  vec3 d = dir;
  for (int bounce = 0; bounce <= max_bounces; ++bounce) {
    uint s = pt_hash(stream ^ pt_hash(uint(bounce)));
    vec2 bounds = pt_bounds(x, d);
    float t = bounds.y > bounds.x
                  ? pt_delta_tracking(x + d * bounds.x, d, bounds.y - bounds.x, pt_hash(s ^ 1u))
                  : 1.0f;
    if (bounds.y <= bounds.x || t > bounds.y - bounds.x) {  // left the medium
      radiance += weight * environment;
      break;
    }
    x += d * (bounds.x + t);
    weight *= albedo;  // sigma_s / sigma_t at a collision sampled in proportion to sigma_t T
    radiance += weight * irradiance * henyey_greenstein(g, dot(d, light)) *
                pt_transmittance_to(x, light, pt_hash(s ^ 2u));
    d = pt_sample_hg(d, g, pt_uniform(s, 3u), pt_uniform(s, 4u));
  }
  return radiance;
}

// Three colour channels on one path (the planet's reference, issue 42): the air's extinction
// differs per channel, the clouds' does not, so a path that carried one channel (each sample a
// third of the samples, weighted by 3) wasted most of what it learnt in the clouds. Here a
// hero channel h decides the path's events, every channel's estimate is kept, and the
// estimates are combined over the three choices of hero with the balance heuristic (Wilkie et
// al. 2014, hero wavelengths; with null collisions as Kutz et al. 2017's spectral tracking):
// channel k's estimate is f_k / mean_j p_j, where p_j is the probability of the path's events
// had j been the hero. With a majorant that bounds every channel the free-flight densities
// cancel, and only each event's probability differs: a tentative collision is real with
// probability sigma_t,j / majorant, null otherwise. The tracking functions return the ratios
// p_k / p_h of these events, which the includer multiplies into the path's.
//
// The includer defines, besides path_inc.glsl's medium (pt_bounds, pt_majorant_segment, whose
// majorant must bound every channel), before including this file:
//   vec3 pt_sigma_t3(vec3 p)   the extinction (1/m) of the three channels at p
// No out parameters (the GLSL subset GLM accepts); a CPU test may include it.

float pt_max3(vec3 v) { return max(v.x, max(v.y, v.z)); }

// Delta tracking from p along d over [0, t_max] by the hero channel `hero`: (x) the distance to
// a real collision (t_max + 1 when the path leaves unscattered), (yzw) each channel's
// probability of the events on the way relative to the hero's: the product over null
// collisions of (1 - sigma_k / majorant) / (1 - sigma_h / majorant), and at the real one
// sigma_k / sigma_h.
vec4 pt_hero_delta_tracking(vec3 p, vec3 d, float t_max, uint stream, int hero) {
  vec3 ratio = vec3(1.0f);
  vec4 walk = vec4(0.0f, 0.0f, pt_majorant_segment(p, d, 0.0f));
  for (int i = 0; i < PT_MAX_COLLISIONS; ++i) {
    float majorant = walk.z;
    walk = pt_walk(p, d, walk.x, vec2(walk.z, walk.w), pt_uniform(stream, uint(2 * i)));
    if (walk.x >= t_max) break;
    if (walk.y == 0.0f) continue;
    vec3 sigma = pt_sigma_t3(p + d * walk.x);
    PT_NOTE_MAJORANT(pt_max3(sigma), majorant);
    vec3 real = sigma / majorant;
    if (pt_uniform(stream, uint(2 * i + 1)) < real[hero]) return vec4(walk.x, ratio * real / real[hero]);
    vec3 null_event = max(1.0f - real, vec3(0.0f));
    ratio *= null_event / null_event[hero];
  }
  return vec4(t_max + 1.0f, ratio);
}

// Ratio tracking of the three channels on shared tentative collisions: each channel's
// transmittance estimate is the product of its (1 - sigma_k / majorant), unbiased for any
// majorant that bounds it; Russian roulette once every channel's falls under 0.1.
vec3 pt_ratio_tracking3(vec3 p, vec3 d, float t_max, uint stream) {
  vec3 transmittance = vec3(1.0f);
  vec4 walk = vec4(0.0f, 0.0f, pt_majorant_segment(p, d, 0.0f));
  for (int i = 0; i < PT_MAX_COLLISIONS; ++i) {
    float majorant = walk.z;
    walk = pt_walk(p, d, walk.x, vec2(walk.z, walk.w), pt_uniform(stream, uint(2 * i)));
    if (walk.x >= t_max) break;
    if (walk.y == 0.0f) continue;
    vec3 sigma = pt_sigma_t3(p + d * walk.x);
    PT_NOTE_MAJORANT(pt_max3(sigma), majorant);
    transmittance *= max(1.0f - sigma / majorant, vec3(0.0f));
    if (pt_max3(transmittance) < 0.1f) {
      if (pt_uniform(stream, uint(2 * i + 1)) < 0.5f) return vec3(0.0f);
      transmittance *= 2.0f;
    }
  }
  return transmittance;
}

// What the medium lets through towards the light from p, per channel.
vec3 pt_transmittance3_to(vec3 p, vec3 d, uint stream) {
  vec2 bounds = pt_bounds(p, d);
  if (bounds.y <= bounds.x) return vec3(1.0f);
  return pt_ratio_tracking3(p + d * bounds.x, d, bounds.y - bounds.x, stream);
}

// The balance heuristic's weight of each channel's estimate, from the ratios p_k / p_h of the
// path's events: p_k / mean_j p_j.
vec3 pt_hero_weights(vec3 ratio) { return ratio * (3.0f / (ratio.x + ratio.y + ratio.z)); }
